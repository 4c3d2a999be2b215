"""A million ellipsoid pairs from numpy arrays: which overlap, how they relate, and when
the moving ones first touch (docs/python.md).

    build/venv/bin/python python/examples/million_pairs.py [N]
"""

import sys
import time

import numpy as np

import ellipsect

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
rng = np.random.default_rng(1)


def random_bodies():
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    return dict(centers=rng.uniform(-10, 10, (n, 3)), radii=rng.uniform(0.5, 3, (n, 3)), quaternions=q)


arrays_a, arrays_b = random_bodies(), random_bodies()
velocity_a, velocity_b = rng.normal(size=(n, 3)), rng.normal(size=(n, 3))

start = time.perf_counter()
a = ellipsect.Ellipsoids(**arrays_a)  # validated once, in C++
b = ellipsect.Ellipsoids(**arrays_b)
pairs = ellipsect.pairs(a, b, velocity_a, velocity_b, t_max=1.0)  # prepared once for the three queries
built = time.perf_counter()
hits = ellipsect.overlap(pairs)  # bool[n], all cores
relations = ellipsect.classify(pairs)  # int8[n] of ellipsect.Relation
contact = ellipsect.first_contact(pairs)  # ContactArrays(status, time, point, normal)
done = time.perf_counter()

print(f"{n} pairs: bodies and pairs built in {built - start:.3f} s, "
      f"overlap + classify + first_contact in {done - built:.3f} s, total {done - start:.3f} s")
print(f"overlapping: {hits.sum()}")
for r in ellipsect.Relation:
    print(f"  {r.name:12s} {np.count_nonzero(relations == r)}")
hit = contact.status == ellipsect.ContactStatus.hit
print(f"first contact within t <= 1: {hit.sum()} pairs, earliest at t = {contact.time[hit].min():.6f}")
