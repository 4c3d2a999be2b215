"""ellipsect.dask on a two-process LocalCluster equals one in-process call bit for bit."""

import numpy as np
import pytest
from conftest import same_bits

import ellipsect
import ellipsect.dask as ed

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        yield c


def arrays(n, dim, seed):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    orientation = {"angles": rng.uniform(-3, 3, n)} if dim == 2 else {"quaternions": q}
    return dict(centers=rng.uniform(-20, 20, (n, dim)), radii=rng.uniform(0.2, 3, (n, dim)), **orientation)


@pytest.mark.parametrize("dim", [2, 3])
def test_cluster_equals_one_process(client, dim):
    n = 4000
    pa, pb = arrays(n, dim, 1), arrays(n, dim, 2)
    a, b = ed.bodies(**pa, chunks=1000), ed.bodies(**pb, chunks=1000)
    kind = ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids
    la, lb = kind(**pa), kind(**pb)
    rng = np.random.default_rng(3)
    va, vb = rng.normal(size=(n, dim)), rng.normal(size=(n, dim))

    flags, relations = client.compute([ed.overlap(a, b), ed.classify(a, b)], sync=True)
    assert np.array_equal(flags, ellipsect.overlap(la, lb)) and flags.any()
    assert np.array_equal(relations, ellipsect.classify(la, lb))
    got = client.compute(list(ed.first_contact(a, va, b, vb, 5.0)), sync=True)
    want = ellipsect.first_contact(la, va, lb, vb, 5.0)
    assert all(same_bits(x, y) for x, y in zip(got, want))
    got = client.compute(list(ed.signed_distance(a, b)), sync=True)
    want = ellipsect.signed_distance(la, lb)
    assert all(same_bits(x, y) for x, y in zip(got, want))
    if dim == 2:
        assert same_bits(ed.iou(a, b).compute(), ellipsect.iou(la, lb))
        assert same_bits(ed.overlap_area(a, b).compute(), ellipsect.overlap_area(la, lb))


def test_mismatched_bodies():
    a = ed.bodies(**arrays(10, 2, 1))
    with pytest.raises(ValueError, match="b: expected 10 bodies"):
        ed.overlap(a, ed.bodies(**arrays(9, 2, 1)))
