"""Bodies against triangles, triangle meshes and boxes: closed forms, a 50-digit check, the
mesh against its triangles one by one, collide-and-slide over a tiled floor, bad input."""

import math
import pickle

import mpmath
import numpy as np
import pytest

import ellipsect

mpmath.mp.dps = 50


def test_ball_and_a_triangle():
    ball = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    face = ellipsect.Triangle3([-1, -1, 3], [2, -1, 3], [-1, 2, 3])
    assert face.vertices.shape == (3, 3) and face.vertices[1].tolist() == [2, -1, 3]
    assert ellipsect.classify(ball, face) == ellipsect.Relation.separated
    assert not ellipsect.overlap(ball, face)
    c = ellipsect.first_contact(ball, [0, 0, 0], face, [0, 0, -1], math.inf)
    assert c.status == ellipsect.ContactStatus.hit
    assert c.time == pytest.approx(2, abs=1e-15)
    assert np.allclose(c.point, [0, 0, 1], atol=1e-15) and np.allclose(c.normal, [0, 0, 1], atol=1e-15)
    assert ellipsect.classify(ball, face.translated([0, 0, -2])) == ellipsect.Relation.touching
    assert ellipsect.classify(ball, face.translated([0, 0, -2.5])) == ellipsect.Relation.overlapping
    small = ellipsect.Triangle2([0, 0], [0.1, 0], [0, 0.1])
    assert ellipsect.classify(ellipsect.Ellipse.ball([0, 0], 1), small) == ellipsect.Relation.a_contains_b
    assert pickle.loads(pickle.dumps(face)).vertices.tolist() == face.vertices.tolist()
    assert repr(small) == "Triangle2([0, 0], [0.1, 0], [0, 0.1])"


def test_segment_against_mpmath():
    """A degenerate triangle (a segment) and random ellipses: the relative gap
    min over the segment of sqrt((x - c)^T M (x - c)) - 1 in 50 digits decides the relation
    wherever it is farther than 1e-10 from the band."""
    rng = np.random.default_rng(7)
    decided = 0
    for _ in range(200):
        e = ellipsect.Ellipse([0, 0], rng.uniform(0.3, 3, 2), angle=rng.uniform(-3, 3))
        p, q = rng.uniform(-3, 3, 2), rng.uniform(-3, 3, 2)
        t = ellipsect.Triangle2(p, q, p)
        A = mpmath.matrix(e.axes.tolist())
        M = A * mpmath.diag([1 / mpmath.mpf(r) ** 2 for r in e.radii]) * A.T
        P, D = mpmath.matrix(p.tolist()), mpmath.matrix((q - p).tolist())
        s = -(D.T * M * P)[0] / (D.T * M * D)[0]
        s = min(max(s, 0), 1)
        X = P + s * D
        gap = mpmath.sqrt((X.T * M * X)[0]) - 1
        if abs(gap) < 1e-10:
            continue
        decided += 1
        want = ellipsect.Relation.separated if gap > 0 else None
        got = ellipsect.classify(e, t)
        if want is not None:
            assert got == want
        else:
            assert got in (ellipsect.Relation.overlapping, ellipsect.Relation.a_contains_b)
    assert decided > 150


def floor_mesh(n):
    """An n x n grid of unit squares at z = 0, two triangles each."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    vertices = np.stack([i.ravel(), j.ravel(), np.zeros(i.size)], axis=1).astype(np.float64)
    at = lambda a, b: a * (n + 1) + b  # noqa: E731
    tris = []
    for a in range(n):
        for b in range(n):
            tris += [[at(a, b), at(a + 1, b), at(a + 1, b + 1)], [at(a, b), at(a + 1, b + 1), at(a, b + 1)]]
    return ellipsect.TriangleMesh3(vertices, np.array(tris, dtype=np.int32))


def test_mesh_floor_fall_and_slide():
    floor = floor_mesh(10)
    assert len(floor) == 200 and floor.vertex_count == 121
    ball = ellipsect.Ellipsoid.ball([5.5, 5.25, 3], 1)
    hit = ellipsect.first_contact(ball, [0, 0, -2], floor, [0, 0, 0], math.inf)
    assert hit.contact.status == ellipsect.ContactStatus.hit
    assert hit.contact.time == pytest.approx(1, abs=1e-15)
    assert hit.triangle == 2 * (5 * 10 + 5)
    r = ellipsect.classify(ball.translated([0, 0, -2.5]), floor)
    assert r.relation == ellipsect.Relation.overlapping and r.triangle >= 0
    assert ellipsect.overlap(ball.translated([0, 0, -2.5]), floor)
    s = ellipsect.collide_and_slide(ball, [3, 2, -4], floor)
    assert s.status == ellipsect.SlideStatus.slid and s.contacts == 1
    assert np.allclose(s.body.center, [8.5, 7.25, 1], atol=1e-9)
    assert floor.triangle(0).vertices.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0]]


def test_mesh_equals_its_triangles_one_by_one():
    rng = np.random.default_rng(3)
    centers = rng.uniform(-5, 5, (100, 3))
    vertices = (centers[:, None, :] + rng.uniform(-1, 1, (100, 3, 3))).reshape(-1, 3)
    mesh = ellipsect.TriangleMesh3(vertices, np.arange(300).reshape(100, 3))
    for _ in range(50):
        body = ellipsect.Ellipsoid(rng.uniform(-6, 6, 3), rng.uniform(0.2, 1.5, 3))
        v = rng.normal(size=3)
        got = ellipsect.first_contact(body, v, mesh, [0, 0, 0], 10.0)
        if got.contact.status != ellipsect.ContactStatus.hit:
            continue
        each = [ellipsect.first_contact(body, v, mesh.triangle(k), [0, 0, 0], 10.0) for k in range(100)]
        hits = [(c.time, k) for k, c in enumerate(each) if c.status == ellipsect.ContactStatus.hit]
        assert min(hits) == (got.contact.time, got.triangle)


def test_mesh_bad_input_names_the_argument():
    v = np.zeros((3, 3))
    t = np.array([[0, 1, 2]])
    with pytest.raises(ValueError, match="vertices: expected shape"):
        ellipsect.TriangleMesh3(np.zeros((3, 2)), t)
    with pytest.raises(TypeError, match="vertices: expected real numbers, got dtype complex128"):
        ellipsect.TriangleMesh3(v.astype(complex), t)
    with pytest.raises(TypeError, match="triangles: expected integers, got dtype float64"):
        ellipsect.TriangleMesh3(v, t.astype(np.float64))
    as_lists = ellipsect.TriangleMesh3(v.astype(np.float32).tolist(), t.tolist())
    assert np.array_equal(as_lists.vertices, v) and np.array_equal(as_lists.triangles, t)
    with pytest.raises(ValueError, match=r"triangles: expected shape \(n, 3\)"):
        ellipsect.TriangleMesh3(v, np.array([0, 1, 2]))
    with pytest.raises(ellipsect.InputError, match=r"triangles\[0\]\[2\]"):
        ellipsect.TriangleMesh3(v, np.array([[0, 1, 3]]))
    bad = v.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ellipsect.InputError, match=r"vertices\[2\]\[1\]"):
        ellipsect.TriangleMesh3(bad, t)
    with pytest.raises(ellipsect.InputError, match=r"vertices\[1\]\[0\]"):
        ellipsect.Triangle2([0, 0], [math.inf, 0], [0, 1])
    with pytest.raises(ellipsect.InputError, match="triangle"):
        ellipsect.TriangleMesh3(v, t).triangle(1)


def test_box():
    ball = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    box = ellipsect.Box3([3, 0, 0], [1, 1, 1])
    assert box.corner(7).tolist() == [4, 1, 1]
    assert ellipsect.classify(ball, box) == ellipsect.Relation.separated
    c = ellipsect.first_contact(ball, [1, 0, 0], box, [0, 0, 0], math.inf)
    assert c.status == ellipsect.ContactStatus.hit and c.time == pytest.approx(1, abs=1e-15)
    assert ellipsect.classify(ball, ellipsect.Box3([0, 0, 0], [2, 2, 2])) == ellipsect.Relation.b_contains_a
    assert ellipsect.classify(ball, ellipsect.Box3([0, 0, 0], [0.5, 0.5, 0.5])) == ellipsect.Relation.a_contains_b
    rect = ellipsect.Box2([0, 2], [1, 1], axes=[[0, -1], [1, 0]])
    assert ellipsect.classify(ellipsect.Ellipse.ball([0, 0], 1), rect) == ellipsect.Relation.touching
    with pytest.raises(ellipsect.InputError, match=r"half_extents\[1\]"):
        ellipsect.Box3([0, 0, 0], [1, 0, 1])
    with pytest.raises(IndexError):
        box.corner(8)


def test_signed_distance_of_triangles_boxes_and_meshes():
    ball = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    floor = ellipsect.Triangle3([-10, -10, 3], [10, -10, 3], [0, 20, 3])
    d = ellipsect.signed_distance(ball, floor)
    assert d.status == ellipsect.DistanceStatus.separated
    assert d.distance == pytest.approx(2, abs=1e-15)
    np.testing.assert_allclose(d.normal, [0, 0, 1], atol=1e-15)
    np.testing.assert_allclose(d.point_b, [0, 0, 3], atol=1e-15)
    # A plane through the body: pushed out by 0.5 along +z; distance() reports 0 there.
    low = ellipsect.Triangle3([-10, -10, 0.5], [10, -10, 0.5], [0, 20, 0.5])
    assert ellipsect.signed_distance(ball, low).distance == pytest.approx(-0.5, abs=1e-15)
    assert ellipsect.distance(ball, low).distance == 0
    assert math.isnan(ellipsect.distance(ball, low).normal[0])
    box = ellipsect.Box3([0, 0, 0], [10, 10, 10])
    assert ellipsect.signed_distance(ball, box).distance == pytest.approx(-11, abs=1e-13)
    # A mesh of two triangles: the nearer one is reported.
    mesh = ellipsect.TriangleMesh3(
        np.array([[-10, -10, 3], [10, -10, 3], [0, 20, 3], [-10, -10, 5], [10, -10, 5], [0, 20, 5]], dtype=float),
        np.array([[3, 4, 5], [0, 1, 2]], dtype=np.int64))
    md = ellipsect.signed_distance(ball, mesh)
    assert md.triangle == 1
    assert md.distance.distance == pytest.approx(2, abs=1e-15)


def test_capsule():
    ball = ellipsect.Ellipsoid.ball([1, 0, 5], 1)
    lying = ellipsect.Capsule3([-3, 0, 0], [3, 0, 0], 0.5)
    assert lying.radius == 0.5 and lying.p1.tolist() == [3, 0, 0]
    assert ellipsect.classify(ball, lying) == ellipsect.Relation.separated
    d = ellipsect.signed_distance(ball, lying)
    assert d.distance == pytest.approx(3.5, abs=1e-14)
    np.testing.assert_allclose(d.normal, [0, 0, -1], atol=1e-14)
    c = ellipsect.first_contact(ball, [0, 0, -2], lying, [0, 0, 0], math.inf)
    assert c.status == ellipsect.ContactStatus.hit and c.time == pytest.approx(1.75, abs=1e-14)
    big = ellipsect.Ellipsoid.ball([0, 0, 0], 10)
    assert ellipsect.classify(big, lying) == ellipsect.Relation.a_contains_b
    with pytest.raises(ellipsect.InputError, match="radius"):
        ellipsect.Capsule2([0, 0], [1, 0], 0)
