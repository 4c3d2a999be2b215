"""Enclosing ellipsoids and least-squares ellipses beside the Python code users reach for
(bench/RESULTS.md, section "Least-squares ellipses", subsection "Beside a numpy Khachiyan
loop and scikit-image"), run by hand:

    bash scripts/run.sh test  # or: the venv of python_test (build/venv), and python3-skimage
    taskset -c 1 build/venv/bin/python bench/bench_geometry.py [--quick] [--cap SECONDS] [--clouds K]

1. Enclosing: ellipsect.enclosing_ellipsoid(points, volume_gap=1e-3 and 1e-9) against the
   numpy Khachiyan baseline (khachiyan below: the mvee(points, tol) loop that circulates, at
   tol 1e-3, the value users pass, and 1e-6; its tol bounds the step of the weights, not the
   volume), on seeded clouds of 10^3, 10^4, 10^5 points (--quick: 10^3), 2D and 3D (the
   clouds of bench/bench_enclosing.cpp, drawn by numpy):
     box          uniform in the box of half extents (1, 2, 0.5)
     gaussian     normal, standard deviations (1, 2, 0.5), turned by a random rotation
     sphere_far   uniform on the ellipsoid of radii (1, 2, 0.5), 1e6 from the origin
     flat         uniform in a box 1e-3 thin along its last axis, turned
     near_circle  on the unit circle (sphere), radial noise 1e-6
   Time: best of 5 runs (3 over a second, 1 over ten); a baseline run past --cap seconds
   (default 60) is stopped, and that tolerance is not run on larger clouds of the kind.
   Volume: ln(volume / volume of ellipsect's answer at 1e-9), whose certified gap bounds its
   distance to the optimum. Outside: points with (p - c)^T A (p - c) > 1 in float64 (and the
   largest form), for ellipsect from its body as returned (center, axes, radii), each such
   point checked again in rationals (fractions), as the library's certificate decides.
2. Fits: ellipsect.fit_ellipsoid(points) against scikit-image's EllipseModel().estimate
   (Halir and Flusser's direct fit) on seeded 2D clouds whose generating ellipse is known,
   20 clouds each (--clouds; 5 with --quick):
     ellipse      radii (40, 15), a random pose about (320, 240), uniform in angle, normal
                  noise of 1% of the major radius per coordinate, 10^3 points
     near_circle  the unit circle about the origin, radial noise 0.01, 10^3 and 10^4 points
     arc30        a 30 degree arc of the circle of radius 100 about (320, 240), noise 1e-3 of
                  the radius per coordinate, 200 points
     hyperbola    both branches of x^2 / 4 - y^2 = 1 scaled by 10, |y| <= sinh 1.5, turned,
                  about (320, 240), noise 0.01, 400 points: no ellipse is right
   Time per fit (best of 3 per cloud, mean over clouds); far: the returned center off the
   generating one by more than 10% of its largest radius (on the hyperbola every returned
   ellipse); refused: ellipsect's status not converged, EllipseModel returning False,
   raising, or a radius that is not finite and positive (it writes NaN as 0); rms: the mean
   RMS orthogonal residual of the returned ellipses, by ellipsect.closest_point (exact
   point-to-ellipse distance); below: clouds where EllipseModel's residual is below
   ellipsect's (by 1e-9 relative, both answering); near where far: clouds where its ellipse
   is not far and ellipsect's converged one is.
"""

import argparse
import math
import os
import time
import warnings
from fractions import Fraction

import numpy as np

import ellipsect
from bench_python import best_of  # beside this file: the same timing

SCALE = np.array([1.0, 2.0, 0.5])


def rotation(dim, rng):
    q, r = np.linalg.qr(rng.normal(size=(dim, dim)))
    return q * np.sign(np.diag(r))


def enclosing_cloud(kind, dim, m):
    rng = np.random.default_rng(4848 + m + 7 * dim + len(kind))
    scale = SCALE[:dim]
    if kind == "box":
        return rng.uniform(-1, 1, (m, dim)) * scale
    if kind == "gaussian":
        return (rng.normal(size=(m, dim)) * scale) @ rotation(dim, rng).T
    if kind in ("sphere_far", "near_circle"):
        p = rng.normal(size=(m, dim))
        p /= np.linalg.norm(p, axis=1)[:, None]
        if kind == "sphere_far":
            return p * scale + 1e6
        return p * (1 + 1e-6 * rng.uniform(-1, 1, m))[:, None]
    if kind == "flat":
        p = rng.uniform(-1, 1, (m, dim))
        p[:, -1] *= 1e-3
        return p @ rotation(dim, rng).T
    raise ValueError(kind)


class Stopped(Exception):
    pass


def khachiyan(points, tol, deadline=None):
    """Khachiyan's minimum-volume enclosing ellipsoid as it circulates (mvee(points, tol)),
    in plain numpy. The copied code forms diag(u) and Q^T X^-1 Q as n-by-n matrices (80 GB at
    10^5 points); here the same products without them. Returns (c, A, iterations), the
    ellipsoid (x - c)^T A (x - c) <= 1."""
    n, d = points.shape
    Q = np.vstack([points.T, np.ones(n)])
    u = np.full(n, 1 / n)
    err, iterations = 1 + tol, 0
    while err > tol:
        X = (Q * u) @ Q.T
        M = np.sum(Q * (np.linalg.inv(X) @ Q), axis=0)  # diag(Q^T X^-1 Q)
        j = np.argmax(M)
        step = (M[j] - d - 1) / ((d + 1) * (M[j] - 1))
        new_u = (1 - step) * u
        new_u[j] += step
        err = np.linalg.norm(new_u - u)
        u = new_u
        iterations += 1
        if deadline is not None and time.perf_counter() > deadline:
            raise Stopped(iterations)
    c = points.T @ u
    A = np.linalg.inv(points.T @ (points * u[:, None]) - np.outer(c, c)) / d
    return c, A, iterations


def outside_of_body(points, body):
    """(points whose form exceeds 1 in float64, of those the ones that do in rationals): the
    form of the body as stored, sum_k (axes_k . (p - c))^2 / radii_k^2."""
    c, axes, radii = np.asarray(body.center), body.axes, body.radii
    y = ((points - c) @ axes) / radii
    rows = np.nonzero(np.sum(y * y, axis=1) > 1)[0]
    exact = 0
    for i in rows:
        d = [Fraction(float(p)) - Fraction(float(q)) for p, q in zip(points[i], c)]
        exact += sum(sum(Fraction(float(axes[j, k])) * d[j] for j in range(len(d))) ** 2 / Fraction(float(radii[k])) ** 2
                     for k in range(len(d))) > 1
    return len(rows), exact


def outside_of_form(points, c, A):
    """(points with (p - c)^T A (p - c) > 1 in float64, the largest form less 1)."""
    d = points - c
    q = np.einsum("ij,jk,ik->i", d, A, d)
    return int(np.count_nonzero(q > 1)), float(q.max() - 1)


def timed(f, cap=None):
    """(best time, last answer): best of 5 runs, 3 over a second, 1 over ten."""
    t = time.perf_counter()
    answer = f(None if cap is None else t + cap)
    first = time.perf_counter() - t
    k = 0 if first > 10 else 2 if first > 1 else 4
    return min(first, best_of(k, lambda: f(None))) if k else first, answer


def enclosing(sizes, cap):
    kinds = ("box", "gaussian", "sphere_far", "flat", "near_circle")
    tols = (1e-3, 1e-6)
    rows = {}
    for dim in (2, 3):
        stopped = {}  # (kind, tol) -> the size where the baseline was stopped
        for m in sizes:
            for kind in kinds:
                p = enclosing_cloud(kind, dim, m)
                row = {}
                for gap in (1e-3, 1e-9):
                    t, e = timed(lambda _, gap=gap: ellipsect.enclosing_ellipsoid(p, volume_gap=gap))
                    outside, exact = outside_of_body(p, e.body)
                    row[("ellipsect", gap)] = dict(time=t, iterations=e.iterations, status=e.status,
                                                   gap=e.volume_gap, log_volume=float(np.sum(np.log(e.body.radii))),
                                                   outside=outside, exact=exact)
                ref = row[("ellipsect", 1e-9)]["log_volume"]
                for tol in tols:
                    if (kind, tol) in stopped:
                        row[("numpy", tol)] = dict(skipped=stopped[(kind, tol)])
                        continue
                    try:
                        t, (c, A, its) = timed(lambda deadline, tol=tol: khachiyan(p, tol, deadline), cap)
                    except Stopped as s:
                        stopped[(kind, tol)] = m
                        row[("numpy", tol)] = dict(stopped=s.args[0])
                        continue
                    except np.linalg.LinAlgError as error:
                        row[("numpy", tol)] = dict(failed=str(error))
                        continue
                    sign, logdet = np.linalg.slogdet(A)
                    outside, worst = outside_of_form(p, c, A)
                    row[("numpy", tol)] = dict(time=t, iterations=its,
                                               log_volume=-0.5 * logdet if sign > 0 else math.nan,
                                               outside=outside, worst=worst)
                for r in row.values():
                    if "log_volume" in r:
                        r["excess"] = r["log_volume"] - ref
                rows[(dim, m, kind)] = row
    return rows


def ms(seconds):
    v = seconds * 1e3
    return f"{v:,.0f}" if v >= 100 else f"{v:.1f}" if v >= 1 else f"{v:.2f}"


def time_cell(r, cap):
    if "skipped" in r:
        return f"not run (stopped at {r['skipped']:,})"
    if "stopped" in r:
        return f"> {cap:.0f} s (stopped, {r['stopped']:,} it.)"
    if "failed" in r:
        return f"failed: {r['failed']}"
    return f"{ms(r['time'])} ({r['iterations']:,})"


def accuracy_cell(r, certified=False):
    if "time" not in r:
        return "—"
    if "exact" in r:
        outside = f"{r['outside']:,}" + (f" (exact {r['exact']})" if r["outside"] else "")
    else:
        outside = f"{r['outside']:,}" + (f", max 1{r['worst']:+.1e}" if r["outside"] else "")
    if certified:
        return f"{r['gap']:.1e} / {outside}"
    if math.isnan(r["excess"]):  # det A <= 0: no ellipsoid
        return f"A not positive definite / {outside}"
    return f"{r['excess']:+.1e} / {outside}"


def ratio(a, b):
    v = a / b
    return f"{v:,.0f}x" if v >= 10 else f"{v:.2g}x"


def print_enclosing(rows, sizes, cap):
    methods = (("ellipsect", 1e-3), ("ellipsect", 1e-9), ("numpy", 1e-3), ("numpy", 1e-6))
    for dim in (2, 3):
        print(f"## Enclosing, {dim}D: milliseconds (iterations)")
        print("| cloud | points | ellipsect 1e-3 | ellipsect 1e-9 | numpy tol 1e-3 | numpy tol 1e-6 "
              "| numpy 1e-3 / ellipsect 1e-3 | numpy 1e-3 / ellipsect 1e-9 |")
        print("|---|---|---|---|---|---|---|---|")
        for (d, m, kind), row in rows.items():
            if d != dim:
                continue
            base = row[("numpy", 1e-3)]
            ratios = [ratio(base["time"], row[("ellipsect", g)]["time"]) if "time" in base else "—"
                      for g in (1e-3, 1e-9)]
            print(f"| {kind} | {m:,} | " + " | ".join(time_cell(row[k], cap) for k in methods) + " | "
                  + " | ".join(ratios) + " |")
        print()
        print(f"## Enclosing, {dim}D: ln(volume / ellipsect 1e-9) / points outside "
              "(ellipsect 1e-9: its certified gap / points outside)")
        print("| cloud | points | ellipsect 1e-3 | ellipsect 1e-9 | numpy tol 1e-3 | numpy tol 1e-6 | ellipsect status |")
        print("|---|---|---|---|---|---|---|")
        for (d, m, kind), row in rows.items():
            if d != dim:
                continue
            status = sorted({row[("ellipsect", g)]["status"] for g in (1e-3, 1e-9)})
            print(f"| {kind} | {m:,} | {accuracy_cell(row[('ellipsect', 1e-3)])} | "
                  f"{accuracy_cell(row[('ellipsect', 1e-9)], certified=True)} | "
                  f"{accuracy_cell(row[('numpy', 1e-3)])} | {accuracy_cell(row[('numpy', 1e-6)])} | "
                  f"{', '.join(status)} |")
        print()
    big = [row for (d, m, kind), row in rows.items() if m == max(sizes)]
    for g in (1e-3, 1e-9):
        ratios = [r[("numpy", 1e-3)]["time"] / r[("ellipsect", g)]["time"] for r in big if "time" in r[("numpy", 1e-3)]]
        if ratios:
            print(f"numpy tol 1e-3 over ellipsect {g:.0e} on {max(sizes):,} points: {ratio(min(ratios), 1)} to "
                  f"{ratio(max(ratios), 1)} ({len(ratios)} of {len(big)} clouds measured)")
    bad = [(d, m, kind, g, r[("ellipsect", g)]["status"], r[("ellipsect", g)]["exact"])
           for (d, m, kind), r in rows.items() for g in (1e-3, 1e-9)
           if r[("ellipsect", g)]["status"] != "optimal" or r[("ellipsect", g)]["exact"]]
    print(f"ellipsect rows not optimal or with a point outside in rationals: {bad if bad else 'none'}")
    print()


def fit_case(kind, m, seed):
    """(points, generating center, its largest radius, whether an ellipse generated them)."""
    rng = np.random.default_rng(4848 + 1000 * seed + m + len(kind))
    center = np.array([320.0, 240.0])
    R = rotation(2, rng)
    if kind == "ellipse":
        t = rng.uniform(0, 2 * np.pi, m)
        p = center + np.column_stack([40 * np.cos(t), 15 * np.sin(t)]) @ R.T + 0.4 * rng.normal(size=(m, 2))
        return p, center, 40.0, True
    if kind == "near_circle":
        t = rng.uniform(0, 2 * np.pi, m)
        return (1 + 0.01 * rng.normal(size=m))[:, None] * np.column_stack([np.cos(t), np.sin(t)]), np.zeros(2), 1.0, True
    if kind == "arc30":
        t = 2 * np.pi * seed / 20 + np.pi / 6 * rng.uniform(0, 1, m)
        p = center + 100 * np.column_stack([np.cos(t), np.sin(t)]) + 0.1 * rng.normal(size=(m, 2))
        return p, center, 100.0, True
    if kind == "hyperbola":
        s = rng.uniform(-1.5, 1.5, m)
        branch = np.where(np.arange(m) % 2, -1.0, 1.0)
        p = center + 10 * np.column_stack([branch * 2 * np.cosh(s), np.sinh(s)]) @ R.T + 0.01 * rng.normal(size=(m, 2))
        return p, center, 10.0, False
    raise ValueError(kind)


def rms_of(body, points):
    d = np.array([ellipsect.closest_point(body, p).signed_distance for p in points])
    return float(np.sqrt(np.mean(d * d)))


def skimage_fit(points):
    from skimage.measure import EllipseModel

    model = EllipseModel()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            ok = model.estimate(points)
        except Exception:  # noqa: BLE001 (a refusal, whatever it raises)
            return None
    if not ok or model.params is None:
        return None
    xc, yc, a, b, theta = model.params
    if not all(math.isfinite(v) for v in model.params) or not (a > 0 and b > 0):
        return None
    try:
        return ellipsect.Ellipse(center=[xc, yc], radii=[a, b], angle=theta)
    except Exception:  # noqa: BLE001 (radii the library does not take)
        return None


def ellipsect_fit(points):
    f = ellipsect.fit_ellipsoid(points)
    return f.body if f.status == "converged" else None


def fits(clouds_each):
    cases = (("ellipse", 1000), ("near_circle", 1000), ("near_circle", 10000), ("arc30", 200), ("hyperbola", 400))
    out = []
    for kind, m in cases:
        stats = {name: dict(time=0.0, far=0, refused=0, rms=[]) for name in ("ellipsect", "skimage")}
        below = near_where_far = 0
        statuses = {}
        for seed in range(clouds_each):
            p, center, size, is_ellipse = fit_case(kind, m, seed)
            answers = {}
            for name, method in (("ellipsect", ellipsect_fit), ("skimage", skimage_fit)):
                stats[name]["time"] += best_of(3, lambda: method(p))
                e = method(p)
                answers[name] = e
                if e is None:
                    stats[name]["refused"] += 1
                    continue
                answers[name + "_far"] = not is_ellipse or np.linalg.norm(np.asarray(e.center) - center) > 0.1 * size
                stats[name]["far"] += answers[name + "_far"]
                answers[name + "_rms"] = rms_of(e, p)
                stats[name]["rms"].append(answers[name + "_rms"])
            status = ellipsect.fit_ellipsoid(p).status
            statuses[status] = statuses.get(status, 0) + 1
            if answers["ellipsect"] is not None and answers["skimage"] is not None:
                below += answers["skimage_rms"] < answers["ellipsect_rms"] * (1 - 1e-9)
            if answers["skimage"] is not None and not answers["skimage_far"] and answers["ellipsect"] is not None \
                    and answers["ellipsect_far"]:
                near_where_far += 1
        out.append((kind, m, clouds_each, stats, below, near_where_far, statuses))
    return out


def print_fits(rows):
    import skimage

    print(f"## Fits: ellipsect.fit_ellipsoid beside scikit-image {skimage.__version__} EllipseModel")
    print("| cloud | points | clouds | ellipsect µs | skimage µs | ellipsect far / refused | skimage far / refused "
          "| ellipsect rms | skimage rms | skimage below ellipsect | skimage near where ellipsect far "
          "| ellipsect statuses |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for kind, m, n, stats, below, near_where_far, statuses in rows:
        e, s = stats["ellipsect"], stats["skimage"]
        rms = [f"{np.mean(x['rms']):.8g}" if x["rms"] else "—" for x in (e, s)]
        print(f"| {kind} | {m:,} | {n} | {e['time'] / n * 1e6:,.0f} | {s['time'] / n * 1e6:,.0f} | "
              f"{e['far']} / {e['refused']} | {s['far']} / {s['refused']} | {rms[0]} | {rms[1]} | {below} | "
              f"{near_where_far} | {', '.join(f'{k} {v}' for k, v in sorted(statuses.items()))} |")
    print()


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true", help="10^3 points only, to check the script")
    parser.add_argument("--cap", type=float, default=60, help="seconds a baseline run may take before it is stopped")
    parser.add_argument("--clouds", type=int, default=20, help="fit clouds per kind")
    args = parser.parse_args()
    sizes = (1000,) if args.quick else (1000, 10_000, 100_000)
    print(f"SIMD target: {ellipsect.simd_target()}, cores: {os.cpu_count()} "
          f"(usable: {len(os.sched_getaffinity(0))}), numpy {np.__version__}")
    start = time.perf_counter()
    print_enclosing(enclosing(sizes, args.cap), sizes, args.cap)
    print_fits(fits(5 if args.quick else args.clouds))
    print(f"total {time.perf_counter() - start:.0f} s")
