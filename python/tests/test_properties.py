"""Invariants on random bodies (hypothesis): swap symmetry, scale invariance by powers of
two, batch = scalar on single pairs, a hint that changes only the cost."""

import math

import numpy as np
import pytest
from conftest import ellipses, ellipsoids, same_bits
from hypothesis import assume, given
from hypothesis import strategies as st

import ellipsect

R = ellipsect.Relation
MIRROR = {R.a_contains_b: R.b_contains_a, R.b_contains_a: R.a_contains_b}
bodies = st.one_of(st.tuples(ellipses(), ellipses()), st.tuples(ellipsoids(), ellipsoids()))


def scaled(body, k):
    """The body scaled by 2^k about the origin, or None where that is not exact (a center
    coordinate that underflows, e.g. 5e-324 times 2^-40)."""
    center, radii = np.ldexp(body.center, k), np.ldexp(body.radii, k)
    if not (np.array_equal(np.ldexp(center, -k), body.center) and np.array_equal(np.ldexp(radii, -k), body.radii)):
        return None
    return type(body).from_axes(center, body.axes, radii)


@given(bodies)
def test_swap_symmetry(pair):
    a, b = pair
    r = ellipsect.classify(a, b)
    assert ellipsect.classify(b, a) == MIRROR.get(r, r)
    assert ellipsect.overlap(a, b) == ellipsect.overlap(b, a) == (r != R.separated)
    d, e = ellipsect.signed_distance(a, b), ellipsect.signed_distance(b, a)
    assert d.status == e.status and same_bits(d.distance, e.distance)
    if r != R.equal:  # distance.hpp: swapped points for two distinct bodies
        assert same_bits(d.point_a, e.point_b) and same_bits(d.normal, -e.normal)


@given(st.tuples(ellipses(), ellipses()))
def test_swap_symmetry_of_areas(pair):
    a, b = pair
    assert same_bits(ellipsect.overlap_area(a, b).area, ellipsect.overlap_area(b, a).area)
    assert same_bits(ellipsect.iou(a, b), ellipsect.iou(b, a))


@given(bodies, st.sampled_from([-40, -7, 1, 9, 300]))
def test_scale_by_powers_of_two(pair, k):
    a, b = pair
    sa, sb = scaled(a, k), scaled(b, k)
    assume(sa is not None and sb is not None)
    assert ellipsect.classify(sa, sb) == ellipsect.classify(a, b)
    d, e = ellipsect.signed_distance(a, b), ellipsect.signed_distance(sa, sb)
    assert d.status == e.status
    # distance.hpp: exact unless a nonzero axis entry or center coordinate (relative to the
    # size) is below about 2^-300: products of those underflow differently at another scale.
    size = max(a.radii.max(), b.radii.max())
    values = np.concatenate([np.abs(x.axes).ravel() for x in (a, b)] + [np.abs(x.center) / size for x in (a, b)])
    if np.min(values[values != 0], initial=1.0) >= 2.0**-300:
        assert same_bits(math.ldexp(d.distance, k), e.distance)
        assert same_bits(np.ldexp(d.point_a, k), e.point_a) and same_bits(d.normal, e.normal)
    if isinstance(a, ellipsect.Ellipse):
        assert same_bits(math.ldexp(ellipsect.overlap_area(a, b).area, 2 * k), ellipsect.overlap_area(sa, sb).area)
        assert same_bits(ellipsect.iou(a, b), ellipsect.iou(sa, sb))


def batch_of(body):
    kind = ellipsect.Ellipses if isinstance(body, ellipsect.Ellipse) else ellipsect.Ellipsoids
    return kind(centers=body.center[None, :], radii=body.radii[None, :], rotations=body.axes[None, :, :].copy())


@given(bodies)
def test_batch_of_one_equals_scalar(pair):
    a, b = pair
    ba, bb = batch_of(a), batch_of(b)
    assert ellipsect.classify(ba, bb)[0] == ellipsect.classify(a, b)
    assert ellipsect.overlap(ba, bb)[0] == ellipsect.overlap(a, b)
    d, e = ellipsect.signed_distance(ba, bb), ellipsect.signed_distance(a, b)
    assert same_bits(d.distance[0], e.distance) and same_bits(d.point_b[0], e.point_b)


def turned(n, angle):
    """The unit vector n turned by `angle` within a plane containing it."""
    other = np.roll(n, 1) if abs(n[0]) < 0.9 else np.roll(n, -1) + 1
    other = other - n * (other @ n)
    other /= np.linalg.norm(other)
    return n * math.cos(angle) + other * math.sin(angle)


@given(bodies, st.floats(0, 0.5), st.sampled_from(["distance", "signed_distance"]))
def test_a_hint_changes_the_cost_not_the_answer(pair, angle, name):
    # distance.hpp: the same claims from any hint (an earlier normal turned by up to 0.5 rad,
    # zero, not finite): the status, the distance within 1e-12 of the scale, and witness
    # points on the bodies' boundaries that the normal supports.
    a, b = pair
    query = getattr(ellipsect, name)
    cold = query(a, b)
    assume(np.all(np.isfinite(cold.normal)))
    scale = a.radii.max() + b.radii.max() + abs(cold.distance)
    for hint in (turned(cold.normal, angle), np.zeros(len(a.center)), np.full(len(a.center), np.nan)):
        warm = query(a, b, hint=hint)
        assert warm.status == cold.status
        assert abs(warm.distance - cold.distance) <= 2e-12 * scale
        for body, point in ((a, warm.point_a), (b, warm.point_b)):
            local = (body.axes.T @ (point - body.center)) / body.radii
            assert abs(np.linalg.norm(local) - 1) * body.radii.min() <= 1e-11 * scale + 1e-15 * np.abs(point).max()


def test_a_hint_of_the_wrong_length_is_refused():
    a = ellipsect.Ellipsoid([0, 0, 0], [1, 2, 3])
    b = ellipsect.Ellipsoid([5, 0, 0], [1, 1, 1])
    with pytest.raises(TypeError, match="hint"):
        ellipsect.distance(a, b, hint=[1.0, 0.0])
    with pytest.raises(TypeError, match="hint"):
        ellipsect.signed_distance(a, b, hint="up")
