"""The gradient examples (python/examples/overlap_removal.py and iou_loss.py,
docs/gradient-examples.md) at small sizes."""

import pathlib
import sys

import numpy as np
import pytest

import ellipsect

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))
import iou_loss  # noqa: E402
import overlap_removal  # noqa: E402


def test_overlap_removal_separates_every_pair_with_local_moves():
    centers, radii, angles = overlap_removal.random_scene(np.random.default_rng(3), 120)
    assert len(ellipsect.overlapping_pairs(ellipsect.Ellipses(centers, radii, angles=angles))) > 60
    moved, iterations = overlap_removal.remove_overlaps(centers, radii, angles, max_iterations=300)
    assert 0 < iterations < 300
    assert len(ellipsect.overlapping_pairs(ellipsect.Ellipses(moved, radii, angles=angles))) == 0
    # A pair's penetration depth is below the sum of its major radii (the supports along the
    # line of centers), so clearing a body's own overlaps needs less than the largest diameter;
    # a larger move would mean bodies shoved along chains across the pack.
    shift = np.linalg.norm(moved - centers, axis=1)
    assert shift.max() < 2 * radii.max()
    assert shift.mean() < radii[:, 0].mean()


def test_overlap_removal_reports_an_exhausted_bound():
    centers, radii, angles = overlap_removal.random_scene(np.random.default_rng(3), 120)
    with pytest.raises(RuntimeError, match="still overlap after 2 steps"):
        overlap_removal.remove_overlaps(centers, radii, angles, max_iterations=2)


def test_surrogates_are_exact_only_for_equal_ellipses():
    table = iou_loss.surrogate_table(np.random.default_rng(4), 200)
    assert set(table) == {"random", "random, overlapping", "near-concentric"}
    for measures in table.values():
        assert np.all((measures["exact"] >= 0) & (measures["exact"] <= 1))
        for name in ("probiou", "kld"):
            assert np.all(np.isfinite(measures[name])) and np.all((measures[name] > 0) & (measures[name] <= 1))
    assert np.all(table["random, overlapping"]["exact"] > 0)
    # Near-concentric pairs (IoU about 0.9): neither surrogate is the IoU.
    close = table["near-concentric"]
    assert close["exact"].mean() > 0.8
    assert np.abs(close["probiou"] - close["exact"]).mean() > 0.01
    assert np.abs(close["kld"] - close["exact"]).mean() > 0.01
    # Disjoint pairs have IoU 0, the Gaussians still overlap.
    apart = table["random"]["exact"] == 0
    assert apart.sum() > 20 and np.all(table["random"]["probiou"][apart] > 0)
    # Equal ellipses: every measure is 1.
    same = iou_loss.random_ellipses(np.random.default_rng(5), 50)
    for values in iou_loss.measures(same, same).values():
        np.testing.assert_allclose(values, 1, rtol=0, atol=1e-14)
    assert "| near-concentric | 200 |" in iou_loss.markdown(table)


@pytest.mark.parametrize("target", [ellipsect.Ellipse([0.0, 0.0], [2.0, 0.8], angle=0.3),
                                    ellipsect.Ellipse([0.5, -0.2], [4.0, 1.0], angle=-2.0),
                                    ellipsect.Ellipse([0.5, -0.2], [1.0, 0.99], angle=1.0)],
                         ids=["example", "aspect-4", "near-circle"])
def test_fit_reaches_the_target(target):
    start = iou_loss.perturbed_start(target, 1.0)
    assert 0 < ellipsect.iou(start, target) < 0.7
    fit = iou_loss.fit_ellipse(target, start, max_iterations=40)
    assert fit.loss <= 1e-12 and fit.iterations < 40
    assert fit.iterations == len(fit.euler) == len(fit.path) - 1 and any(fit.euler)
    assert fit.losses[-1] == fit.loss
    np.testing.assert_allclose(fit.ellipse.center, target.center, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fit.ellipse.radii, target.radii, rtol=0, atol=1e-9)
    assert 1 - ellipsect.iou(fit.ellipse, target) <= 1e-12


def test_fit_gradient_by_the_shape_matrix_against_differences():
    target = ellipsect.Ellipse([0.0, 0.0], [2.0, 0.8], angle=0.3)
    goal = ellipsect.Ellipses(np.array([target.center]), np.array([target.radii]), rotations=np.array([target.axes]))
    y = iou_loss.to_parameters(iou_loss.perturbed_start(target, 1.0))
    np.testing.assert_allclose(iou_loss.to_parameters(iou_loss.to_ellipse(y)), y, rtol=0, atol=1e-14)
    (f,), (g,) = iou_loss.loss_and_gradient(y[None], goal)
    h = 1e-6
    ups, _ = iou_loss.loss_and_gradient(y + h * np.eye(5), goal)
    downs, _ = iou_loss.loss_and_gradient(y - h * np.eye(5), goal)
    np.testing.assert_allclose(g, (ups - downs) / (2 * h), rtol=0, atol=1e-8)


def test_fit_rejects_a_start_apart_from_the_target():
    target = ellipsect.Ellipse([0.0, 0.0], [2.0, 0.8], angle=0.3)
    with pytest.raises(ValueError, match="does not overlap"):
        iou_loss.fit_ellipse(target, ellipsect.Ellipse([10.0, 0.0], [1.0, 1.0]))
