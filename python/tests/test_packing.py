"""jam_packing: a small fast compression of bidisperse disks and of ellipsoids; the arrays it
returns rebuild bodies that overlap nowhere (the closed overlap test finds only pairs that
classify as touching), the density is the bodies' volume over the box's, contacts are the
pairs whose Perram-Wertheim scale is within the gap; bad input is named."""

import numpy as np
import pytest

import ellipsect


def bodies_of(p, dim):
    kind = ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids
    return kind(centers=p.centers, radii=p.radii, rotations=p.axes)


@pytest.mark.parametrize("dim", [2, 3])
def test_small_compression_jams_without_overlap(dim):
    n = 80 if dim == 2 else 100
    shape = [1.0, 1.0] if dim == 2 else [1.25, 1.0, 0.8]
    radii = np.array([np.array(shape) * (1.4 if i % 2 and dim == 2 else 1.0) for i in range(n)])
    p = ellipsect.jam_packing(radii, schedule=[(0.0, 0.1)], pressure=1e3, seed=3)
    assert p.status == "jammed"
    assert p.overlapping == 0 and p.predictions_overlapping == 0 and p.predictions_stopped == 0
    assert p.centers.shape == (n, dim) and p.axes.shape == (n, dim, dim) and p.radii.shape == (n, dim)
    # The shapes kept: each body's radii are the given ones times one common scale.
    scale = p.radii / radii
    assert np.allclose(scale, scale[0, 0], rtol=1e-12)
    volume = (np.pi if dim == 2 else 4 * np.pi / 3) * np.prod(p.radii, axis=1).sum()
    assert p.density == pytest.approx(volume / np.prod(p.box), rel=1e-12)
    assert p.pressure >= 1e3 and p.collisions > 0
    assert 0.6 < p.density < (0.86 if dim == 2 else 0.76)
    assert p.history.shape[1] == 2 and np.all(np.diff(p.history[:, 0]) > 0)
    # No pair overlaps: every pair the closed test finds touches (within the tangency band).
    bodies = bodies_of(p, dim)
    body = ellipsect.Ellipse if dim == 2 else ellipsect.Ellipsoid

    def image_of(j, image):
        return body(p.centers[j] + np.asarray(image) * p.box, p.radii[j], rotation=p.axes[j])

    for i, j, *image in ellipsect.overlapping_pairs(bodies, box=p.box):
        assert ellipsect.classify(bodies[int(i)], image_of(j, image)) == ellipsect.Relation.touching
    # Contacts: i < j, within the gap by the Perram-Wertheim function.
    assert p.contacts.shape[1] == 2 + dim and len(p.contacts) > n
    for i, j, *image in p.contacts[:20]:
        mu = np.sqrt(ellipsect.perram_wertheim(bodies[int(i)], image_of(j, image)).f)
        assert i < j and mu - 1 < 100 / 1e3
    assert p.mean_contacts == pytest.approx(2 * len(p.contacts) / n)


def test_bad_input_is_named():
    radii = np.ones((10, 2))
    with pytest.raises(ValueError, match="radii"):
        ellipsect.jam_packing(np.ones((10, 4)))
    bad = radii.copy()
    bad[4, 0] = -1
    with pytest.raises(ellipsect.InputError, match=r"radii\[4\]"):
        ellipsect.jam_packing(bad)
    with pytest.raises(ellipsect.InputError, match="pressure"):
        ellipsect.jam_packing(radii, pressure=0.5)
    with pytest.raises(ellipsect.InputError, match=r"schedule\[1\]"):
        ellipsect.jam_packing(radii, schedule=[(0.0, 0.1), (0.0, 0.2)])


def test_density_example_runs(tmp_path):
    # python/examples/packing_density.py (docs/packing.md) at a small size.
    import pathlib
    import sys

    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))
    import packing_density

    rows = packing_density.run(2, 40, [1.0, 1.5], [1], [(0.0, 0.1)], 1e3, 1e-2)
    assert [r["alpha"] for r in rows] == [1.0, 1.5]
    assert all(0.75 < r["density"] < 0.92 and r["pressure"] >= 1e3 for r in rows)
    packing_density.plot(rows, 2, str(tmp_path / "plot.png"), "test")
    packing_density.picture(packing_density.first_packing, 2, str(tmp_path / "picture.png"))
    assert (tmp_path / "plot.png").stat().st_size > 1000 and (tmp_path / "picture.png").stat().st_size > 1000
