"""ellipsect.plot draws bodies, contacts, normals and witness points (Agg backend)."""

import numpy as np
import pytest
from conftest import random_ellipses, random_ellipsoids
from matplotlib import pyplot as plt

import ellipsect
import ellipsect.plot as ep


def test_picture_of_a_2d_scene(tmp_path):
    a = ellipsect.Ellipse([0, 0], [3, 1], angle=0.5)
    b = ellipsect.Ellipse([8, 1.5], [1.5, 0.5], angle=-0.3)
    ax = ep.bodies(None, [a, b], labels=["a", "b"])
    ep.contact(ax, ellipsect.first_contact(a, [0, 0], b, [-2, -0.25], 10.0))
    ep.witnesses(ax, ellipsect.signed_distance(a, b))
    assert len(ax.patches) == 2 and np.isclose(ax.patches[0].angle % 180, np.degrees(0.5))
    assert np.isclose(ax.patches[0].width, 6) and np.isclose(ax.patches[0].height, 2)
    ax.figure.savefig(tmp_path / "scene.png")
    assert (tmp_path / "scene.png").stat().st_size > 1000
    plt.close(ax.figure)


def test_picture_of_batches(tmp_path):
    bodies, _ = random_ellipses(40, seed=3)
    ax = ep.bodies(None, bodies)
    ep.pairs(ax, bodies, ellipsect.overlapping_pairs(bodies))
    a, b = bodies.take(np.arange(20)), bodies.take(np.arange(20, 40))
    ep.witnesses(ax, ellipsect.signed_distance(a, b))
    ep.contact(ax, ellipsect.first_contact(a, np.zeros((20, 2)), b, np.ones((20, 2)), 5.0))
    solids, _ = random_ellipsoids(10, seed=4)
    ep.bodies(ax, solids, plane="xz", edgecolor="gray")
    assert len(ax.patches) == 50
    ax.figure.savefig(tmp_path / "batch.png")
    plt.close(ax.figure)


def test_ellipsoid_outline_of_an_axis_aligned_body():
    ax = ep.bodies(None, ellipsect.Ellipsoid([1, 2, 3], [3, 2, 1]), plane="yz")
    p = ax.patches[0]
    assert np.allclose(p.center, [2, 3]) and np.isclose(max(p.width, p.height), 4)
    plt.close(ax.figure)


def test_pairs_of_a_list_of_bodies():
    batch, scalar = random_ellipses(12, seed=5)
    index_pairs = ellipsect.overlapping_pairs(batch)
    from_list = ep.pairs(None, scalar, index_pairs)
    from_batch = ep.pairs(None, batch, index_pairs)
    assert len(from_list.lines) == len(from_batch.lines) == len(index_pairs) > 0
    for u, v in zip(from_list.lines, from_batch.lines):
        assert np.array_equal(u.get_xydata(), v.get_xydata())
    plt.close(from_list.figure)
    plt.close(from_batch.figure)


def test_points_hull_and_their_ellipses(tmp_path):
    square = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0], [1.0, 1.0], [3.0, 0.5]])
    e = ellipsect.enclosing_ellipsoid(square)
    ax = ep.points(None, square, support=e.support_points)
    ep.hull(ax, ellipsect.hull_half_spaces(square))
    ep.bodies(ax, [e.body, ellipsect.inscribed_ellipsoid(ellipsect.hull_half_spaces(square)).body])
    polygon = ax.patches[0].get_xy()[:-1]  # closed: the first corner again at the end
    assert sorted(map(tuple, np.round(polygon, 12))) == [(0, 0), (0, 2), (4, 0), (4, 2)]
    assert len(ax.lines) == 2 and len(ax.lines[0].get_xdata()) == 6 and len(ax.lines[1].get_xdata()) == 4
    ax.figure.savefig(tmp_path / "points.png")
    plt.close(ax.figure)
    with pytest.raises(ValueError, match="half_planes"):
        ep.hull(None, ellipsect.hull_half_spaces(np.eye(4, 3)))
