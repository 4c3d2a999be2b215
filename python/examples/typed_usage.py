"""The package under `mypy --strict` (python/tests/test_typing.py checks this file): scalar
bodies and shapes, batches from numpy arrays, prepared pairs, results and their fields, and a
picture (`python typed_usage.py scene.png`)."""

import pickle
import sys

import numpy as np
import numpy.typing as npt

import ellipsect


def earliest_hit(a: ellipsect.Ellipsoids, b: ellipsect.Ellipsoids, velocities: npt.NDArray[np.float64]) -> float:
    """The earliest first contact time among the pairs (a[i], b[i]), inf without one."""
    contact = ellipsect.first_contact(a, velocities, b, -velocities, 2.0)
    hits = contact.time[contact.status == ellipsect.ContactStatus.hit]
    return float(hits.min()) if hits.size else float("inf")


def picture(bodies: ellipsect.Ellipsoids, path: str) -> None:
    """The bodies' outlines on the xy plane joined by their overlapping pairs, saved to path."""
    import ellipsect.plot as ep

    ax = ep.bodies(None, bodies)
    ep.pairs(ax, bodies, ellipsect.overlapping_pairs(bodies))
    ax.figure.savefig(path)


def main() -> None:
    a = ellipsect.Ellipse([0.0, 0.0], [3.0, 1.0], angle=0.5)
    b = ellipsect.Ellipse([4.0, 0.0], [1.0, 1.0])
    relation: ellipsect.Relation = ellipsect.classify(a, b)
    contact = ellipsect.first_contact(a, [1.0, 0.0], b, [0.0, 0.0], 5.0)
    gap = ellipsect.signed_distance(a, ellipsect.Box2([0.0, -3.0], [5.0, 1.0]))
    print(relation.name, contact.status.name, contact.time, gap.distance, gap.point_a)
    assert pickle.loads(pickle.dumps(a)) == a

    rng = np.random.default_rng(1)
    n = 100
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    bodies = ellipsect.Ellipsoids(centers=rng.uniform(-5, 5, (n, 3)), radii=rng.uniform(0.5, 2, (n, 3)),
                                  quaternions=q.astype(np.float32))
    others = bodies.take(np.arange(n)[::-1])
    flags = ellipsect.overlap(bodies, others)
    pairs = ellipsect.pairs(bodies, others, dtype=np.float32)
    print(int(flags.sum()), len(pairs), ellipsect.overlapping_pairs(bodies).shape,
          earliest_hit(bodies, others, rng.normal(size=(n, 3))))
    if len(sys.argv) > 1:
        picture(bodies, sys.argv[1])


if __name__ == "__main__":
    main()
