"""enclosing_ellipsoid from Python: the library's certified minimum-volume ellipse or
ellipsoid, against closed forms and mpmath (50 digits), and its argument checks."""

import mpmath
import numpy as np
import pytest

import ellipsect

mpmath.mp.dps = 50


def form(body, point):
    """(p - c)^T A (p - c) in 50 digits from the stored center, axes and radii."""
    axes = [[mpmath.mpf(float(x)) for x in row] for row in np.asarray(body.axes)]
    center = [mpmath.mpf(float(x)) for x in np.asarray(body.center)]
    radii = [mpmath.mpf(float(x)) for x in np.asarray(body.radii)]
    n = len(center)
    q = mpmath.mpf(0)
    for k in range(n):
        y = sum(axes[j][k] * (mpmath.mpf(float(point[j])) - center[j]) for j in range(n)) / radii[k]
        q += y * y
    return q


def test_box_corners_give_the_circumscribed_ellipse():
    h = np.array([3.0, 0.5])
    angle = 0.3
    r = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    corners = np.array([[sx * h[0], sy * h[1]] for sx in (-1, 1) for sy in (-1, 1)]) @ r.T + [10.0, -2.0]
    e = ellipsect.enclosing_ellipsoid(corners)
    assert e.status == "optimal"
    assert 0 < e.volume_gap <= 1e-9
    assert isinstance(e.body, ellipsect.Ellipse)
    assert all(form(e.body, p) <= 1 for p in corners)
    # The optimum: radii sqrt(2) h, area pi * 2 h0 h1.
    area = mpmath.pi * np.prod([mpmath.mpf(float(x)) for x in np.asarray(e.body.radii)])
    optimum = mpmath.pi * 2 * mpmath.mpf(3.0) * mpmath.mpf(0.5)
    assert optimum * (1 - mpmath.mpf(1e-13)) <= area <= optimum * (1 + mpmath.mpf(e.volume_gap) + mpmath.mpf(1e-13))
    assert set(e.support.tolist()) == {0, 1, 2, 3}
    assert e.weights.sum() == pytest.approx(1.0)


def test_cloud_in_3d_every_point_inside():
    rng = np.random.default_rng(7)
    points = rng.normal(size=(2000, 3)) * [1.0, 3.0, 0.2] + [1e6, 0, 0]
    e = ellipsect.enclosing_ellipsoid(points, volume_gap=1e-6)
    assert e.status == "optimal"
    assert e.volume_gap <= 1e-6
    assert isinstance(e.body, ellipsect.Ellipsoid)
    worst = max(form(e.body, points[i]) for i in e.support)
    assert worst <= 1
    # Every point, in double with a margin far above its rounding, and the support exactly.
    c = np.asarray(e.body.center)
    y = (points - c) @ np.asarray(e.body.axes) / np.asarray(e.body.radii)
    assert np.max(np.sum(y * y, axis=1)) <= 1 + 1e-9
    assert ellipsect.classify(e.body, ellipsect.Ellipsoid.ball(points[e.support[0]], 1e-3)) != ellipsect.Relation.separated


def test_bad_input_is_named():
    with pytest.raises(ellipsect.InputError, match=r"points\[2\]"):
        ellipsect.enclosing_ellipsoid([[0, 0], [1, 0], [np.nan, 1], [1, 1]])
    with pytest.raises(ellipsect.InputError, match="points"):
        ellipsect.enclosing_ellipsoid([[0, 0], [1, 1], [2, 2]])
    with pytest.raises(ellipsect.InputError, match="line"):
        ellipsect.enclosing_ellipsoid([[0, 0], [1, 1], [2, 2], [3, 3]])
    with pytest.raises(ValueError, match=r"points: expected shape"):
        ellipsect.enclosing_ellipsoid(np.zeros((5, 4)))
    with pytest.raises(TypeError, match="points"):
        ellipsect.enclosing_ellipsoid([["a", "b"], ["c", "d"], ["e", "f"]])
    with pytest.raises(ellipsect.InputError, match="volume_gap"):
        ellipsect.enclosing_ellipsoid(np.eye(3), volume_gap=0)
    with pytest.raises(ellipsect.InputError, match="max_enclosing_iterations"):
        ellipsect.enclosing_ellipsoid(np.eye(3), max_enclosing_iterations=0)


def test_shapes_bodies_boxes_capsules_mesh():
    rng = np.random.default_rng(3)
    centers = rng.uniform(-3, 3, size=(12, 3))
    radii = rng.uniform(0.1, 1, size=(12, 3))
    quaternions = rng.normal(size=(12, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1)[:, None]
    bodies = ellipsect.Ellipsoids(centers=centers, radii=radii, quaternions=quaternions)
    e = ellipsect.enclosing_ellipsoid(bodies)
    assert e.status == "optimal" and e.volume_gap <= 1e-9
    # Every body inside, by the library's exact classification; the support points inside the bodies they name.
    for i in range(12):
        assert ellipsect.classify(e.body, bodies[i], ellipsect.Options(tolerance=0)) in (
            ellipsect.Relation.a_contains_b, ellipsect.Relation.equal)
    assert e.support_points.shape == (len(e.support), 3)
    for j, p in zip(e.support, e.support_points):
        assert form(bodies[int(j)], p) <= 1
    # The same set as a list of bodies answers the same, bit for bit.
    again = ellipsect.enclosing_ellipsoid([bodies[i] for i in range(12)])
    assert np.array_equal(np.asarray(again.body.radii), np.asarray(e.body.radii))
    box = ellipsect.Box3([0, 0, 0], [1, 2, 0.5])
    b = ellipsect.enclosing_ellipsoid([box])
    assert np.sort(np.asarray(b.body.radii)) == pytest.approx(np.sqrt(3) * np.array([0.5, 1, 2]), rel=1e-9)
    c = ellipsect.enclosing_ellipsoid([ellipsect.Capsule2([0, 0], [0, 0], 2.0)])
    assert np.asarray(c.body.radii) == pytest.approx([2, 2], rel=1e-9)
    vertices = np.array([[sx, sy, sz] for sx in (-1.0, 1) for sy in (-1.0, 1) for sz in (-1.0, 1)])
    mesh = ellipsect.TriangleMesh3(vertices, np.array([[0, 1, 3], [4, 5, 7]]))
    m = ellipsect.enclosing_ellipsoid(mesh)
    assert np.asarray(m.body.radii) == pytest.approx([np.sqrt(3)] * 3, rel=1e-9)
    with pytest.raises(ellipsect.InputError, match="bodies"):
        ellipsect.enclosing_ellipsoid(ellipsect.Ellipses(centers=np.zeros((0, 2)), radii=np.ones((0, 2)), angles=np.zeros(0)))
    with pytest.raises(ellipsect.InputError, match="capsules"):
        ellipsect.enclosing_ellipsoid([ellipsect.Capsule2([0, 0], [1e4, 0], 1e-9)])
