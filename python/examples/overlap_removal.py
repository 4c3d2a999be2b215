"""Push overlapping ellipses apart by gradient descent on their total penetration
(docs/gradient-examples.md).

    build/venv/bin/python python/examples/overlap_removal.py [--n 1000] [--seed 1] [--omega 1.5] [--out picture.png]

Only the centers c_i move (radii and angles stay). With d_ij the signed distance of an
overlapping pair (negative: minus the penetration depth) and a small margin m > 0, the loss is

    L(c) = 1/2 sum over overlapping pairs (i, j) of (m - d_ij)^2,

its gradient dL/dc_i = -sum_j (m - d_ij) dd_ij/dc_i with dd_ij/dc_i from
ellipsect.signed_distance_gradient (a unit vector: the translation derivative of the depth).
One pair alone is resolved to first order by moving each body (m - d_ij) / 2 along it; a body
in k_i overlaps takes the mean of its pairs' moves, over-relaxed by omega:

    c_i <- c_i - omega / (2 k_i) dL/dc_i

(each pair's move is the least-norm step that zeroes its linearized m - d_ij; averaging them
per body is a Jacobi-style, Cimmino, iteration).

The pairs are found again (ellipsect.overlapping_pairs) before every step; the loop ends when
there are none and raises RuntimeError when max_iterations steps leave some.
"""

from __future__ import annotations

import argparse
import io
import time
from typing import Optional, Tuple

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from matplotlib import pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402 (matplotlib's own dependency)

import ellipsect  # noqa: E402
import ellipsect.plot as ep  # noqa: E402


def random_scene(rng: np.random.Generator, n: int, fill: float = 0.5) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """n random ellipses (centers (n, 2), radii (n, 2), angles (n,)): minor radius in [0.5, 1],
    aspect ratio in [1, 4], centers uniform in a square whose area is the ellipses' total
    area over `fill` (0.5: about 1.1 overlapping pairs per ellipse)."""
    minor = rng.uniform(0.5, 1.0, n)
    radii = np.column_stack([minor * rng.uniform(1.0, 4.0, n), minor])
    side = np.sqrt(np.pi * radii.prod(axis=1).sum() / fill)
    return rng.uniform(0.0, side, (n, 2)), radii, rng.uniform(-np.pi, np.pi, n)


def remove_overlaps(centers: np.ndarray, radii: np.ndarray, angles: np.ndarray, *, max_iterations: int = 1000,
                    omega: float = 1.5, margin: Optional[float] = None) -> Tuple[np.ndarray, int]:
    """Centers at which no two of the ellipses overlap, and the number of steps taken.

    margin: the separation each step aims for (default 5% of the smallest radius), so that
    pairs end apart rather than touching. Raises RuntimeError when max_iterations steps leave
    overlapping pairs, or when a gradient is not finite.
    """
    centers = np.array(centers, dtype=float)
    margin = 0.05 * float(np.min(radii)) if margin is None else margin
    for iteration in range(max_iterations + 1):
        bodies = ellipsect.Ellipses(centers, radii, angles=angles)
        pairs = ellipsect.overlapping_pairs(bodies)
        if len(pairs) == 0:
            return centers, iteration
        if iteration == max_iterations:
            break
        g = ellipsect.signed_distance_gradient(bodies.take(pairs[:, 0]), bodies.take(pairs[:, 1]))
        bad = ~(np.isfinite(g.center_a).all(axis=1) & np.isfinite(g.center_b).all(axis=1))
        if bad.any():
            raise RuntimeError(f"step {iteration}: non-finite signed distance gradient for pairs {pairs[bad].tolist()}")
        # -dL/dc per pair and body: (m - d) dd/dc; each body sums its pairs' and divides by 2 k.
        push = (margin - g.value)[:, None]
        descent = np.zeros_like(centers)
        np.add.at(descent, pairs[:, 0], push * g.center_a)
        np.add.at(descent, pairs[:, 1], push * g.center_b)
        count = np.bincount(pairs.ravel(), minlength=len(centers))
        centers += omega * descent / (2 * np.maximum(count, 1))[:, None]
    raise RuntimeError(f"{len(pairs)} pairs still overlap after {max_iterations} steps")


def save_png(fig: plt.Figure, path: str) -> None:
    """The figure at 100 dpi as a 32-colour PNG (a fraction of the bytes of matplotlib's RGBA)."""
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=100)
    plt.close(fig)
    Image.open(buffer).convert("RGB").quantize(colors=32).save(path, optimize=True)


def draw(before: np.ndarray, after: np.ndarray, radii: np.ndarray, angles: np.ndarray, path: str) -> None:
    """Before (overlapping bodies in red) and after, side by side."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 5.3), sharex=True, sharey=True)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.94, wspace=0.04)
    start = ellipsect.Ellipses(before, radii, angles=angles)
    hit = np.zeros(len(before), dtype=bool)
    hit[ellipsect.overlapping_pairs(start).ravel()] = True
    ep.bodies(axes[0], start.take(np.flatnonzero(~hit)), color="0.45", linewidth=0.5)
    ep.bodies(axes[0], start.take(np.flatnonzero(hit)), color="crimson", linewidth=0.5)
    ep.bodies(axes[1], ellipsect.Ellipses(after, radii, angles=angles), color="0.2", linewidth=0.5)
    axes[0].set_title(f"before: {hit.sum()} of {len(before)} ellipses overlap")
    axes[1].set_title("after: no overlaps")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
    save_png(fig, path)


def main(argv: Optional[list] = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1000, help="number of ellipses")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--fill", type=float, default=0.5, help="total ellipse area over the square's")
    parser.add_argument("--omega", type=float, default=1.5, help="over-relaxation of the Jacobi step")
    parser.add_argument("--max-iterations", type=int, default=1000)
    parser.add_argument("--out", help="PNG of the bodies before and after")
    args = parser.parse_args(argv)

    centers, radii, angles = random_scene(np.random.default_rng(args.seed), args.n, args.fill)
    initial = len(ellipsect.overlapping_pairs(ellipsect.Ellipses(centers, radii, angles=angles)))
    start = time.perf_counter()
    moved, iterations = remove_overlaps(centers, radii, angles, max_iterations=args.max_iterations,
                                        omega=args.omega)
    elapsed = time.perf_counter() - start
    left = ellipsect.overlapping_pairs(ellipsect.Ellipses(moved, radii, angles=angles))
    if len(left):
        raise SystemExit(f"{len(left)} pairs still overlap")
    shift = np.linalg.norm(moved - centers, axis=1)
    print(f"{args.n} ellipses, {initial} overlapping pairs: none left after {iterations} steps in {elapsed:.3f} s; "
          f"centers moved {shift.mean():.3f} on average, at most {shift.max():.3f} "
          f"(largest radius {radii.max():.3f})")
    if args.out:
        draw(centers, moved, radii, angles, args.out)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
