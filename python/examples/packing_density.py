"""Jammed packing fraction against aspect ratio (docs/packing.md): ellipsect.jam_packing over a
list of shapes and seeds, a table (JSON) and the plot of phi_J against the aspect ratio.

    build/venv/bin/python python/examples/packing_density.py [--dim 3] [--n 200] [--seeds 1]
        [--aspects 1,1.1,1.25,1.5,2,2.5,3] [--kinds prolate,oblate] [--schedule 0:0.1,10:0.01] [--pressure 1e4] [--contact-gap 1e-3]
        [--initial-density 0.2] [--json results.json] [--plot packing_density.png] [--picture packing.png]

3D: prolate spheroids (alpha, 1, 1) and, with --kinds prolate,oblate, oblate ones (1, 1, 1 / alpha);
2D: ellipses
(alpha, 1), half of them scaled by 1.4 (bidisperse, so that disks do not crystallize).
--picture draws the packing of the first shape and seed (3D: the bodies whose centers lie in
a slab a largest radius thick across the middle of the box, seen along z), with its contacts.
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Dict, List, Sequence, Tuple

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from matplotlib import pyplot as plt  # noqa: E402

import ellipsect  # noqa: E402


def shapes(dim: int, n: int, alpha: float, oblate: bool) -> np.ndarray:
    """n bodies' radii: a spheroid (alpha, 1, 1) or (1, 1, 1 / alpha) in 3D; in 2D an
    ellipse (alpha, 1), every second one scaled by 1.4."""
    if dim == 3:
        one = [1.0, 1.0, 1.0 / alpha] if oblate else [alpha, 1.0, 1.0]
        return np.tile(one, (n, 1))
    scale = np.where(np.arange(n) % 2 == 1, 1.4, 1.0)
    return np.column_stack([alpha * scale, scale])


def run(dim: int, n: int, alphas: Sequence[float], seeds: Sequence[int], schedule: List[Tuple[float, float]],
        pressure: float, contact_gap: float, oblate: bool = False, initial_density: float = 0.2) -> List[Dict[str, float]]:
    """One row per (alpha, seed): density, reduced pressure, mean contacts without rattlers,
    collisions and seconds; every packing checked (no overlap, no failed prediction)."""
    rows = []
    global first_packing
    for alpha in alphas:
        for seed in seeds:
            start = time.perf_counter()
            p = ellipsect.jam_packing(shapes(dim, n, alpha, oblate), seed=seed, schedule=schedule, pressure=pressure,
                                      contact_gap=contact_gap, initial_density=initial_density)
            seconds = time.perf_counter() - start
            if first_packing is None:
                first_packing = p
            if p.overlapping or p.predictions_overlapping or p.predictions_stopped or p.status != "jammed":
                raise RuntimeError(f"alpha {alpha} seed {seed}: {p.status}, overlapping {p.overlapping}, "
                                   f"predictions {p.predictions_overlapping} / {p.predictions_stopped}")
            rows.append({"alpha": alpha, "oblate": oblate, "seed": seed, "density": p.density,
                         "pressure": p.pressure, "contacts": p.mean_contacts_without_rattlers,
                         "rattlers": p.rattlers, "collisions": p.collisions, "seconds": seconds})
            print(f"alpha {alpha:5.3g}{' oblate' if oblate else ''} seed {seed}: phi {p.density:.4f} "
                  f"Z {p.mean_contacts_without_rattlers:.2f} ({p.rattlers} rattlers), p {p.pressure:.3g}, "
                  f"{p.collisions} collisions, {seconds:.0f} s", flush=True)
    return rows


first_packing = None


def picture(p, dim: int, path: str) -> None:
    """The packing p in its box, contacts as segments between centers (nearest images)."""
    import ellipsect.plot as ep

    keep = np.ones(len(p.radii), bool)
    if dim == 3:
        keep = np.abs(p.centers[:, 2] - p.box[2] / 2) < p.radii.max()
    kind = ellipsect.Ellipses if dim == 2 else ellipsect.Ellipsoids
    fig, ax = plt.subplots(figsize=(6, 6))
    ep.bodies(ax, kind(centers=p.centers[keep], radii=p.radii[keep], rotations=p.axes[keep]))
    for i, j, *image in p.contacts:
        if keep[i] and keep[j]:
            a, b = p.centers[i], p.centers[j] + np.asarray(image) * p.box
            ax.plot([a[0], b[0]], [a[1], b[1]], color="crimson", lw=0.8)
    ax.add_patch(plt.Rectangle((0, 0), p.box[0], p.box[1], fill=False, ls="--", color="gray"))
    ax.set_aspect("equal")
    ax.set_title(f"phi = {p.density:.4f}, {p.mean_contacts_without_rattlers:.2f} contacts per body" +
                 (" (slab across z)" if dim == 3 else ""))
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot(rows: List[Dict[str, float]], dim: int, path: str, title: str) -> None:
    fig, ax = plt.subplots(figsize=(6, 4))
    for oblate, marker, label in ((False, "o", "prolate (alpha, 1, 1)" if dim == 3 else "ellipses, bidisperse"),
                                  (True, "s", "oblate (1, 1, 1 / alpha)")):
        mine = [r for r in rows if bool(r["oblate"]) == oblate]
        if not mine:
            continue
        alphas = sorted({r["alpha"] for r in mine})
        mean = [np.mean([r["density"] for r in mine if r["alpha"] == a]) for a in alphas]
        ax.plot(alphas, mean, marker=marker, label=label)
    ax.set_xlabel("aspect ratio alpha")
    ax.set_ylabel("jammed packing fraction")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dim", type=int, default=3, choices=(2, 3))
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--seeds", default="1")
    parser.add_argument("--aspects", default="1,1.1,1.25,1.5,2,2.5,3")
    parser.add_argument("--kinds", default="prolate", help="3D: prolate, oblate or prolate,oblate")
    parser.add_argument("--schedule", default="0:0.1,10:0.01", help="from_pressure:rate,...")
    parser.add_argument("--pressure", type=float, default=1e4)
    parser.add_argument("--contact-gap", type=float, default=1e-3)
    parser.add_argument("--initial-density", type=float, default=0.2,
                        help="of the random start (lower it where few long bodies do not fit the box)")
    parser.add_argument("--json")
    parser.add_argument("--plot")
    parser.add_argument("--picture")
    a = parser.parse_args()
    schedule = [(float(x.split(":")[0]), float(x.split(":")[1])) for x in a.schedule.split(",")]
    alphas = [float(x) for x in a.aspects.split(",")]
    seeds = [int(x) for x in a.seeds.split(",")]
    rows = []
    for kind in a.kinds.split(","):
        rows += run(a.dim, a.n, alphas, seeds, schedule, a.pressure, a.contact_gap, oblate=kind == "oblate",
                    initial_density=a.initial_density)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"dim": a.dim, "n": a.n, "schedule": schedule, "pressure": a.pressure,
                       "contact_gap": a.contact_gap, "rows": rows}, f, indent=1)
    if a.plot:
        plot(rows, a.dim, a.plot, f"{a.n} bodies, growth {a.schedule}, jammed at p = {a.pressure:g}")
    if a.picture:
        picture(first_packing, a.dim, a.picture)


if __name__ == "__main__":
    main()
