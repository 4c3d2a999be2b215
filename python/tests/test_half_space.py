"""Bodies against half-planes and half-spaces: closed forms, a 50-digit check, bad input."""

import math
import pickle

import mpmath
import numpy as np
import pytest

import ellipsect

mpmath.mp.dps = 50


def test_ball_above_a_floor():
    floor = ellipsect.HalfSpace([0, 0, -2], [0, 0, 5])
    assert floor.normal.tolist() == [0, 0, 1]
    ball = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    assert ellipsect.classify(ball, floor) == ellipsect.Relation.separated
    assert not ellipsect.overlap(ball, floor)
    d = ellipsect.signed_distance(ball, floor)
    assert d.status == ellipsect.DistanceStatus.separated and d.distance == 1.0
    assert d.point_a.tolist() == [0, 0, -1] and d.point_b.tolist() == [0, 0, -2]
    assert d.normal.tolist() == [0, 0, -1]
    c = ellipsect.first_contact(ball, [0, 0, -1], floor, [0, 0, 1], math.inf)
    assert c.status == ellipsect.ContactStatus.hit and c.time == 0.5
    assert c.point.tolist() == [0, 0, -1.5]
    deep = ellipsect.HalfSpace([0, 0, 5], [0, 0, 1])
    assert ellipsect.classify(ball, deep) == ellipsect.Relation.b_contains_a
    assert ellipsect.signed_distance(ball, deep).distance == -6.0
    assert ellipsect.distance(ball, deep).distance == 0.0
    assert pickle.loads(pickle.dumps(floor)).point.tolist() == [0, 0, -2]
    assert "HalfSpace(point=[0, 0, -2]" in repr(floor)
    assert ellipsect.HalfSpace([0, 0, 0], [1, 0, 0]).translated([1, 2, 3]).point.tolist() == [1, 2, 3]


def test_half_plane_against_mpmath():
    """The gap n . (c - p) - |diag(r) A^T n| of random ellipses, in 50 digits."""
    rng = np.random.default_rng(5)
    for _ in range(200):
        angle = rng.uniform(-3, 3)
        e = ellipsect.Ellipse(rng.uniform(-3, 3, 2), rng.uniform(0.1, 3, 2), angle=angle)
        h = ellipsect.HalfPlane(rng.uniform(-3, 3, 2), rng.normal(size=2))
        n = [mpmath.mpf(x) for x in h.normal]
        norm = mpmath.sqrt(n[0] ** 2 + n[1] ** 2)
        n = [x / norm for x in n]
        axes = e.axes
        rho = mpmath.sqrt(sum((mpmath.mpf(e.radii[k]) * sum(mpmath.mpf(axes[i, k]) * n[i] for i in range(2))) ** 2
                              for k in range(2)))
        gap = sum(n[i] * (mpmath.mpf(e.center[i]) - mpmath.mpf(h.point[i])) for i in range(2)) - rho
        d = ellipsect.signed_distance(e, h)
        assert abs(d.distance - float(gap)) <= 1e-14 * (max(e.radii) + abs(float(gap)))


def test_bad_input_names_the_field():
    with pytest.raises(ellipsect.InputError, match="normal") as info:
        ellipsect.HalfSpace([0, 0, 0], [0, 0, 0])
    assert info.value.field == "normal"
    with pytest.raises(ellipsect.InputError, match=r"point\[1\]"):
        ellipsect.HalfPlane([0, math.nan], [0, 1])
    with pytest.raises(TypeError):
        ellipsect.HalfPlane([0, 0, 0], [0, 1])
    ball = ellipsect.Ellipse.ball([0, 0], 1)
    bad = ellipsect.first_contact(ball, [math.nan, 0], ellipsect.HalfPlane([0, -2], [0, 1]), [0, 0], 1.0)
    assert bad.status == ellipsect.ContactStatus.invalid_input


def test_collide_and_slide_in_a_corner():
    walls = [ellipsect.HalfPlane([0, 0], [1, 0]), ellipsect.HalfPlane([0, 0], [0, 1])]
    e = ellipsect.Ellipse([5, 5], [2, 1])
    s = ellipsect.collide_and_slide(e, [-10, -6], walls)
    assert s.status == ellipsect.SlideStatus.slid and s.contacts == 2
    assert np.allclose(s.body.center, [2, 1], atol=1e-14)
    assert all(ellipsect.classify(s.body, w) == ellipsect.Relation.touching for w in walls)
    assert np.allclose(s.moved, [-3, -4], atol=1e-14)
    floor = [ellipsect.HalfSpace([0, 0, 0], [0, 0, 1])]
    ball = ellipsect.Ellipsoid.ball([0, 0, 2], 1)
    slid = ellipsect.collide_and_slide(ball, [4, 0, -3], floor)
    assert slid.last_contact == 0 and np.allclose(slid.body.center, [4, 0, 1], atol=1e-14)
    assert ellipsect.collide_and_slide(ball, [1, 1, 1], []).status == ellipsect.SlideStatus.moved
    assert ellipsect.collide_and_slide(ball, [math.nan, 0, 0], floor).status == ellipsect.SlideStatus.invalid_input
