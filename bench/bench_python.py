"""Figures of the Python module (bench/RESULTS.md, section "Python"), run by hand:

    bash scripts/run.sh test  # or: the venv of python_test (build/venv) and
    cmake --build build/release --target python_baseline
    build/venv/bin/python bench/bench_python.py [--pairs N] [--quick]

1. Overhead of ellipsect.overlap / classify on N ellipsoid pairs over the C++ span overloads
   (build/release/bench/python_baseline on the same bodies; best of 5 each), from the bodies,
   on pairs prepared once, and on float32 pairs (pairs(..., dtype=float32)).
2. Ellipse IoU: ellipsect.iou against shapely polygons of 64 and 256 vertices: time per
   pair and error against the exact area (the scalar overlap_area, 1e-12 accurate).
3. Dask: pairs per second of ellipsect.dask.overlap on LocalCluster(2 workers x 1 thread)
   against one in-process call.
"""

import argparse
import json
import os
import subprocess
import tempfile
import time

import numpy as np

import ellipsect

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def best_of(k, f):
    best = float("inf")
    for _ in range(k):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def ellipsoid_arrays(n, rng):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    return dict(centers=rng.uniform(-10, 10, (n, 3)), radii=rng.uniform(0.5, 3, (n, 3)), quaternions=q)


def overhead(n):
    rng = np.random.default_rng(1)
    pa, pb = ellipsoid_arrays(n, rng), ellipsoid_arrays(n, rng)
    build = best_of(3, lambda: ellipsect.Ellipsoids(**pa))
    a, b = ellipsect.Ellipsoids(**pa), ellipsect.Ellipsoids(**pb)
    p = ellipsect.pairs(a, b)
    build_pairs = best_of(3, lambda: ellipsect.pairs(a, b))
    build_single = best_of(3, lambda: ellipsect.pairs(a, b, dtype=np.float32))
    single = ellipsect.pairs(a, b, dtype=np.float32)
    py = {"overlap": best_of(5, lambda: ellipsect.overlap(a, b)), "classify": best_of(5, lambda: ellipsect.classify(a, b)),
          "overlap_pairs": best_of(5, lambda: ellipsect.overlap(p)),
          "classify_pairs": best_of(5, lambda: ellipsect.classify(p)),
          "overlap_pairs_float": best_of(5, lambda: ellipsect.overlap(single)),
          "classify_pairs_float": best_of(5, lambda: ellipsect.classify(single))}
    program = os.path.join(ROOT, "build", "release", "bench", "python_baseline")
    with tempfile.TemporaryDirectory() as d:
        for side, p in (("a", pa), ("b", pb)):
            for k, v in p.items():
                np.ascontiguousarray(v, dtype=np.float64).tofile(os.path.join(d, f"{side}_{k}"))
        cpp = json.loads(subprocess.run([program, d, str(n)], check=True, capture_output=True, text=True).stdout)
    assert cpp["hits"] == int(ellipsect.overlap(a, b).sum())
    print(f"## overhead, {n} ellipsoid pairs (best of 5)")
    print(f"Ellipsoids(...) from arrays: {build:.3f} s ({build / n * 1e9:.0f} ns per body)")
    print(f"pairs(a, b): {build_pairs:.3f} s; pairs(a, b, dtype=float32): {build_single:.3f} s")
    print("| query | C++ | Python | overhead |")
    print("|---|---|---|---|")
    for q, what in (("overlap", "overlap(a, b)"), ("classify", "classify(a, b)"),
                    ("overlap_pairs", "overlap(pairs), pairs built once"),
                    ("classify_pairs", "classify(pairs), pairs built once"),
                    ("overlap_pairs_float", "overlap(pairs), float32 pairs"),
                    ("classify_pairs_float", "classify(pairs), float32 pairs")):
        print(f"| {what} | {cpp[q] * 1e3:.1f} ms | {py[q] * 1e3:.1f} ms | {100 * (py[q] / cpp[q] - 1):+.1f}% |")


def iou_versus_shapely(n):
    from shapely.geometry import Polygon

    rng = np.random.default_rng(2)
    centers, radii, angles = rng.uniform(-2, 2, (2 * n, 2)), rng.uniform(0.5, 3, (2 * n, 2)), rng.uniform(-3, 3, 2 * n)
    e = ellipsect.Ellipses(centers=centers, radii=radii, angles=angles)
    a, b = e.take(np.arange(n)), e.take(np.arange(n, 2 * n))
    t_iou = best_of(3, lambda: ellipsect.iou(a, b, threads=1))
    exact = ellipsect.iou(a, b)

    def polygon(i, k):
        t = np.linspace(0, 2 * np.pi, k, endpoint=False)
        c, s = np.cos(angles[i]), np.sin(angles[i])
        x, y = radii[i, 0] * np.cos(t), radii[i, 1] * np.sin(t)
        return Polygon(np.column_stack([centers[i, 0] + c * x - s * y, centers[i, 1] + s * x + c * y]))

    print(f"## IoU of {n} ellipse pairs (one thread)")
    print("| method | time per pair | max abs IoU error | mean abs IoU error |")
    print("|---|---|---|---|")
    print(f"| ellipsect.iou (exact to ~1e-12) | {t_iou / n * 1e6:.2f} us | reference | reference |")
    for k in (64, 256):
        pa = [polygon(i, k) for i in range(n)]
        pb = [polygon(n + i, k) for i in range(n)]
        t0 = time.perf_counter()
        got = np.array([p.intersection(q).area / p.union(q).area for p, q in zip(pa, pb)])
        t = time.perf_counter() - t0
        err = np.abs(got - exact)
        print(f"| shapely, {k}-gons (intersection + union) | {t / n * 1e6:.1f} us | {err.max():.1e} | {err.mean():.1e} |")


def dask_throughput(n):
    import distributed

    import ellipsect.dask as ed

    rng = np.random.default_rng(3)
    pa, pb = ellipsoid_arrays(n, rng), ellipsoid_arrays(n, rng)
    def one_process(threads):
        return best_of(3, lambda: ellipsect.overlap(ellipsect.Ellipsoids(**pa), ellipsect.Ellipsoids(**pb),
                                                     threads=threads))

    one, every_core = one_process(1), one_process(0)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        def persisted(bodies):  # the arrays held by the workers, as a real cluster's data would be
            c, r, q = client.persist([bodies.centers, bodies.radii, bodies.orientation_values])
            return ed.Bodies(bodies.dim, c, r, bodies.orientation, q)

        a, b = persisted(ed.bodies(**pa, chunks=n // 8)), persisted(ed.bodies(**pb, chunks=n // 8))
        ed.overlap(ed.bodies(**ellipsoid_arrays(1000, rng)), ed.bodies(**ellipsoid_arrays(1000, rng))).compute()
        # One compute: the tasks are pure, so a second one could find their answers still held.
        start = time.perf_counter()
        ed.overlap(a, b).compute()
        cluster_s = time.perf_counter() - start
    print(f"## Dask, {n} ellipsoid pairs (bodies built per chunk; 8 chunks)")
    print("| run | pairs per second |")
    print("|---|---|")
    print(f"| one process, one thread (build + overlap) | {n / one / 1e6:.2f} M |")
    print(f"| one process, every core (build + overlap) | {n / every_core / 1e6:.2f} M |")
    print(f"| LocalCluster, 2 workers x 1 thread | {n / cluster_s / 1e6:.2f} M |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--pairs", type=int, default=1_000_000)
    parser.add_argument("--quick", action="store_true", help="small sizes, to check the script")
    args = parser.parse_args()
    n = 20_000 if args.quick else args.pairs
    print(f"SIMD target: {ellipsect.simd_target()}, cores: {os.cpu_count()}")
    overhead(n)
    iou_versus_shapely(200 if args.quick else 2000)
    dask_throughput(n)
