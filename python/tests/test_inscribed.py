"""inscribed_ellipsoid from Python: the library's certified maximum-volume ellipse or
ellipsoid inside half-spaces, against closed forms and mpmath (50 digits), its statuses and
its argument checks."""

import mpmath
import numpy as np
import pytest

import ellipsect

mpmath.mp.dps = 50


def support_excess(body, half_space):
    """n . (c - p) + |diag(r) A^T n| in 50 digits from the stored numbers (<= 0: inside)."""
    axes = [[mpmath.mpf(float(x)) for x in row] for row in np.asarray(body.axes)]
    center = [mpmath.mpf(float(x)) for x in np.asarray(body.center)]
    radii = [mpmath.mpf(float(x)) for x in np.asarray(body.radii)]
    n = [mpmath.mpf(float(x)) for x in np.asarray(half_space.normal)]
    p = [mpmath.mpf(float(x)) for x in np.asarray(half_space.point)]
    dim = len(center)
    s = sum(n[j] * (center[j] - p[j]) for j in range(dim))
    rho = mpmath.sqrt(sum((radii[k] * sum(axes[j][k] * n[j] for j in range(dim))) ** 2 for k in range(dim)))
    return s + rho


def box(h, center, rotation):
    out = []
    for k in range(len(h)):
        for sign in (1.0, -1.0):
            n = sign * rotation[:, k]
            out.append((np.asarray(center) + h[k] * n, n))
    return out


def test_box_gives_its_ellipse_and_the_arrays_agree():
    angle = 0.4
    r = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    h = [3.0, 0.5]
    faces = box(h, [10.0, -2.0], r)
    planes = [ellipsect.HalfPlane(p, n) for p, n in faces]
    e = ellipsect.inscribed_ellipsoid(planes)
    assert e.status == "optimal"
    assert 0 <= e.volume_gap <= 1e-9
    assert isinstance(e.body, ellipsect.Ellipse)
    assert all(support_excess(e.body, hp) <= 0 for hp in planes)
    assert sorted(np.asarray(e.body.radii)) == pytest.approx(sorted(h), rel=1e-9)
    assert np.asarray(e.body.center) == pytest.approx([10.0, -2.0], abs=1e-9)
    area = mpmath.pi * np.prod([mpmath.mpf(float(x)) for x in np.asarray(e.body.radii)])
    optimum = mpmath.pi * mpmath.mpf(3.0) * mpmath.mpf(0.5)
    assert optimum / (1 + mpmath.mpf(e.volume_gap)) * (1 - mpmath.mpf(1e-12)) <= area <= optimum * (1 + mpmath.mpf(1e-12))
    assert sorted(e.active.tolist()) == [0, 1, 2, 3]
    assert e.weights.sum() == pytest.approx(1.0, abs=1e-5)
    # The same polytope as normals and offsets n . x <= n . p.
    normals = np.array([n * 2.5 for _, n in faces])
    offsets = np.array([np.dot(n * 2.5, p) for p, n in faces])
    a = ellipsect.inscribed_ellipsoid(normals, offsets)
    assert a.status == "optimal"
    assert sorted(np.asarray(a.body.radii)) == pytest.approx(sorted(h), rel=1e-9)


def test_triangle_gives_the_steiner_inellipse_and_3d_simplex_its_ball():
    p = np.array([[0.0, 0.0], [4.0, 1.0], [1.0, 3.0]])
    planes = []
    for k in range(3):
        e = p[(k + 1) % 3] - p[k]
        planes.append(ellipsect.HalfPlane(p[k], [e[1], -e[0]]))  # counterclockwise: outward to the right
    t = ellipsect.inscribed_ellipsoid(planes)
    assert t.status == "optimal"
    area = abs(np.cross(p[1] - p[0], p[2] - p[0])) / 2
    assert np.pi * np.prod(np.asarray(t.body.radii)) == pytest.approx(np.pi / (3 * np.sqrt(3)) * area, rel=1e-9)
    assert np.asarray(t.body.center) == pytest.approx(p.mean(axis=0), abs=1e-9)
    v = np.array([[1.0, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]])
    tet = [ellipsect.HalfSpace(v[(k + 1) % 4], -v[k]) for k in range(4)]
    s = ellipsect.inscribed_ellipsoid(tet)
    assert s.status == "optimal"
    assert isinstance(s.body, ellipsect.Ellipsoid)
    assert np.asarray(s.body.radii) == pytest.approx([1 / np.sqrt(3)] * 3, rel=1e-9)
    assert all(support_excess(s.body, hs) <= 0 for hs in tet)
    # Every half-space contains the body by the library's exact classification too.
    for hs in tet:
        assert ellipsect.classify(s.body, hs, ellipsect.Options(tolerance=0)) == ellipsect.Relation.b_contains_a


def test_statuses_unbounded_empty_cap():
    slab = ellipsect.inscribed_ellipsoid(np.array([[0.0, 1], [0, -1], [0, 1]]), np.array([1.0, 1, 2]))
    assert slab.status == "unbounded"
    assert np.isinf(slab.volume_gap)
    assert len(slab.active) == 0
    empty = ellipsect.inscribed_ellipsoid(np.array([[1.0, 0], [-1, 0], [0, 1], [0, -1]]), np.array([-1.0, -1, 1, 1]))
    assert empty.status == "empty"
    planes = [ellipsect.HalfSpace(p, n) for p, n in box([1.0, 2, 3], [0, 0, 0], np.eye(3))]
    capped = ellipsect.inscribed_ellipsoid(planes, max_inscribed_iterations=2)
    assert capped.status == "did_not_converge"
    assert all(support_excess(capped.body, hs) <= 0 for hs in planes)


def test_bad_input_is_named():
    with pytest.raises(ellipsect.InputError, match="half_spaces"):
        ellipsect.inscribed_ellipsoid([ellipsect.HalfPlane([0, 0], [1, 0]), ellipsect.HalfPlane([0, 0], [-1, 0])])
    with pytest.raises(ellipsect.InputError, match=r"normals\[1\]"):
        ellipsect.inscribed_ellipsoid(np.array([[1.0, 0], [0, 0], [0, 1]]), np.zeros(3))
    with pytest.raises(ellipsect.InputError, match=r"offsets\[2\]"):
        ellipsect.inscribed_ellipsoid(np.array([[1.0, 0], [-1, 0], [0, 1]]), np.array([1.0, 1, np.nan]))
    with pytest.raises(ValueError, match="offsets"):
        ellipsect.inscribed_ellipsoid(np.array([[1.0, 0], [-1, 0], [0, 1]]), np.zeros(4))
    with pytest.raises(ValueError, match="normals: expected shape"):
        ellipsect.inscribed_ellipsoid(np.zeros((5, 4)), np.zeros(5))
    planes = [ellipsect.HalfPlane(p, n) for p, n in box([1.0, 1], [0, 0], np.eye(2))]
    with pytest.raises(ellipsect.InputError, match="volume_gap"):
        ellipsect.inscribed_ellipsoid(planes, volume_gap=0)
    with pytest.raises(ellipsect.InputError, match="max_inscribed_iterations"):
        ellipsect.inscribed_ellipsoid(planes, max_inscribed_iterations=0)


def test_hull_half_spaces_of_a_cube_and_its_inscribed_ball():
    rng = np.random.default_rng(5)
    corners = np.array([[x, y, z] for x in (0.0, 2.0) for y in (0.0, 2.0) for z in (0.0, 2.0)]) + [1e6, 0, -3]
    points = np.vstack([corners, corners.min(axis=0) + 2 * rng.random((50, 3))])
    faces = ellipsect.hull_half_spaces(points)
    assert len(faces) == 6 and all(isinstance(f, ellipsect.HalfSpace) for f in faces)
    for f in faces:
        n = [mpmath.mpf(float(x)) for x in np.asarray(f.normal)]
        p = [mpmath.mpf(float(x)) for x in np.asarray(f.point)]
        assert max(sum(n[j] * (mpmath.mpf(float(q[j])) - p[j]) for j in range(3)) for q in points) == 0
    e = ellipsect.inscribed_ellipsoid(faces)
    assert e.status == "optimal"
    assert np.asarray(e.body.radii) == pytest.approx([1.0, 1.0, 1.0], rel=1e-8)
    assert all(support_excess(e.body, f) <= 0 for f in faces)
    square = ellipsect.hull_half_spaces([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5], [0.5, 0.0]])
    assert len(square) == 4 and all(isinstance(f, ellipsect.HalfPlane) for f in square)


def test_hull_half_spaces_names_bad_points():
    with pytest.raises(ellipsect.InputError, match=r"points: are collinear"):
        ellipsect.hull_half_spaces([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    with pytest.raises(ellipsect.InputError, match=r"points: are coplanar"):
        ellipsect.hull_half_spaces([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    with pytest.raises(ellipsect.InputError, match=r"points\[2\]: must be finite"):
        ellipsect.hull_half_spaces([[0.0, 0.0], [1.0, 0.0], [np.nan, 1.0]])
    with pytest.raises(ValueError, match="points: expected shape"):
        ellipsect.hull_half_spaces(np.zeros((5, 4)))
