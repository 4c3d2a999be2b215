"""Pictures of bodies and query answers with matplotlib.

Every function draws on a matplotlib Axes and returns it. Ellipses are drawn as they are;
ellipsoids as their outline (shadow) on a coordinate plane, `plane` = "xy", "xz" or "yz".
The answers drawn come from the queries (points, normals); only the drawing is done here::

    import ellipsect, ellipsect.plot as ep
    ax = ep.bodies(None, [a, b])
    ep.contact(ax, ellipsect.first_contact(a, va, b, vb, 10.0))
    ep.witnesses(ax, ellipsect.signed_distance(a, b))
    ax.figure.savefig("scene.png")

and of bodies made from points::

    e = ellipsect.enclosing_ellipsoid(cloud)
    ax = ep.points(None, cloud, support=e.support_points)
    ep.hull(ax, ellipsect.hull_half_spaces(cloud))
    ep.bodies(ax, [e.body, ellipsect.fit_ellipsoid(cloud).body])
"""

from __future__ import annotations

from typing import Any, Iterable, Iterator, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from matplotlib import patches
from matplotlib import pyplot as plt

import ellipsect

_PLANES = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2)}

# A matplotlib Axes (matplotlib ships no type information); bodies: a body, a batch or a
# sequence of bodies.
Axes = Any
Body = Union[ellipsect.Ellipse, ellipsect.Ellipsoid]
Bodies = Union[Body, ellipsect.Ellipses, ellipsect.Ellipsoids, Iterable[Body]]


def _axes(ax: Optional[Axes]) -> Axes:
    if ax is None:
        _, ax = plt.subplots()
        ax.set_aspect("equal")
    return ax


def _outline(center: np.ndarray, axes: np.ndarray, radii: np.ndarray, plane: str) -> Tuple[Any, float, float, float]:
    """Center, width, height and angle (degrees) of the body's outline on `plane`: the
    ellipse {x : x^T S^-1 x <= 1} with S the plane's block of axes diag(radii^2) axes^T."""
    i, j = _PLANES[plane]
    s = (axes * radii**2) @ axes.T
    block = s[np.ix_([i, j], [i, j])]
    values, vectors = np.linalg.eigh(block)
    angle = np.degrees(np.arctan2(vectors[1, 1], vectors[0, 1]))
    return center[[i, j]], 2 * np.sqrt(values[1]), 2 * np.sqrt(values[0]), angle


def _rows(bodies: Bodies) -> Iterator[Tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """(center, axes, radii) of each body of an Ellipse / Ellipsoid, a batch or a sequence."""
    if isinstance(bodies, (ellipsect.Ellipses, ellipsect.Ellipsoids)):
        return zip(bodies.centers, bodies.rotations, bodies.radii)
    if isinstance(bodies, (ellipsect.Ellipse, ellipsect.Ellipsoid)):
        bodies = [bodies]
    return ((b.center, b.axes, b.radii) for b in bodies)


def bodies(ax: Optional[Axes], bodies: Bodies, *, plane: str = "xy", labels: Optional[Sequence[Any]] = None,
           **style: Any) -> Axes:
    """Draws the outline of each body; `style`: matplotlib patch options (defaults: no fill).
    Rescales the view to the bodies."""
    ax = _axes(ax)
    style = {"fill": False, "linewidth": 1.2, **style}
    for k, (center, axes, radii) in enumerate(_rows(bodies)):
        c, w, h, angle = _outline(np.asarray(center), np.asarray(axes), np.asarray(radii), plane)
        ax.add_patch(patches.Ellipse(c, w, h, angle=angle, **style))
        if labels is not None:
            ax.annotate(str(labels[k]), c, ha="center", va="center", fontsize=8)
    ax.autoscale_view()
    return ax


def _points(x: npt.ArrayLike, plane: str) -> np.ndarray:
    x = np.atleast_2d(np.asarray(x, dtype=float))
    return x[:, list(_PLANES[plane])] if x.shape[1] == 3 else x


def contact(ax: Optional[Axes], result: Any, *, plane: str = "xy", normal_length: float = 1.0,
            color: str = "crimson") -> Axes:
    """Contact points and normals (arrows from a towards b) of a first_contact answer (a
    Contact or ContactArrays); rows without a contact (NaN point) are skipped."""
    ax = _axes(ax)
    p, n = _points(result.point, plane), _points(result.normal, plane)
    keep = np.all(np.isfinite(p), axis=1)
    ax.plot(p[keep, 0], p[keep, 1], "o", color=color, markersize=4)
    ax.quiver(p[keep, 0], p[keep, 1], n[keep, 0] * normal_length, n[keep, 1] * normal_length, color=color,
              angles="xy", scale_units="xy", scale=1, width=0.004)
    return ax


def witnesses(ax: Optional[Axes], result: Any, *, plane: str = "xy", color: str = "seagreen") -> Axes:
    """Witness points of a distance / signed_distance answer (Distance or DistanceArrays),
    joined by a segment; rows without points (NaN) are skipped."""
    ax = _axes(ax)
    pa, pb = _points(result.point_a, plane), _points(result.point_b, plane)
    keep = np.all(np.isfinite(pa), axis=1) & np.all(np.isfinite(pb), axis=1)
    for u, v in zip(pa[keep], pb[keep]):
        ax.plot([u[0], v[0]], [u[1], v[1]], "-", color=color, linewidth=1)
    ax.plot(pa[keep, 0], pa[keep, 1], "s", pb[keep, 0], pb[keep, 1], "^", color=color, markersize=4)
    return ax


def pairs(ax: Optional[Axes], bodies: Bodies, index_pairs: npt.ArrayLike, *, plane: str = "xy",
          color: str = "orange") -> Axes:
    """Segments between the centers of the bodies of each pair (e.g. overlapping_pairs);
    `bodies`: a batch or a sequence of bodies."""
    ax = _axes(ax)
    centers = _points([center for center, _, _ in _rows(bodies)], plane)
    for i, j in np.asarray(index_pairs):
        ax.plot(centers[[i, j], 0], centers[[i, j], 1], "-", color=color, linewidth=0.8)
    return ax


def points(ax: Optional[Axes], points: npt.ArrayLike, *, plane: str = "xy", support: Optional[npt.ArrayLike] = None,
           color: str = "black", **style: Any) -> Axes:
    """The points ((n, 2) or (n, 3), on `plane`) as dots; `support`: points to ring, such as an
    enclosing_ellipsoid answer's support_points (those that carry its certificate)."""
    ax = _axes(ax)
    p = _points(points, plane)
    ax.plot(p[:, 0], p[:, 1], ".", color=color, **{"markersize": 4, **style})
    if support is not None and np.size(support):
        s = _points(support, plane)
        ax.plot(s[:, 0], s[:, 1], "o", markerfacecolor="none", markeredgecolor="royalblue", markersize=9)
    ax.autoscale_view()
    return ax


def hull(ax: Optional[Axes], half_planes: Sequence[ellipsect.HalfPlane], *, color: str = "grey", **style: Any) -> Axes:
    """The convex polygon of 2D half-planes in order around it, such as hull_half_spaces'
    answer: each corner where consecutive edges' lines meet. `style`: patch options."""
    ax = _axes(ax)
    if not half_planes or not all(isinstance(h, ellipsect.HalfPlane) for h in half_planes):
        raise ValueError("half_planes: expected a non-empty list of HalfPlane in order (hull_half_spaces of 2D points)")
    n = np.array([np.asarray(h.normal) for h in half_planes])
    b = np.array([float(np.dot(h.normal, h.point)) for h in half_planes])
    nxt = np.roll(np.arange(len(n)), -1)
    corners = np.array([np.linalg.solve(np.array([n[k], n[j]]), [b[k], b[j]]) for k, j in enumerate(nxt)])
    ax.add_patch(patches.Polygon(corners, closed=True, **{"fill": False, "edgecolor": color, "linewidth": 1, **style}))
    ax.autoscale_view()
    return ax
