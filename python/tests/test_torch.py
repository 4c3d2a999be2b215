"""ellipsect.torch: torch.autograd.gradcheck in float64 for every wrapper (2D and 3D, linear
and rigid motion), float32 in and out, batches of pairs, and masked pairs without a derivative."""

import numpy as np
import pytest
import torch

import ellipsect
import ellipsect.torch as et


def bodies(rng, n, dim, spread):
    centers = torch.tensor(rng.uniform(-spread, spread, (n, dim)), dtype=torch.float64, requires_grad=True)
    radii = torch.tensor(rng.uniform(0.3, 1.5, (n, dim)), dtype=torch.float64, requires_grad=True)
    shape = (n,) if dim == 2 else (n, 4)
    orientations = torch.tensor(rng.normal(size=shape) * (1.0 if dim == 2 else 1.7), dtype=torch.float64,
                                requires_grad=True)
    return centers, orientations, radii


def separated_pairs(dim, n=6, seed=1):
    # a near the origin, b about 6 away: apart, and nowhere near a switch of the deepest
    # direction, so that the values are smooth where gradcheck's differences look.
    rng = np.random.default_rng(seed)
    a = bodies(rng, n, dim, 0.3)
    b = bodies(rng, n, dim, 0.3)
    with torch.no_grad():
        b[0].add_(torch.tensor([6.0] + [0.0] * (dim - 1), dtype=torch.float64))
    return a, b


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("function", [et.signed_distance, et.perram_wertheim])
def test_static_gradcheck(dim, function):
    a, b = separated_pairs(dim)
    assert torch.autograd.gradcheck(lambda *x: function(*x), (*a, *b), eps=1e-6, atol=1e-7, rtol=1e-6)


@pytest.mark.parametrize("function", [et.iou, et.overlap_area])
def test_area_gradcheck(function):
    # Overlapping pairs (b's center back near a's, both larger), and a pair with b inside a.
    a, b = separated_pairs(2, seed=7)
    with torch.no_grad():
        b[0].sub_(torch.tensor([5.5, 0.0], dtype=torch.float64))
        a[2].add_(0.5)
        a[2][0] = torch.tensor([4.0, 4.0], dtype=torch.float64)
        a[0][0] = b[0][0].detach()
    values = function(*a, *b)
    assert ((values > 0) & (values < (1 if function is et.iou else 100))).all()
    assert torch.autograd.gradcheck(lambda *x: function(*x), (*a, *b), eps=1e-6, atol=1e-7, rtol=1e-6)


@pytest.mark.parametrize("dim", [2, 3])
def test_overlapping_signed_distance_gradcheck(dim):
    a, b = separated_pairs(dim, seed=2)
    with torch.no_grad():  # b's center back near a's, both radii above 1.3: overlapping
        b[0].sub_(torch.tensor([6.0] + [0.0] * (dim - 1), dtype=torch.float64))
        a[2].add_(1.0)
        b[2].add_(1.0)
    assert (et.signed_distance(*a, *b) < 0).all()
    assert torch.autograd.gradcheck(lambda *x: et.signed_distance(*x), (*a, *b), eps=1e-6, atol=1e-7, rtol=1e-6)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("rigid", [False, True])
def test_contact_time_gradcheck(dim, rigid):
    a, b = separated_pairs(dim, seed=3)
    with torch.no_grad():  # b straight ahead of a along x: a sure hit
        b[0][:, 1:] = a[0][:, 1:]
    n = a[0].shape[0]
    rng = np.random.default_rng(4)
    va = torch.tensor(np.column_stack([rng.uniform(1.0, 2.0, n)] + [rng.uniform(-0.05, 0.05, n)] * (dim - 1)),
                      requires_grad=True)
    vb = torch.tensor(rng.uniform(-0.05, 0.05, (n, dim)), requires_grad=True)
    turns = (n,) if dim == 2 else (n, 3)
    wa = torch.tensor(rng.uniform(-0.3, 0.3, turns), requires_grad=True) if rigid else None
    wb = torch.tensor(rng.uniform(-0.3, 0.3, turns), requires_grad=True) if rigid else None

    def time(ca, oa, ra, va_, cb, ob, rb, vb_, *spins):
        w = dict(zip(["angular_velocities_a", "angular_velocities_b"], spins))
        t, status = et.contact_time(ca, oa, ra, va_, cb, ob, rb, vb_, 20.0, **w)
        assert (status == int(ellipsect.ContactStatus.hit)).all()
        return t

    inputs = (a[0], a[1], a[2], va, b[0], b[1], b[2], vb) + ((wa, wb) if rigid else ())
    assert torch.autograd.gradcheck(time, inputs, eps=1e-6, atol=1e-6, rtol=1e-5)


def test_float32_in_and_out():
    a, b = separated_pairs(3, n=4, seed=5)
    a32 = [x.detach().float().requires_grad_() for x in a]
    b32 = [x.detach().float().requires_grad_() for x in b]
    d = et.signed_distance(*a32, *b32)
    assert d.dtype == torch.float32
    d.sum().backward()
    assert all(x.grad is not None and x.grad.dtype == torch.float32 for x in a32 + b32)
    with pytest.raises(TypeError, match="float64 or float32"):
        et.signed_distance(*[x.detach().to(torch.int64) for x in a], *b)


def test_masked_pairs_without_a_derivative_leave_others_finite():
    # Pair 1 never meets (NaN derivative); masked out by torch.where, pair 0's gradient stays.
    a, b = separated_pairs(2, n=2, seed=6)
    va = torch.tensor([[1.5, 0.0], [-1.5, 0.0]], dtype=torch.float64, requires_grad=True)
    vb = torch.zeros(2, 2, dtype=torch.float64)
    t, status = et.contact_time(*a, va, *b, vb, 20.0)
    assert status.tolist() == [int(ellipsect.ContactStatus.hit), int(ellipsect.ContactStatus.no_contact_in_window)]
    loss = torch.where(status == int(ellipsect.ContactStatus.hit), t, torch.zeros_like(t)).sum()
    loss.backward()
    assert torch.isfinite(a[0].grad).all() and torch.isfinite(va.grad).all()
    assert (a[0].grad[1] == 0).all() and (a[0].grad[0] != 0).any()
