"""Value-and-gradient batches: closed forms for balls in 50-digit mpmath, batches equal to
one pair at a time bit for bit, the non-differentiable statuses, and bad input."""

import mpmath
import numpy as np
import pytest
from conftest import random_ellipses, random_ellipsoids, same_bits

import ellipsect

mpmath.mp.dps = 50
MAKERS = {2: random_ellipses, 3: random_ellipsoids}


def balls(rng, n, dim, spread=4.0):
    centers = rng.uniform(-spread, spread, (n, dim))
    radii = np.repeat(rng.uniform(0.1, 1.0, (n, 1)), dim, axis=1)
    if dim == 2:
        return ellipsect.Ellipses(centers, radii, angles=rng.uniform(-3, 3, n)), centers, radii[:, 0]
    q = rng.normal(size=(n, 4))
    return ellipsect.Ellipsoids(centers, radii, quaternions=q / np.linalg.norm(q, axis=1, keepdims=True)), centers, \
        radii[:, 0]


def close(got, want, rel):
    return abs(got - float(want)) <= rel * max(1.0, abs(float(want)))


@pytest.mark.parametrize("dim", [2, 3])
def test_balls_signed_distance_and_f_by_closed_form(dim):
    # |c_b - c_a| - r_a - r_b and F = |c_b - c_a|^2 / (r_a + r_b)^2; both by center, radius
    # (each of the equal radii carries its share) and orientation (0).
    rng = np.random.default_rng(1)
    a, ca, ra = balls(rng, 60, dim)
    b, cb, rb = balls(rng, 60, dim)
    d = ellipsect.signed_distance_gradient(a, b)
    f = ellipsect.perram_wertheim_gradient(a, b)
    for i in range(60):
        r = [mpmath.mpf(float(y)) - mpmath.mpf(float(x)) for x, y in zip(ca[i], cb[i])]
        length = mpmath.sqrt(sum(x * x for x in r))
        s = mpmath.mpf(float(ra[i])) + mpmath.mpf(float(rb[i]))
        assert close(d.value[i], length - s, 1e-14)
        assert close(f.value[i], length**2 / s**2, 1e-14)
        radius_share = [d.radii_a[i].sum(), d.radii_b[i].sum()]
        assert all(close(x, -1, 1e-12) for x in radius_share)
        assert close(f.radii_a[i].sum(), -2 * length**2 / s**3, 1e-12)
        for k in range(dim):
            assert close(d.center_a[i, k], -r[k] / length, 1e-12) and close(d.center_b[i, k], r[k] / length, 1e-12)
            assert close(f.center_b[i, k], 2 * r[k] / s**2, 1e-12)
        assert np.all(np.abs(d.orientation_a[i]) <= 1e-12) and np.all(np.abs(f.orientation_b[i]) <= 1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_balls_contact_time_by_closed_form(dim):
    # Centers r(t) = r + t w apart reach r_a + r_b at the smaller root t of
    # |w|^2 t^2 + 2 (r.w) t + |r|^2 - s^2; with the closing rate r(t).w (negative):
    # dt/dc_a = r(t) / (r(t).w), dt/dv_b = -t r(t) / (r(t).w), dt/dr_a = s / (r(t).w).
    # The point x = c_a + t v_a + (r_a / s) r(t) moves with m = v_a + (r_a / s) w along the
    # time: dx/dc_a = (1 - r_a / s) I + m dt/dc_a^T, dx/dv_b = (r_a / s) t I + m dt/dv_b^T,
    # and by a's common radius r_b / s^2 r(t) + m dt/dr_a.
    rng = np.random.default_rng(2)
    a, ca, ra = balls(rng, 80, dim)
    b, cb, rb = balls(rng, 80, dim)
    va = 0.1 * rng.normal(size=(80, dim))  # b heads for a
    vb = (ca - cb) * rng.uniform(0.3, 1.0, (80, 1)) + 0.1 * rng.normal(size=(80, dim))
    g = ellipsect.first_contact_gradient(a, va, b, vb, 10.0)
    hits = 0
    for i in range(80):
        if g.status[i] != ellipsect.ContactStatus.hit:
            continue
        hits += 1
        r = [mpmath.mpf(float(y)) - mpmath.mpf(float(x)) for x, y in zip(ca[i], cb[i])]
        w = [mpmath.mpf(float(y)) - mpmath.mpf(float(x)) for x, y in zip(va[i], vb[i])]
        s = mpmath.mpf(float(ra[i])) + mpmath.mpf(float(rb[i]))
        qa, qb, qc = sum(x * x for x in w), 2 * sum(x * y for x, y in zip(r, w)), sum(x * x for x in r) - s * s
        t = (-qb - mpmath.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa)
        rt = [x + t * y for x, y in zip(r, w)]
        closing = sum(x * y for x, y in zip(rt, w))
        assert close(g.time[i], t, 1e-12)
        for k in range(dim):
            assert close(g.center_a[i, k], rt[k] / closing, 1e-9)
            assert close(g.velocity_b[i, k], -t * rt[k] / closing, 1e-9)
        assert close(g.radii_a[i].sum(), s / closing, 1e-9)
        share = mpmath.mpf(float(ra[i])) / s
        m = [mpmath.mpf(float(x)) + share * y for x, y in zip(va[i], w)]
        jac = g.point_jacobian
        for j in range(dim):
            assert close(g.point[i, j], float(ca[i, j]) + t * float(va[i, j]) + share * rt[j], 1e-12)
            assert close(jac.radii_a[i, j].sum(), (1 - share) / s * rt[j] + m[j] * s / closing, 1e-9)
            for k in range(dim):
                eye = 1 if j == k else 0
                assert close(jac.center_a[i, j, k], (1 - share) * eye + m[j] * rt[k] / closing, 1e-9)
                assert close(jac.velocity_b[i, j, k], share * t * eye - m[j] * t * rt[k] / closing, 1e-9)
    assert hits > 40


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("query", ["signed_distance_gradient", "perram_wertheim_gradient"])
def test_batch_equals_one_pair_at_a_time(dim, query):
    a, _ = MAKERS[dim](120, seed=3)
    b, _ = MAKERS[dim](120, seed=4)
    whole = getattr(ellipsect, query)(a, b, threads=2)
    value = {"signed_distance_gradient": ellipsect.signed_distance,
             "perram_wertheim_gradient": lambda x, y: ellipsect.perram_wertheim(x, y)}[query]
    for i in range(0, 120, 7):
        one = getattr(ellipsect, query)(type(a)(a.centers[i:i + 1], a.radii[i:i + 1], rotations=a.rotations[i:i + 1]),
                                        type(b)(b.centers[i:i + 1], b.radii[i:i + 1], rotations=b.rotations[i:i + 1]),
                                        threads=1)
        for field in whole._fields:
            assert same_bits(getattr(one, field)[0], getattr(whole, field)[i]), (field, i)
        scalar = value(a[i], b[i])
        assert same_bits(whole.value[i], scalar.distance if hasattr(scalar, "distance") else scalar.f)


@pytest.mark.parametrize("dim", [2, 3])
def test_contact_statuses_without_a_derivative(dim):
    # Overlapping at the start: 0 (t = 0 nearby); no contact in the window: NaN.
    rng = np.random.default_rng(5)
    a, ca, _ = balls(rng, 2, dim)
    centers = np.array([ca[0], ca[1] + 100.0])
    b = (ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids)(centers, np.full((2, dim), 0.5))
    g = ellipsect.first_contact_gradient(a, np.zeros((2, dim)), b, np.zeros((2, dim)), 1.0)
    assert g.status[0] == ellipsect.ContactStatus.overlapping_at_start
    assert g.status[1] == ellipsect.ContactStatus.no_contact_in_window
    derivatives = [getattr(g, f) for f in g._fields[2:12]] + list(g.point_jacobian)
    assert len(derivatives) == 20
    for field in derivatives:
        assert np.all(field[0] == 0) and np.all(np.isnan(field[1]))
    assert np.all(np.isnan(g.point))


def test_rigid_motion_and_shapes_of_the_answer():
    a, _ = random_ellipsoids(40, seed=6)
    b, _ = random_ellipsoids(40, seed=7)
    rng = np.random.default_rng(8)
    va, vb, wa = rng.normal(size=(40, 3)), rng.normal(size=(40, 3)), rng.normal(size=(40, 3))
    g = ellipsect.first_contact_gradient(a, va, b, vb, 5.0, angular_velocity_a=wa)
    assert g.center_a.shape == (40, 3) and g.orientation_b.shape == (40, 3) and g.angular_velocity_a.shape == (40, 3)
    assert g.point.shape == (40, 3) and all(x.shape == (40, 3, 3) for x in g.point_jacobian)
    spun = [ellipsect.first_contact(a[i], va[i], b[i], vb[i], 5.0, angular_velocity_a=wa[i]) for i in range(40)]
    assert same_bits(g.time, [c.time for c in spun])
    e, _ = random_ellipses(30, seed=9)
    f, _ = random_ellipses(30, seed=10)
    g2 = ellipsect.first_contact_gradient(e, np.ones((30, 2)), f, np.zeros((30, 2)), 5.0,
                                          angular_velocity_b=np.full(30, 0.3))
    assert g2.orientation_a.shape == (30,) and g2.angular_velocity_b.shape == (30,) and g2.velocity_a.shape == (30, 2)
    jac = g2.point_jacobian
    assert jac.orientation_a.shape == (30, 2) and jac.angular_velocity_b.shape == (30, 2) and jac.radii_b.shape == (30, 2, 2)


def test_quaternion_gradient():
    # f(q) = u . R(q) e_x has world gradient R e_x x u; the chain against differences.
    rng = np.random.default_rng(11)
    q = rng.normal(size=(20, 4))
    u = rng.normal(size=(20, 3))

    def axis(x):
        x = x / np.linalg.norm(x)
        w, v = x[0], x[1:]
        return np.array([1 - 2 * (v[1] ** 2 + v[2] ** 2), 2 * (v[0] * v[1] + w * v[2]), 2 * (v[0] * v[2] - w * v[1])])

    world = np.array([np.cross(axis(q[i]), u[i]) for i in range(20)])
    got = ellipsect.quaternion_gradient(q, world)
    h = 1e-6
    for i in range(20):
        for k in range(4):
            dq = np.zeros(4)
            dq[k] = h
            want = (u[i] @ axis(q[i] + dq) - u[i] @ axis(q[i] - dq)) / (2 * h)
            assert abs(got[i, k] - want) <= 1e-7 * np.linalg.norm(world[i])
    with pytest.raises(ValueError, match="gradient: expected 20 rows"):
        ellipsect.quaternion_gradient(q, world[:5])
    with pytest.raises(ValueError, match=r"quaternions: expected shape \(n, 4\)"):
        ellipsect.quaternion_gradient(q[:, :3], world)


def test_bad_input_names_the_argument():
    a, _ = random_ellipses(5, seed=12)
    b, _ = random_ellipses(4, seed=13)
    with pytest.raises(ValueError, match="b: expected 5 bodies"):
        ellipsect.signed_distance_gradient(a, b)
    c, _ = random_ellipses(5, seed=14)
    with pytest.raises(ValueError, match="angular_velocity_a"):
        ellipsect.first_contact_gradient(a, np.zeros((5, 2)), c, np.zeros((5, 2)), 1.0,
                                         angular_velocity_a=np.zeros((5, 3)))
    with pytest.raises(ValueError, match="velocity_b"):
        ellipsect.first_contact_gradient(a, np.zeros((5, 2)), c, np.zeros((4, 2)), 1.0)


@pytest.mark.parametrize("dim", [2, 3])
def test_closest_approach_gradient(dim):
    # Balls: sigma = r_a + r_b along any direction, 1 by each common radius and 0 by the rest.
    rng = np.random.default_rng(15)
    a, _, ra = balls(rng, 30, dim)
    b, _, rb = balls(rng, 30, dim)
    u = rng.normal(size=(30, dim)) * rng.uniform(0.1, 10, (30, 1))
    g = ellipsect.closest_approach_gradient(a, b, u)
    assert np.all(g.status == ellipsect.ContactFunctionStatus.ok)
    for i in range(30):
        assert close(g.value[i], mpmath.mpf(float(ra[i])) + mpmath.mpf(float(rb[i])), 1e-14)
        assert close(g.radii_a[i].sum(), 1, 1e-12) and close(g.radii_b[i].sum(), 1, 1e-12)
        assert np.all(np.abs(g.direction[i]) <= 1e-12) and np.all(np.abs(g.orientation_a[i]) <= 1e-12)
        assert np.all(g.center_a[i] == 0) and np.all(g.center_b[i] == 0)
    # Random bodies: one pair at a time bit for bit, and the direction's derivative against
    # central differences of the value.
    e, _ = MAKERS[dim](40, seed=16)
    f, _ = MAKERS[dim](40, seed=17)
    d = rng.normal(size=(40, dim))
    whole = ellipsect.closest_approach_gradient(e, f, d, threads=2)
    for i in range(0, 40, 3):
        one = ellipsect.closest_approach(e[i], f[i], d[i])
        assert same_bits(whole.value[i], one.distance)
        for k in range(dim):
            h = 1e-6 * np.linalg.norm(d[i])
            step = np.eye(dim)[k] * h
            diff = (ellipsect.closest_approach(e[i], f[i], d[i] + step).distance
                    - ellipsect.closest_approach(e[i], f[i], d[i] - step).distance) / (2 * h)
            assert abs(whole.direction[i, k] - diff) <= 1e-6 * whole.value[i] / np.linalg.norm(d[i])
    with pytest.raises(ellipsect.InputError, match=r"direction\[2\]"):
        bad = d.copy()
        bad[2] = 0
        ellipsect.closest_approach_gradient(e, f, bad)
    with pytest.raises(ValueError, match="direction"):
        ellipsect.closest_approach_gradient(e, f, d[:5])
