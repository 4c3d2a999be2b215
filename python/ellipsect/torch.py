"""PyTorch autograd functions over the library's value-and-gradient batches (docs/python.md).

Bodies are given as tensors, one row per pair: centers (n, N), orientations (2D: angles (n,)
in radians, counterclockwise; 3D: quaternions (n, 4) as (w, x, y, z) of any nonzero norm, the
axes those of q / |q|) and radii (n, N). CPU tensors of float64 or float32 (computed in
float64, returned in the inputs' dtype). Values and derivatives both come from the library
(signed_distance_gradient, perram_wertheim_gradient, first_contact_gradient); the backward
pass only multiplies them by the incoming gradient, so these functions are differentiable
once (not twice).

Where a value has no derivative the library's is NaN (a first contact that is not a hit,
for instance); a pair whose incoming gradient is 0 contributes 0 there (so masking such pairs
with torch.where leaves the other pairs' gradients finite).
"""

from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np
import torch

from . import _ellipsect as _e

__all__ = ["signed_distance", "perram_wertheim", "iou", "overlap_area", "contact_time"]


def _array(t: torch.Tensor) -> np.ndarray:
    return t.detach().to(torch.float64).cpu().numpy()


def _bodies(centers: torch.Tensor, orientations: torch.Tensor, radii: torch.Tensor) -> Any:
    c, o, r = _array(centers), _array(orientations), _array(radii)
    if c.ndim != 2 or c.shape[1] not in (2, 3):
        raise ValueError(f"centers: expected shape (n, 2) or (n, 3), got {c.shape}")
    if c.shape[1] == 2:
        return _e.Ellipses(c, r, angles=o)
    if o.ndim != 2 or o.shape[1] != 4:
        raise ValueError(f"orientations: expected quaternions of shape (n, 4), got {o.shape}")
    norms = np.linalg.norm(o, axis=1, keepdims=True)
    return _e.Ellipsoids(c, r, quaternions=o / np.where(norms > 0, norms, 1.0))


def _orientation_gradient(orientations: torch.Tensor, gradient: np.ndarray) -> np.ndarray:
    """The library's gradient by the world rotation vector, as one by the given orientations."""
    if gradient.ndim == 1:  # 2D: the angle is the rotation
        return gradient
    return _e.quaternion_gradient(_array(orientations), gradient)


def _scaled(grad_out: torch.Tensor, g: np.ndarray, like: torch.Tensor) -> torch.Tensor:
    """grad_out times the library's derivatives, row by row; 0 where grad_out is 0."""
    d = torch.from_numpy(np.ascontiguousarray(g)).to(grad_out.dtype)
    w = grad_out.reshape((-1,) + (1,) * (d.dim() - 1))
    return torch.where(w == 0, torch.zeros_like(d), w * d).to(like.dtype)


def _check(*tensors: torch.Tensor) -> torch.dtype:
    dtype = tensors[0].dtype
    for t in tensors:
        if not isinstance(t, torch.Tensor):
            raise TypeError(f"expected torch tensors, got {type(t).__name__}")
        if t.dtype not in (torch.float64, torch.float32):
            raise TypeError(f"expected float64 or float32 tensors, got {t.dtype}")
        if t.device.type != "cpu":
            raise TypeError(f"expected CPU tensors, got one on {t.device}")
    return dtype


class _StaticQuery(torch.autograd.Function):
    """value(a, b) of a pair of bodies, by a batch function returning GradientArrays."""

    @staticmethod
    def forward(ctx: Any, query: Any, options: Any, ca: torch.Tensor, oa: torch.Tensor, ra: torch.Tensor,
                cb: torch.Tensor, ob: torch.Tensor, rb: torch.Tensor) -> torch.Tensor:
        dtype = _check(ca, oa, ra, cb, ob, rb)
        g = query(_bodies(ca, oa, ra), _bodies(cb, ob, rb), options)
        ctx.derivatives = (g.center_a, _orientation_gradient(oa, g.orientation_a), g.radii_a, g.center_b,
                           _orientation_gradient(ob, g.orientation_b), g.radii_b)
        ctx.likes = (ca, oa, ra, cb, ob, rb)
        return torch.from_numpy(g.value).to(dtype)

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx: Any, grad_out: torch.Tensor) -> Tuple[Optional[torch.Tensor], ...]:
        grads = tuple(_scaled(grad_out, d, like) for d, like in zip(ctx.derivatives, ctx.likes))
        return (None, None) + grads


def signed_distance(centers_a: torch.Tensor, orientations_a: torch.Tensor, radii_a: torch.Tensor,
                    centers_b: torch.Tensor, orientations_b: torch.Tensor, radii_b: torch.Tensor,
                    options: Optional[_e.Options] = None) -> torch.Tensor:
    """The signed distance of each pair (n,): positive apart, minus the penetration depth when
    overlapping (distance.hpp), differentiable by every tensor argument."""
    return _StaticQuery.apply(_e.signed_distance_gradient, options or _e.Options(), centers_a, orientations_a,
                              radii_a, centers_b, orientations_b, radii_b)


def perram_wertheim(centers_a: torch.Tensor, orientations_a: torch.Tensor, radii_a: torch.Tensor,
                    centers_b: torch.Tensor, orientations_b: torch.Tensor, radii_b: torch.Tensor,
                    options: Optional[_e.Options] = None) -> torch.Tensor:
    """The Perram-Wertheim contact function F of each pair (n,): < 1 overlapping, 1 touching,
    > 1 apart (contact_function.hpp), differentiable by every tensor argument."""
    return _StaticQuery.apply(_e.perram_wertheim_gradient, options or _e.Options(), centers_a, orientations_a,
                              radii_a, centers_b, orientations_b, radii_b)


def iou(centers_a: torch.Tensor, angles_a: torch.Tensor, radii_a: torch.Tensor, centers_b: torch.Tensor,
        angles_b: torch.Tensor, radii_b: torch.Tensor, options: Optional[_e.Options] = None) -> torch.Tensor:
    """The intersection over union of each pair of ellipses (n,), exact (intersect2.hpp),
    differentiable by every tensor argument (not where the ellipses are equal: NaN)."""
    return _StaticQuery.apply(_e.iou_gradient, options or _e.Options(), centers_a, angles_a, radii_a, centers_b,
                              angles_b, radii_b)


def overlap_area(centers_a: torch.Tensor, angles_a: torch.Tensor, radii_a: torch.Tensor, centers_b: torch.Tensor,
                 angles_b: torch.Tensor, radii_b: torch.Tensor, options: Optional[_e.Options] = None) -> torch.Tensor:
    """The area of the intersection of each pair of ellipses (n,) (intersect2.hpp),
    differentiable by every tensor argument (not where the ellipses are equal: NaN)."""
    return _StaticQuery.apply(_e.overlap_area_gradient, options or _e.Options(), centers_a, angles_a, radii_a,
                              centers_b, angles_b, radii_b)


class _ContactTime(torch.autograd.Function):
    @staticmethod
    def forward(ctx: Any, options: Any, t_max: Any, rigid: bool, ca: torch.Tensor, oa: torch.Tensor,
                ra: torch.Tensor, va: torch.Tensor, wa: torch.Tensor, cb: torch.Tensor, ob: torch.Tensor,
                rb: torch.Tensor, vb: torch.Tensor, wb: torch.Tensor) -> Tuple[torch.Tensor, torch.Tensor]:
        dtype = _check(ca, oa, ra, va, wa, cb, ob, rb, vb, wb)
        spin = {"angular_velocity_a": _array(wa), "angular_velocity_b": _array(wb)} if rigid else {}
        g = _e.first_contact_gradient(_bodies(ca, oa, ra), _array(va), _bodies(cb, ob, rb), _array(vb), t_max,
                                      options=options, **spin)
        ctx.derivatives = (g.center_a, _orientation_gradient(oa, g.orientation_a), g.radii_a, g.velocity_a,
                           g.angular_velocity_a, g.center_b, _orientation_gradient(ob, g.orientation_b), g.radii_b,
                           g.velocity_b, g.angular_velocity_b)
        ctx.likes = (ca, oa, ra, va, wa, cb, ob, rb, vb, wb)
        status = torch.from_numpy(g.status)
        ctx.mark_non_differentiable(status)
        return torch.from_numpy(g.time).to(dtype), status

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx: Any, grad_out: torch.Tensor, _status: Any) -> Tuple[Optional[torch.Tensor], ...]:
        grads = tuple(_scaled(grad_out, d, like) for d, like in zip(ctx.derivatives, ctx.likes))
        return (None, None, None) + grads


def contact_time(centers_a: torch.Tensor, orientations_a: torch.Tensor, radii_a: torch.Tensor,
                 velocities_a: torch.Tensor, centers_b: torch.Tensor, orientations_b: torch.Tensor,
                 radii_b: torch.Tensor, velocities_b: torch.Tensor, t_max: Any,
                 angular_velocities_a: Optional[torch.Tensor] = None,
                 angular_velocities_b: Optional[torch.Tensor] = None,
                 options: Optional[_e.Options] = None) -> Tuple[torch.Tensor, torch.Tensor]:
    """The first contact of each pair in [0, t_max] (contact.hpp): (time (n,), status (n,) int8
    of ContactStatus). The time is differentiable by every tensor argument where status is hit
    (0 for overlapping_at_start, NaN otherwise). Linear motion; rigid motion about the centers
    where an angular velocity is given (2D: rates (n,); 3D: (n, 3) vectors)."""
    rigid = angular_velocities_a is not None or angular_velocities_b is not None
    turns = centers_a.shape[:1] if centers_a.shape[-1] == 2 else (centers_a.shape[0], 3)
    still = torch.zeros(turns, dtype=centers_a.dtype)
    wa = angular_velocities_a if angular_velocities_a is not None else still
    wb = angular_velocities_b if angular_velocities_b is not None else still
    if isinstance(t_max, torch.Tensor):
        t_max = _array(t_max)
    return _ContactTime.apply(options or _e.Options(), t_max, rigid, centers_a, orientations_a, radii_a,
                              velocities_a, wa, centers_b, orientations_b, radii_b, velocities_b, wb)
