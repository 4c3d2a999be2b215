"""fit_ellipsoid from Python: the library's least-squares ellipse or ellipsoid, against the
generating body, the library's own closest_point (the residuals it reports), differences of
the sum of squares (stationarity), hyperbolas, and its argument checks."""

import numpy as np
import pytest

import ellipsect


def on_ellipse(center, angle, radii, t):
    c, s = np.cos(angle), np.sin(angle)
    r = np.array([[c, -s], [s, c]])
    return np.asarray(center) + (np.stack([radii[0] * np.cos(t), radii[1] * np.sin(t)], axis=1)) @ r.T


def residuals(body, points):
    return np.array([ellipsect.closest_point(body, p).signed_distance for p in points])


def test_noise_free_ellipse_is_recovered():
    t = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    points = on_ellipse([1e6, -3.0], 0.4, [30.0, 2.0], t)
    f = ellipsect.fit_ellipsoid(points)
    assert f.status == "converged"
    assert isinstance(f.body, ellipsect.Ellipse)
    assert np.allclose(np.asarray(f.body.center), [1e6, -3.0], rtol=0, atol=1e-7)
    assert np.allclose(sorted(np.asarray(f.body.radii)), [2.0, 30.0], rtol=0, atol=1e-7)
    assert f.max_residual <= 1e-7
    assert f.rank == 5
    assert f.covariance.shape == (5, 5)


def test_noisy_ellipse_matches_its_own_residuals_and_is_stationary():
    rng = np.random.default_rng(48)
    t = rng.uniform(0, 2 * np.pi, 400)
    points = on_ellipse([2.0, 5.0], -0.3, [4.0, 1.5], t) + 0.05 * rng.normal(size=(400, 2))
    f = ellipsect.fit_ellipsoid(points)
    assert f.status == "converged"
    d = residuals(f.body, points)
    assert f.rms_residual == pytest.approx(np.sqrt(np.mean(d * d)), rel=1e-12)
    assert f.max_residual == pytest.approx(np.max(np.abs(d)), rel=1e-12)
    assert f.rms_residual <= f.algebraic_rms_residual
    assert isinstance(f.algebraic, ellipsect.Ellipse)
    # Moving the center or a radius by 1e-6 raises the sum of squares (to second order).
    ss = np.sum(d * d)
    c, axes, radii = np.asarray(f.body.center), np.asarray(f.body.axes), np.asarray(f.body.radii)
    for k in range(2):
        for h in (1e-6, -1e-6):
            moved = ellipsect.Ellipse.from_axes(c + h * np.eye(2)[k], axes, radii)
            assert np.sum(residuals(moved, points) ** 2) >= ss - 1e-12
            grown = ellipsect.Ellipse.from_axes(c, axes, radii + h * np.eye(2)[k])
            assert np.sum(residuals(grown, points) ** 2) >= ss - 1e-12
    # The covariance: positive on its diagonal, the center's spread about noise / sqrt(n).
    assert np.all(np.diag(f.covariance) > 0)
    assert 0.3 < np.sqrt(f.covariance[0, 0]) / (0.05 / np.sqrt(200)) < 3


def test_ellipsoid_in_3d():
    rng = np.random.default_rng(3)
    u = rng.normal(size=(500, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    points = (u * [3.0, 1.0, 0.2]) @ q.T + [10.0, 0.0, -1.0]
    f = ellipsect.fit_ellipsoid(points)
    assert f.status == "converged"
    assert isinstance(f.body, ellipsect.Ellipsoid)
    assert np.allclose(np.asarray(f.body.center), [10.0, 0.0, -1.0], atol=1e-8)
    assert np.allclose(sorted(np.asarray(f.body.radii)), [0.2, 1.0, 3.0], atol=1e-8)
    assert f.covariance.shape == (9, 9)


def test_same_numbers_as_the_enclosing_of_its_points_would_hold():
    # The same call twice gives the same numbers (the fit is deterministic).
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    points = on_ellipse([0.0, 0.0], 1.0, [2.0, 1.0], t) + 1e-3 * np.sin(7 * t)[:, None]
    a, b = ellipsect.fit_ellipsoid(points), ellipsect.fit_ellipsoid(points.tolist())
    assert a.body == b.body
    assert a.rms_residual == b.rms_residual
    assert np.array_equal(a.covariance, b.covariance)


def test_hyperbola_is_not_an_ellipse():
    s = np.linspace(-1.5, 1.5, 100)
    points = np.concatenate([np.stack([2 * np.cosh(s), np.sinh(s)], 1), np.stack([-2 * np.cosh(s), np.sinh(s)], 1)])
    f = ellipsect.fit_ellipsoid(points)
    assert f.status == "not_an_ellipse"


def test_cap_and_options():
    rng = np.random.default_rng(5)
    t = rng.uniform(0, 2 * np.pi, 200)
    points = on_ellipse([0.0, 0.0], 0.2, [5.0, 1.0], t) + 0.2 * rng.normal(size=(200, 2))
    f = ellipsect.fit_ellipsoid(points, max_fit_iterations=1)
    assert f.status == "did_not_converge"
    assert f.iterations == 1
    assert f.rms_residual <= f.algebraic_rms_residual


def test_bad_input_is_named():
    with pytest.raises(ellipsect.InputError, match=r"points\[3\]"):
        ellipsect.fit_ellipsoid([[0, 0], [1, 0], [0, 1], [np.nan, 1], [1, 1], [2, 3]])
    with pytest.raises(ellipsect.InputError, match="at least 5"):
        ellipsect.fit_ellipsoid([[0, 0], [1, 1], [2, 0], [1, 3]])
    with pytest.raises(ellipsect.InputError, match="line"):
        ellipsect.fit_ellipsoid([[i, 2 * i] for i in range(10)])
    with pytest.raises(ellipsect.InputError, match="plane"):
        ellipsect.fit_ellipsoid([[np.cos(i), np.sin(i), 0.0] for i in range(12)])
    with pytest.raises(ValueError, match=r"points: expected shape"):
        ellipsect.fit_ellipsoid(np.zeros((6, 4)))
    with pytest.raises(TypeError, match="points"):
        ellipsect.fit_ellipsoid([["a", "b"]] * 6)
    with pytest.raises(ellipsect.InputError, match="fit_tolerance"):
        ellipsect.fit_ellipsoid(np.eye(5, 2), fit_tolerance=0)
    with pytest.raises(ellipsect.InputError, match="max_fit_iterations"):
        ellipsect.fit_ellipsoid(np.eye(5, 2), max_fit_iterations=0)


def test_batches_of_clouds_answer_as_one_by_one():
    rng = np.random.default_rng(21)
    clouds = []
    for k in range(7):
        t = rng.uniform(0, 2 * np.pi, 60 + 10 * k)
        xy = np.c_[3 * np.cos(t), (1 + 0.2 * k) * np.sin(t)] + rng.normal(scale=0.01, size=(t.size, 2)) + [k, -k]
        clouds.append(xy)
    for threads in (0, 1, 3):
        fits = ellipsect.fit_ellipsoids(clouds, threads=threads)
        hulls = ellipsect.enclosing_ellipsoids(clouds, volume_gap=1e-6, threads=threads)
        assert len(fits) == len(hulls) == len(clouds)
        for cloud, f, e in zip(clouds, fits, hulls):
            one = ellipsect.fit_ellipsoid(cloud)
            assert f.status == one.status and f.rms_residual == one.rms_residual
            assert np.array_equal(np.asarray(f.body.center), np.asarray(one.body.center))
            alone = ellipsect.enclosing_ellipsoid(cloud, volume_gap=1e-6)
            assert e.status == alone.status == "optimal" and e.volume_gap == alone.volume_gap
            assert np.array_equal(np.asarray(e.body.radii), np.asarray(alone.body.radii))
    assert ellipsect.fit_ellipsoids([]) == []
    assert isinstance(ellipsect.enclosing_ellipsoids([np.eye(4, 3) + 0.1 * np.ones((4, 3))])[0].body, ellipsect.Ellipsoid)


def test_batches_of_clouds_name_the_bad_cloud():
    good = np.random.default_rng(2).normal(size=(20, 2))
    line = np.c_[np.arange(10.0), np.arange(10.0)]
    with pytest.raises(ellipsect.InputError, match=r"clouds\[1\]: "):
        ellipsect.fit_ellipsoids([good, line, line])
    bad = good.copy()
    bad[4, 1] = np.inf
    with pytest.raises(ellipsect.InputError, match=r"clouds\[2\]\[4\]: must be finite"):
        ellipsect.enclosing_ellipsoids([good, good, bad])
    with pytest.raises(ValueError, match=r"clouds\[1\]: 3 columns"):
        ellipsect.enclosing_ellipsoids([good, np.ones((5, 3))])
    with pytest.raises(ValueError, match=r"clouds\[0\]: expected shape"):
        ellipsect.fit_ellipsoids([np.ones(5)])
