"""Batch queries over numpy arrays equal the scalar functions bit for bit."""

import numpy as np
import pytest
from conftest import random_ellipses, random_ellipsoids, same_bits

import ellipsect

MAKERS = {2: random_ellipses, 3: random_ellipsoids}


@pytest.mark.parametrize("dim", [2, 3])
def test_construction_round_trips(dim):
    batch, bodies = MAKERS[dim](50, seed=1)
    assert len(batch) == 50
    assert same_bits(batch.centers, [b.center for b in bodies])
    assert same_bits(batch.radii, [b.radii for b in bodies])
    assert same_bits(batch.rotations, [b.axes for b in bodies])
    assert same_bits(batch[7].center, bodies[7].center) and same_bits(batch[-1].radii, bodies[-1].radii)
    again = type(batch)(centers=batch.centers, radii=batch.radii, rotations=batch.rotations)
    assert same_bits(again.rotations, batch.rotations)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("threads", [1, 0])
def test_overlap_and_classify_equal_scalar(dim, threads):
    a, sa = MAKERS[dim](400, seed=2)
    b, sb = MAKERS[dim](400, seed=3)
    flags = ellipsect.overlap(a, b, threads=threads)
    relations = ellipsect.classify(a, b, threads=threads)
    assert flags.dtype == np.bool_ and relations.dtype == np.int8
    assert flags.tolist() == [ellipsect.overlap(x, y) for x, y in zip(sa, sb)]
    assert relations.tolist() == [int(ellipsect.classify(x, y)) for x, y in zip(sa, sb)]
    assert 0 < flags.sum() < len(flags)


@pytest.mark.parametrize("dim", [2, 3])
def test_first_contact_equals_scalar(dim):
    a, sa = MAKERS[dim](300, seed=4)
    b, sb = MAKERS[dim](300, seed=5)
    rng = np.random.default_rng(6)
    va, vb = rng.normal(size=(300, dim)), rng.normal(size=(300, dim))
    t_max = rng.uniform(0, 5, 300)
    got = ellipsect.first_contact(a, va, b, vb, t_max)
    want = [ellipsect.first_contact(x, u, y, v, t) for x, u, y, v, t in zip(sa, va, sb, vb, t_max)]
    assert got.status.tolist() == [int(c.status) for c in want]
    assert same_bits(got.time, [c.time for c in want])
    assert same_bits(got.point, [c.point for c in want])
    assert same_bits(got.normal, [c.normal for c in want])
    assert ellipsect.ContactStatus.hit in got.status
    same_window = ellipsect.first_contact(a, va, b, vb, 2.5)
    assert same_bits(same_window.time, ellipsect.first_contact(a, va, b, vb, np.full(300, 2.5)).time)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("query", ["distance", "signed_distance"])
def test_distances_equal_scalar(dim, query):
    a, sa = MAKERS[dim](150, seed=7)
    b, sb = MAKERS[dim](150, seed=8)
    got = getattr(ellipsect, query)(a, b, threads=2)
    want = [getattr(ellipsect, query)(x, y) for x, y in zip(sa, sb)]
    assert got.status.tolist() == [int(d.status) for d in want]
    for field in ("distance", "point_a", "point_b", "normal"):
        assert same_bits(getattr(got, field), [getattr(d, field) for d in want]), field


def test_areas_equal_scalar():
    a, sa = random_ellipses(300, seed=9, spread=3)
    b, sb = random_ellipses(300, seed=10, spread=3)
    assert same_bits(ellipsect.overlap_area(a, b), [ellipsect.overlap_area(x, y).area for x, y in zip(sa, sb)])
    iou = ellipsect.iou(a, b)
    assert same_bits(iou, [ellipsect.iou(x, y) for x, y in zip(sa, sb)])
    assert np.all((iou >= 0) & (iou <= 1)) and np.any(iou > 0)


def test_take_selects_rows():
    a, sa = random_ellipses(20, seed=11)
    picked = a.take(np.array([3, 3, 0]))
    assert same_bits(picked.centers, [sa[3].center, sa[3].center, sa[0].center])
    with pytest.raises(IndexError):
        a.take(np.array([20]))


@pytest.mark.parametrize("dim", [2, 3])
def test_prepared_pairs_equal_bodies(dim):
    a, _ = MAKERS[dim](300, seed=12)
    b, _ = MAKERS[dim](300, seed=13)
    rng = np.random.default_rng(14)
    va, vb, t_max = rng.normal(size=(300, dim)), rng.normal(size=(300, dim)), rng.uniform(0, 3, 300)
    static = ellipsect.pairs(a, b)
    assert len(static) == 300
    assert np.array_equal(ellipsect.overlap(static), ellipsect.overlap(a, b))
    assert np.array_equal(ellipsect.classify(static, threads=1), ellipsect.classify(a, b))
    got = ellipsect.first_contact(ellipsect.pairs(a, b, va, vb, t_max))
    want = ellipsect.first_contact(a, va, b, vb, t_max)
    assert all(same_bits(x, y) for x, y in zip(got, want))


@pytest.mark.parametrize("dim", [2, 3])
def test_batches_pickle_bit_for_bit(dim):
    import pickle

    a, _ = MAKERS[dim](100, seed=15)
    again = pickle.loads(pickle.dumps(a))
    assert type(again) is type(a) and len(again) == 100
    for field in ("centers", "radii", "rotations"):
        assert same_bits(getattr(again, field), getattr(a, field))


def test_float32_orientations_are_normalized():
    # Unit quaternions and rotations rounded to float32 are ~6e-8 off unit norm and
    # orthonormality, beyond the 1e-9 of the float64 checks: as float32 arrays, or with
    # normalize=True after astype(float64), each row within float32's tolerance is made exact.
    rng = np.random.default_rng(21)
    n = 200
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    centers, radii = rng.uniform(-5, 5, (n, 3)), rng.uniform(0.5, 2, (n, 3))
    exact = ellipsect.Ellipsoids(centers=centers, radii=radii, quaternions=q)
    q32, r32 = q.astype(np.float32), exact.rotations.astype(np.float32)
    for name, given in (("quaternions", q32), ("rotations", r32)):
        with pytest.raises(ellipsect.InputError, match=name):
            ellipsect.Ellipsoids(centers=centers, radii=radii, **{name: given.astype(np.float64)})
        got = ellipsect.Ellipsoids(centers=centers, radii=radii, **{name: given})
        again = ellipsect.Ellipsoids(centers=centers, radii=radii, normalize=True, **{name: given.astype(np.float64)})
        assert same_bits(got.rotations, again.rotations)
        assert np.abs(got.rotations - exact.rotations).max() < 1e-6
        gram = np.einsum("nki,nkj->nij", got.rotations, got.rotations)
        assert np.abs(gram - np.eye(3)).max() <= 12 * np.finfo(float).eps  # as from_axes keeps axes
        scalar = ellipsect.Ellipsoid(centers[5], radii[5], normalize=True, **{name[:-1]: given[5].astype(np.float64)})
        assert same_bits(scalar.axes, got.rotations[5])
        bad = given.copy()
        bad[7] *= 2
        with pytest.raises(ellipsect.InputError, match=rf"{name}\[7"):
            ellipsect.Ellipsoids(centers=centers, radii=radii, **{name: bad})
    flat, _ = random_ellipses(n, seed=22)
    r2 = flat.rotations.astype(np.float32)
    with pytest.raises(ellipsect.InputError, match="rotations"):
        ellipsect.Ellipses(centers=flat.centers, radii=flat.radii, rotations=r2.astype(np.float64))
    got = ellipsect.Ellipses(centers=flat.centers, radii=flat.radii, rotations=r2)
    assert np.abs(got.rotations - flat.rotations).max() < 1e-6
    assert same_bits(ellipsect.Ellipse(flat.centers[3], flat.radii[3], rotation=r2[3], normalize=True).axes,
                     got.rotations[3])


@pytest.mark.parametrize("dim", [2, 3])
def test_overlapping_pairs_equal_all_pairs_loop(dim):
    bodies, scalar = MAKERS[dim](150, seed=11)
    pairs = ellipsect.overlapping_pairs(bodies)
    expected = [(i, j) for i in range(150) for j in range(i + 1, 150) if ellipsect.overlap(scalar[i], scalar[j])]
    assert pairs.dtype == np.int64 and pairs.shape == (len(expected), 2)
    assert [tuple(p) for p in pairs.tolist()] == expected and len(expected) > 20


def test_overlapping_pairs_in_a_periodic_box():
    # Ellipses of radii up to 3 in a box of side 14: pairs meet across the faces.
    side = 14.0
    rng = np.random.default_rng(12)
    centers = rng.uniform(0, side, (80, 2)) + side * rng.integers(-2, 3, (80, 2))  # anywhere: taken modulo the box
    radii = rng.uniform(0.2, 1.6, (80, 2))
    angles = rng.uniform(-np.pi, np.pi, 80)
    bodies = ellipsect.Ellipses(centers=centers, radii=radii, angles=angles)
    got = ellipsect.overlapping_pairs(bodies, box=[side, side])
    expected = []
    for i in range(80):
        a = ellipsect.Ellipse(centers[i], radii[i], angle=angles[i])
        for j in range(i + 1, 80):
            near = np.round((centers[i] - centers[j]) / side).astype(int)
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    m = near + [dx, dy]
                    b = ellipsect.Ellipse(centers[j] + m * side, radii[j], angle=angles[j])
                    if ellipsect.overlap(a, b):
                        expected.append((i, j, m[0], m[1]))
    assert got.shape == (len(expected), 4)
    assert [tuple(p) for p in got.tolist()] == sorted(expected)
    assert any(p[2] != 0 or p[3] != 0 for p in got.tolist())
    with pytest.raises(ValueError, match="box"):
        ellipsect.overlapping_pairs(bodies, box=[side, 1.0])


@pytest.mark.parametrize("dim", [2, 3])
def test_earliest_contact_equals_the_pairwise_minimum(dim):
    rng = np.random.default_rng(20 + dim)
    n, side = 25, 20.0 if dim == 2 else 10.0
    centers = []
    while len(centers) < n:  # bounding balls (radius 1) apart
        c = rng.uniform(0, side, dim)
        if all(np.linalg.norm(c - d) > 2.0 for d in centers):
            centers.append(c)
    centers = np.array(centers)
    radii = rng.uniform(0.3, 1.0, (n, dim))
    if dim == 2:
        angles = rng.uniform(-np.pi, np.pi, n)
        bodies = ellipsect.Ellipses(centers=centers, radii=radii, angles=angles)
        scalar = [ellipsect.Ellipse(c, r, angle=a) for c, r, a in zip(centers, radii, angles)]
        spins = rng.normal(size=n)
    else:
        q = rng.normal(size=(n, 4))
        q /= np.linalg.norm(q, axis=1)[:, None]
        bodies = ellipsect.Ellipsoids(centers=centers, radii=radii, quaternions=q)
        scalar = [ellipsect.Ellipsoid(c, r, quaternion=w) for c, r, w in zip(centers, radii, q)]
        spins = rng.normal(size=(n, 3))
    velocities = rng.normal(size=(n, dim))
    best = (np.inf, None)
    for i in range(n):
        for j in range(i + 1, n):
            c = ellipsect.first_contact(scalar[i], velocities[i], scalar[j], velocities[j], 5.0,
                                        angular_velocity_a=spins[i], angular_velocity_b=spins[j])
            if c.status == ellipsect.ContactStatus.hit and c.time < best[0]:
                best = (c.time, (i, j))
    assert best[1] is not None
    i, j, image, contact = ellipsect.earliest_contact(bodies, velocities, 5.0, angular_velocities=spins)
    assert contact.status == ellipsect.ContactStatus.hit and (i, j) == best[1] and image == (0,) * dim
    assert abs(contact.time - best[0]) <= 1e-12 * best[0]
    # In a periodic box the first contact can only come sooner (more images), never later.
    *_, periodic = ellipsect.earliest_contact(bodies, velocities, 5.0, angular_velocities=spins, box=[side] * dim)
    assert periodic.status == ellipsect.ContactStatus.hit and periodic.time <= contact.time * (1 + 1e-12)
    with pytest.raises(ValueError, match="velocities"):
        ellipsect.earliest_contact(bodies, velocities[:3], 5.0)
    bad = velocities.copy()
    bad[4, 0] = np.nan
    with pytest.raises(ValueError, match=r"motions\[4\].velocity"):
        ellipsect.earliest_contact(bodies, bad, 5.0)


@pytest.mark.parametrize("dim", [2, 3])
def test_gpu_entry_points_equal_batch(dim):
    a, _ = MAKERS[dim](300, seed=11)
    b, _ = MAKERS[dim](300, seed=12)
    p = ellipsect.pairs(a, b)
    info = ellipsect.gpu_info()
    expected = "gpu" if info["built"] and info["devices"] > 0 else "cpu"
    flags, on = ellipsect.overlap_on_gpu(p)
    relations, on_classify = ellipsect.classify_on_gpu(p)
    assert on == on_classify == expected
    assert flags.dtype == np.bool_ and relations.dtype == np.int8
    assert flags.tolist() == ellipsect.overlap(p).tolist()
    assert relations.tolist() == ellipsect.classify(p).tolist()
    assert 0 < flags.sum() < len(flags)


def float_exact_scene(dim, n, seed):
    """n pairs of bodies whose every number is a float32: axes signed permutations, centres
    and radii multiples of 2^-10, b placed along a's axis 0 at gaps of about +-2^-k (k = 4..30)
    times the pair's size from touching a from outside, or from inside a where it fits, its
    centre rounded to float32 (so the gaps below float's resolution are 0 or a few ulps).
    The double bodies are then exactly their float32 roundings; returns a, b and the gaps."""
    rng = np.random.default_rng(seed)

    def axes():
        m = np.eye(dim)[rng.permutation(dim)] * rng.choice([-1.0, 1.0], dim)
        return m if np.linalg.det(m) > 0 else m * np.r_[-1.0, np.ones(dim - 1)]

    grid = 2.0**-10
    ca, ra, cb, rb, ma, mb, gaps = [], [], [], [], [], [], []
    for i in range(n):
        r_a = np.round(rng.uniform(0.5, 4.0, dim) / grid) * grid
        r_b = np.round(rng.uniform(0.25, 2.0, dim) / grid) * grid
        m_a = axes()
        u = m_a[:, 0]
        # b's extent along u is its radius along the axis that its permutation puts there.
        m_b = np.eye(dim)
        inside = i % 3 == 2 and np.all(r_b < r_a.min() / 2)
        gap = rng.choice([-1.0, 1.0]) * 2.0 ** -rng.integers(4, 31) * (r_a[0] + r_b[0])
        gap = 0.0 if i % 7 == 0 else gap
        reach = r_a[0] - r_b[0] if inside else r_a[0] + r_b[0]
        c_a = np.round(rng.uniform(-8, 8, dim) / grid) * grid
        c_b = (c_a + u * (reach + gap)).astype(np.float32).astype(np.float64)
        ca.append(c_a)
        cb.append(c_b)
        ra.append(r_a)
        rb.append(r_b)
        ma.append(m_a)
        mb.append(m_b)
        gaps.append(u @ (c_b - c_a) - reach)  # exact: float32 numbers
    make = ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids
    a = make(centers=np.array(ca), radii=np.array(ra), rotations=np.array(ma))
    b = make(centers=np.array(cb), radii=np.array(rb), rotations=np.array(mb))
    for batch in (a, b):
        for field in ("centers", "radii", "rotations"):
            values = getattr(batch, field)
            assert np.array_equal(values.astype(np.float32), values)
    return a, b, np.array(gaps)


@pytest.mark.parametrize("dim", [2, 3])
def test_float32_pairs_answer_as_the_bodies_in_float(dim):
    # The bodies are float32 numbers, so rounding them changes nothing and the float pairs'
    # answers must be the double ones, at every gap down to 2^-30 of the pair's size.
    a, b, gaps = float_exact_scene(dim, 300, seed=21)
    p = ellipsect.pairs(a, b, dtype=np.float32)
    assert type(p).__name__ == f"Pairs{dim}f" and p.dtype == np.float32 and len(p) == 300
    relations = ellipsect.classify(p)
    assert relations.tolist() == ellipsect.classify(a, b).tolist()
    assert ellipsect.overlap(p, threads=1).tolist() == ellipsect.overlap(a, b).tolist()
    assert ellipsect.classify_on_gpu(p)[1] == "cpu"  # float pairs are filtered on the host
    kinds = set(relations.tolist())
    assert {int(ellipsect.Relation.separated), int(ellipsect.Relation.touching)} <= kinds and len(kinds) >= 4
    assert np.sum(np.abs(gaps) < 1e-6) > 20  # many pairs closer to tangency than float's epsilon

    rng = np.random.default_rng(22)
    va = np.round(rng.normal(size=(300, dim)) * 64) / 64
    vb = np.zeros((300, dim))
    t_max = np.full(300, 2.0)
    got = ellipsect.first_contact(ellipsect.pairs(a, b, va, vb, t_max, dtype="float32"))
    want = ellipsect.first_contact(a, va, b, vb, t_max)
    assert got.time.dtype == got.point.dtype == got.normal.dtype == np.float32
    assert got.status.tolist() == want.status.tolist()
    assert same_bits(got.time, want.time.astype(np.float32))
    assert same_bits(got.point, want.point.astype(np.float32))
    assert ellipsect.ContactStatus.hit in got.status


@pytest.mark.parametrize("dim", [2, 3])
def test_float32_pairs_round_each_body(dim):
    # Rotated bodies are not float numbers: rounding moves them by about 1e-7 of their size,
    # which can change an answer only for pairs that close to tangency.
    a, _ = MAKERS[dim](400, seed=23)
    b, _ = MAKERS[dim](400, seed=24)
    p = ellipsect.pairs(a, b, dtype=np.float32)
    got, want = ellipsect.classify(p), ellipsect.classify(a, b)
    depth = ellipsect.signed_distance(a, b).distance / (a.radii.max(axis=1) + b.radii.max(axis=1))
    clear = np.abs(depth) > 1e-5
    assert clear.sum() > 390
    assert got[clear].tolist() == want[clear].tolist()
    assert ellipsect.overlap(p).tolist() == (got != int(ellipsect.Relation.separated)).tolist()


def test_float32_pairs_name_what_float_cannot_hold():
    centers, radii = np.zeros((3, 3)), np.ones((3, 3))
    a = ellipsect.Ellipsoids(centers=centers, radii=radii)
    big, tiny, far = radii.copy(), radii.copy(), centers.copy()
    big[1] = 1e39
    tiny[2] = 1e-46
    far[1, 0] = -1e39
    with pytest.raises(ellipsect.InputError, match=r"b\[1\]\.radii\[0\]") as error:
        ellipsect.pairs(a, ellipsect.Ellipsoids(centers=centers, radii=big), dtype=np.float32)
    assert error.value.field == "b[1].radii[0]" and "float32" in str(error.value)
    with pytest.raises(ellipsect.InputError, match=r"a\[2\]\.radii\[0\]"):
        ellipsect.pairs(ellipsect.Ellipsoids(centers=centers, radii=tiny), a, dtype=np.float32)
    with pytest.raises(ellipsect.InputError, match=r"a\[1\]\.center\[0\]"):
        ellipsect.pairs(ellipsect.Ellipsoids(centers=far, radii=radii), a, dtype=np.float32)
    with pytest.raises(TypeError, match="dtype: expected float64 or float32, got float16"):
        ellipsect.pairs(a, a, dtype=np.float16)
    assert len(ellipsect.pairs(a, ellipsect.Ellipsoids(centers=centers, radii=big))) == 3  # double holds it
    # A velocity beyond float's range is that pair's invalid input, as in the C++ batch.
    v = np.zeros((3, 3))
    v[0, 0] = 1e39
    contact = ellipsect.first_contact(ellipsect.pairs(a, a, v, np.zeros((3, 3)), 1.0, dtype=np.float32))
    assert contact.status[0] == ellipsect.ContactStatus.invalid_input
    assert contact.status[1] != ellipsect.ContactStatus.invalid_input
