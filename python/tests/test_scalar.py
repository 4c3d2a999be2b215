"""The scalar API: bodies, result objects, enums, pickling."""

import enum
import pickle

import numpy as np
import pytest

import ellipsect


def test_bodies_and_their_fields():
    e = ellipsect.Ellipse([1, 2], [3, 1], angle=0.5)
    assert np.allclose(e.center, [1, 2]) and np.allclose(e.radii, [3, 1])
    assert np.allclose(e.axes[:, 0], [np.cos(0.5), np.sin(0.5)])
    assert np.allclose(e.quadric() @ (e.axes[:, 0] * 3), e.axes[:, 0] / 3)
    assert np.allclose(e.translated([1, 1]).center, [2, 3])
    same = ellipsect.Ellipse.from_quadric(e.center, e.quadric())
    assert ellipsect.classify(same, e) == ellipsect.Relation.equal
    r = ellipsect.Ellipse([0, 0], [2, 1], rotation=[[0, -1], [1, 0]])
    assert np.allclose(r.axes, [[0, -1], [1, 0]])
    # The angle read back: the constructor's, in (-pi, pi].
    assert abs(e.angle - 0.5) <= 1e-15 and abs(r.angle - np.pi / 2) <= 1e-15
    assert abs(ellipsect.Ellipse([0, 0], [2, 1], angle=3.0 + 2 * np.pi).angle - 3.0) <= 1e-14
    area = ellipsect.overlap_area(e, e)
    assert repr(area) == f"OverlapArea(relation=equal, area={area.area!r})"
    s = ellipsect.Ellipsoid([0, 0, 0], [3, 2, 1], quaternion=[np.cos(0.3), 0, 0, np.sin(0.3)])
    assert np.allclose(s.axes[:, 0], [np.cos(0.6), np.sin(0.6), 0])
    assert "Ellipsoid(center=[0, 0, 0]" in repr(s)
    with pytest.raises(ValueError, match="not both"):
        ellipsect.Ellipse([0, 0], [1, 1], angle=0.0, rotation=np.eye(2))
    for body in (e, s, ellipsect.Options(tolerance=1e-10, max_contact_iterations=10)):
        again = pickle.loads(pickle.dumps(body))
        assert type(again) is type(body)
    assert pickle.loads(pickle.dumps(e)).radii.tolist() == e.radii.tolist()


def test_enums_are_int_enums():
    for kind in (ellipsect.Relation, ellipsect.ContactStatus, ellipsect.DistanceStatus, ellipsect.Verdict,
                 ellipsect.Side, ellipsect.QuarticStatus, ellipsect.CrossingKind, ellipsect.BoundaryStatus,
                 ellipsect.ContactFunctionStatus):
        assert issubclass(kind, enum.IntEnum) and kind.__module__ == "ellipsect"
        assert pickle.loads(pickle.dumps(list(kind))) == list(kind)
    assert [r.name for r in ellipsect.Relation] == ["separated", "touching", "overlapping", "a_contains_b",
                                                    "b_contains_a", "equal"]
    a, b = ellipsect.Ellipse([0, 0], [2, 1]), ellipsect.Ellipse([0.5, 0], [0.5, 0.5])
    assert ellipsect.classify(a, b) is ellipsect.Relation.a_contains_b
    assert ellipsect.classify(a, b, ellipsect.Options(tolerance=1e-9)) == 3


def test_result_objects():
    a = ellipsect.Ellipse([0, 0], [3, 1], angle=0.5)
    b = ellipsect.Ellipse([8, 1.5], [1.5, 0.5], angle=-0.3)
    c = ellipsect.first_contact(a, [0, 0], b, [-2, -0.25], 10.0)
    assert c.status == ellipsect.ContactStatus.hit and 0 < c.time < 10 and c.iterations > 0
    assert np.isclose(np.linalg.norm(c.normal), 1) and c.point.shape == (2,)
    d = ellipsect.distance(a, b)
    assert d.status == ellipsect.DistanceStatus.separated
    assert np.allclose(d.point_b - d.point_a, d.distance * d.normal)
    x = ellipsect.intersect_boundaries(a, ellipsect.Ellipse([1, 0], [3, 1]))
    assert x.status == ellipsect.BoundaryStatus.points and x.points.shape == (x.count, 2)
    assert x.kinds == [ellipsect.CrossingKind.transverse] * x.count
    area = ellipsect.overlap_area(a, a)
    assert area.relation == ellipsect.Relation.equal and np.isclose(area.area, 3 * np.pi)
    p = ellipsect.closest_point(a, [10, 0])
    assert p.signed_distance > 0 and p.point.shape == (2,)
    s3 = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    assert ellipsect.closest_point(s3, [0, 0, 3]).signed_distance == 2
    assert ellipsect.signed_distance(s3, ellipsect.Ellipsoid.ball([1, 0, 0], 1)).distance == pytest.approx(-1)


def test_niemitalo_objects():
    circle = ellipsect.Circle([4, 0], 1)
    assert circle.radius == 1 and np.allclose(circle.center, [4, 0])
    assert ellipsect.overlap(circle.ellipse(), ellipsect.Ellipse([0, 0], [3.5, 1]))
    e = ellipsect.Ellipse([0, 0], [3.5, 1])
    r = ellipsect.polygonal_overlap(e, circle)
    assert r.verdict == ellipsect.Verdict.collision and r.gap_lo <= -0.5 <= r.gap_hi
    r = ellipsect.polygonal_overlap(e, ellipsect.Ellipse([0, 3], [1, 0.5]), max_level=20)
    assert r.verdict == ellipsect.Verdict.no_collision and r.level <= 20
    assert ellipsect.circle_cover_overlap(e, ellipsect.Circle([0, 5], 1)).verdict == ellipsect.Verdict.no_collision
    assert ellipsect.polygonal_overlap(e, circle, max_level=99).verdict == ellipsect.Verdict.invalid_input
    assert 0 < ellipsect.niemitalo_error_bound(e, 10) < 1e-5
    for route in (ellipsect.closest_point_quartic, ellipsect.closest_point_closed_form):
        q = route(e, [5, 0])
        assert q.status == ellipsect.QuarticStatus.outside and q.distance == pytest.approx(1.5)
    assert ellipsect.closest_point_quartic(e, [0, 0]).status == ellipsect.QuarticStatus.inside
