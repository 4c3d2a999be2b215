"""The exact IoU of two ellipses as a loss: Gaussian surrogates against it, and a fit of an
ellipse to a target to 1 - IoU <= 1e-12 with its gradient (docs/gradient-examples.md).

    build/venv/bin/python python/examples/iou_loss.py [--n 2000] [--seed 1] [--trials 100] [--out picture.png]

Surrogates. An ellipse (center c, radii r, rotation R) is replaced by the Gaussian with the
mean and covariance of the uniform distribution over it: N(c, S), S = R diag(r^2) R^T / 4.
ProbIoU (Llerena et al. 2021): with S = (S_a + S_b) / 2 and dc = c_b - c_a, the Bhattacharyya
distance B = dc^T S^-1 dc / 8 + ln(det S / sqrt(det S_a det S_b)) / 2, the Hellinger distance
H = sqrt(1 - exp(-B)), ProbIoU = 1 - H. KLD (Yang et al. 2021, the loss 1 - 1 / (tau + f(D))
with f = ln(1 + D), tau = 1): D = KL(N_b || N_a) = dc^T S_a^-1 dc / 2 + tr(S_a^-1 S_b) / 2
+ ln(det S_a / det S_b) / 2 - 1, similarity 1 / (1 + ln(1 + D)); a is the prediction, b the target.

Fit. The ellipse is the image c + M u of the unit disk |u| <= 1 with M = R diag(r) R^T
symmetric positive definite; the parameters are y = (c_x, c_y, M_11, M_12, M_22), which unlike
(angle, radii) are regular at circles. f(y) = 1 - IoU(y, target) and its gradient come from
ellipsect.iou_gradient (by center, angle and radii, carried to M below). Near the optimum y*,
f(y) = N(y - y*) + O(|y - y*|^2) with N positively homogeneous of degree 1 (the symmetric
difference is first order in the boundary's displacement), so Euler's identity gives
grad f(y) . (y - y*) = f(y) + O(|y - y*|^2): every evaluated gradient is one linear equation for
y*. Each iteration evaluates f at y and at y +- rho e_k (rho = f times the current mean radius,
of the order of the distance to y*) and solves the 11 equations for y* by least squares (error
O(|y - y*|^2): quadratic convergence). Where that point does not lower f (far from the
optimum), the iteration takes a gradient step of Polyak's length f / |grad f|^2 (the optimal
value 0 is known), halved until f decreases.
"""

from __future__ import annotations

import argparse
import time
from typing import Dict, List, NamedTuple, Optional, Tuple

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from matplotlib import pyplot as plt  # noqa: E402

import ellipsect  # noqa: E402
import ellipsect.plot as ep  # noqa: E402

# The smallest nonzero tolerance: ellipses closer than about it are 'equal' (IoU 1, NaN
# gradient); with the default 1e-12 the last steps of the fit would read 1 - IoU as 0.
OPTIONS = ellipsect.Options(tolerance=1e-14)


# --- Gaussian surrogates ---------------------------------------------------------------------

def gaussians(centers: np.ndarray, radii: np.ndarray, angles: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Mean (n, 2) and covariance (n, 2, 2) of the uniform distribution over each ellipse."""
    c, s = np.cos(angles), np.sin(angles)
    rotations = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
    return centers, rotations @ (radii[:, :, None] ** 2 / 4 * np.swapaxes(rotations, 1, 2))


def probiou(ma: np.ndarray, sa: np.ndarray, mb: np.ndarray, sb: np.ndarray) -> np.ndarray:
    """1 - Hellinger distance of the Gaussians, from their Bhattacharyya distance."""
    s = (sa + sb) / 2
    dc = mb - ma
    b = (np.einsum("ni,nij,nj->n", dc, np.linalg.inv(s), dc) / 8
         + np.log(np.linalg.det(s) / np.sqrt(np.linalg.det(sa) * np.linalg.det(sb))) / 2)
    return 1 - np.sqrt(np.maximum(1 - np.exp(-b), 0))


def kld_similarity(ma: np.ndarray, sa: np.ndarray, mb: np.ndarray, sb: np.ndarray) -> np.ndarray:
    """1 / (1 + ln(1 + KL(N_b || N_a))): a the prediction, b the target."""
    inv = np.linalg.inv(sa)
    dc = mb - ma
    d = (np.einsum("ni,nij,nj->n", dc, inv, dc) / 2 + np.trace(inv @ sb, axis1=1, axis2=2) / 2
         + np.log(np.linalg.det(sa) / np.linalg.det(sb)) / 2 - 1)
    return 1 / (1 + np.log1p(np.maximum(d, 0)))


def random_ellipses(rng: np.random.Generator, n: int, spread: float = 2.0) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centers uniform in [-spread, spread]^2, minor radius in [0.5, 1], aspect in [1, 4], any angle."""
    minor = rng.uniform(0.5, 1.0, n)
    radii = np.column_stack([minor * rng.uniform(1.0, 4.0, n), minor])
    return rng.uniform(-spread, spread, (n, 2)), radii, rng.uniform(-np.pi, np.pi, n)


def near_concentric(rng: np.random.Generator, a: Tuple[np.ndarray, np.ndarray, np.ndarray],
                    spread: float = 0.05) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each ellipse of a perturbed: center by `spread` times its mean radius per coordinate,
    radii by a factor exp(spread N(0, 1)) each, angle by spread N(0, 1) (Gaussian draws)."""
    centers, radii, angles = a
    n = len(centers)
    size = np.sqrt(radii.prod(axis=1))[:, None]
    return (centers + spread * size * rng.normal(size=(n, 2)), radii * np.exp(spread * rng.normal(size=(n, 2))),
            angles + spread * rng.normal(size=n))


def measures(a: Tuple[np.ndarray, ...], b: Tuple[np.ndarray, ...]) -> Dict[str, np.ndarray]:
    """Exact IoU (ellipsect.iou), ProbIoU and KLD similarity of each pair (a[i], b[i])."""
    exact = ellipsect.iou(ellipsect.Ellipses(a[0], a[1], angles=a[2]), ellipsect.Ellipses(b[0], b[1], angles=b[2]))
    ga, gb = gaussians(*a), gaussians(*b)
    return {"exact": exact, "probiou": probiou(*ga, *gb), "kld": kld_similarity(*ga, *gb)}


def surrogate_table(rng: np.random.Generator, n: int) -> Dict[str, Dict[str, np.ndarray]]:
    """The three measures on n random pairs, on those of them that overlap, and on n
    near-concentric pairs, by category."""
    a = random_ellipses(rng, n)
    table = {"random": measures(a, random_ellipses(rng, n))}
    meeting = table["random"]["exact"] > 0
    table["random, overlapping"] = {k: v[meeting] for k, v in table["random"].items()}
    a = random_ellipses(rng, n)
    table["near-concentric"] = measures(a, near_concentric(rng, a))
    return table


def markdown(table: Dict[str, Dict[str, np.ndarray]]) -> str:
    """Mean and max |surrogate - exact IoU| per category, as a markdown table."""
    lines = ["| pairs | n | mean IoU | ProbIoU mean abs. error | ProbIoU max | KLD mean abs. error | KLD max |",
             "|---|---|---|---|---|---|---|"]
    for name, m in table.items():
        errors = [np.abs(m[k] - m["exact"]) for k in ("probiou", "kld")]
        cells = [f"{e.mean():.4f} | {e.max():.4f}" for e in errors]
        lines.append(f"| {name} | {len(m['exact'])} | {m['exact'].mean():.4f} | {cells[0]} | {cells[1]} |")
    return "\n".join(lines)


# --- Fit by the exact IoU ------------------------------------------------------------------

class Fit(NamedTuple):
    ellipse: ellipsect.Ellipse  # the fitted ellipse
    loss: float  # 1 - IoU with the target at the end
    iterations: int
    evaluations: int  # IoU-and-gradient evaluations
    path: List[np.ndarray]  # y at the start and after each iteration
    losses: List[float]  # 1 - IoU at each of them
    euler: List[bool]  # per iteration: the Euler-identity step (True) or a gradient step


def to_parameters(e: ellipsect.Ellipse) -> np.ndarray:
    """y = (c_x, c_y, M_11, M_12, M_22), M = R diag(r) R^T."""
    m = (e.axes * e.radii) @ e.axes.T
    return np.array([e.center[0], e.center[1], m[0, 0], m[0, 1], m[1, 1]])


def _shapes(y: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Radii (n, 2), major first, and angles (n,) of the major axis, from rows y."""
    m = np.stack([np.stack([y[:, 2], y[:, 3]], -1), np.stack([y[:, 3], y[:, 4]], -1)], -2)
    values, vectors = np.linalg.eigh(m)  # ascending: column 1 is the major axis
    return values[:, ::-1], np.arctan2(vectors[:, 1, 1], vectors[:, 0, 1])


def to_ellipse(y: np.ndarray) -> ellipsect.Ellipse:
    radii, angles = _shapes(y[None])
    return ellipsect.Ellipse(y[:2], radii[0], angle=angles[0])


def loss_and_gradient(y: np.ndarray, target: ellipsect.Ellipses) -> Tuple[np.ndarray, np.ndarray]:
    """f = 1 - IoU (n,) and df/dy (n, 5) for rows y against a one-ellipse batch; rows whose M is
    not positive definite (or beyond the library's aspect ratio 1e8) get f = inf, gradient NaN.

    With R the rotation of angle t and G' = [[f_a, f_t / (2 (a - b))], [., f_b]] (from
    dM = R [[da, (a - b) dt], [(a - b) dt, db]] R^T), df/dM = R G' R^T; M_12 counts twice."""
    radii, angles = _shapes(y)
    valid = radii[:, 1] > 1e-8 * radii[:, 0]
    f = np.full(len(y), np.inf)
    grad = np.full((len(y), 5), np.nan)
    g = ellipsect.iou_gradient(ellipsect.Ellipses(y[valid, :2], radii[valid], angles=angles[valid]),
                               target.take(np.zeros(valid.sum(), dtype=np.int64)), options=OPTIONS)
    a, b = radii[valid, 0], radii[valid, 1]
    twist = np.divide(-g.orientation_a, 2 * (a - b), out=np.zeros_like(a), where=a > b)  # f_t = 0 at a circle
    c, s = np.cos(angles[valid]), np.sin(angles[valid])
    r = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
    inner = np.zeros((len(a), 2, 2))
    inner[:, 0, 0], inner[:, 1, 1] = -g.radii_a[:, 0], -g.radii_a[:, 1]
    inner[:, 0, 1] = inner[:, 1, 0] = twist
    dm = r @ inner @ np.swapaxes(r, 1, 2)
    f[valid] = 1 - g.value
    grad[valid] = np.column_stack([-g.center_a, dm[:, 0, 0], 2 * dm[:, 0, 1], dm[:, 1, 1]])
    return f, grad


def fit_ellipse(target: ellipsect.Ellipse, start: ellipsect.Ellipse, *, tolerance: float = 1e-12,
                max_iterations: int = 100, euler_steps: bool = True) -> Fit:
    """Minimizes 1 - IoU(ellipse, target) from `start` (which must overlap the target) until it
    is <= tolerance; raises RuntimeError after max_iterations iterations, or when a gradient step
    finds no decrease. euler_steps=False takes only the gradient steps (for comparison)."""
    goal = ellipsect.Ellipses(np.array([target.center]), np.array([target.radii]), rotations=np.array([target.axes]))
    y = to_parameters(start)
    (f,), (g,) = loss_and_gradient(y[None], goal)
    if not f < 1:
        raise ValueError("start does not overlap the target")
    path, losses, evaluations = [y], [f], 1
    euler: List[bool] = []
    while f > tolerance:
        if len(euler) == max_iterations:
            raise RuntimeError(f"1 - IoU = {f:.3e} > {tolerance:g} after {max_iterations} iterations")
        took_euler = False
        if euler_steps:
            rho = f * np.sqrt(y[2] * y[4] - y[3] ** 2)  # f times sqrt(det M) = sqrt(a b)
            points = y + np.vstack([np.zeros(5), rho * np.eye(5), -rho * np.eye(5)])
            fs, gs = loss_and_gradient(points, goal)
            use = np.isfinite(gs).all(axis=1) & (fs < 1)  # apart, IoU 0 has gradient 0: no equation
            guess, *_ = np.linalg.lstsq(gs[use], np.einsum("ij,ij->i", gs[use], points[use]) - fs[use], rcond=None)
            (f_guess,), (g_guess,) = loss_and_gradient(guess[None], goal)
            evaluations += len(points) + 1
            if f_guess < f:
                y, f, g, took_euler = guess, f_guess, g_guess, True
        if not took_euler:
            step = f / (g @ g)
            for _ in range(60):
                (f_next,), (g_next,) = loss_and_gradient((y - step * g)[None], goal)
                evaluations += 1
                if f_next < f:
                    break
                step /= 2
            else:
                raise RuntimeError(f"no decrease along the gradient at 1 - IoU = {f:.3e}")
            y, f, g = y - step * g, f_next, g_next
        path.append(y)
        losses.append(f)
        euler.append(took_euler)
    return Fit(to_ellipse(y), float(f), len(euler), evaluations, path, losses, euler)


def perturbed_start(target: ellipsect.Ellipse, direction: float) -> ellipsect.Ellipse:
    """The target moved by 30% of its mean radius along angle `direction`, turned by 0.5 rad,
    its radii scaled by 1.4 and 0.6."""
    shift = 0.3 * np.sqrt(np.prod(target.radii)) * np.array([np.cos(direction), np.sin(direction)])
    angle = np.arctan2(target.axes[1, 0], target.axes[0, 0])
    return ellipsect.Ellipse(target.center + shift, target.radii * [1.4, 0.6], angle=angle + 0.5)


def trials(rng: np.random.Generator, n: int, euler_steps: bool) -> Tuple[List[int], List[int], int]:
    """Fits from perturbed_start on n random targets: iterations and evaluations of the fits
    that converged within 300 iterations, and the number that did not."""
    centers, radii, angles = random_ellipses(rng, n, spread=1.0)
    iterations, evaluations, failed = [], [], 0
    for c, r, t, d in zip(centers, radii, angles, rng.uniform(-np.pi, np.pi, n)):
        target = ellipsect.Ellipse(c, r, angle=t)
        try:
            fit = fit_ellipse(target, perturbed_start(target, d), max_iterations=300, euler_steps=euler_steps)
        except RuntimeError:
            failed += 1
            continue
        iterations.append(fit.iterations)
        evaluations.append(fit.evaluations)
    return iterations, evaluations, failed


# --- Pictures and main ---------------------------------------------------------------------

def draw(target: ellipsect.Ellipse, fit: Fit, path: str) -> None:
    """The start and the iterates still visibly apart from the target, and log10(1 - IoU)
    against the iteration."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(11.5, 4.4))
    fig.subplots_adjust(left=0.04, right=0.98, bottom=0.12, top=0.9, wspace=0.6)  # the legend in between
    for i, (y, f) in enumerate(zip(fit.path, fit.losses)):
        if f > 1e-3:
            ep.bodies(left, to_ellipse(y), color=plt.cm.tab10(i % 10), linewidth=1.2,
                      label=f"{'start' if i == 0 else f'iteration {i}'}: 1 - IoU = {f:.2g}")
    ep.bodies(left, target, color="black", linewidth=2.0, linestyle="--", label="target")
    left.set_aspect("equal")
    left.legend(loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=8, frameon=False)
    left.set_title("start and iterates with 1 - IoU > 1e-3")
    k = np.arange(len(fit.losses))
    loss = np.array(fit.losses)
    shown = loss > 0  # 1 - IoU can round to <= 0 at the end
    kinds = np.array([False] + fit.euler)
    right.plot(k[shown], np.log10(loss[shown]), "-", color="0.6")
    right.plot(k[shown & ~kinds], np.log10(loss[shown & ~kinds]), "o", color="darkorange",
               label="start / gradient step")
    right.plot(k[shown & kinds], np.log10(loss[shown & kinds]), "s", color="navy", label="Euler-identity step")
    right.axhline(-12, color="crimson", linewidth=0.8, linestyle=":")
    right.set_xlabel("iteration")
    right.set_ylabel("log10(1 - IoU)")
    right.legend(fontsize=8)
    right.set_title(f"1 - IoU at the end: {fit.loss:.2e}")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv: Optional[list] = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=2000, help="pairs per category of the surrogate table")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--trials", type=int, default=100, help="random fits, with and without Euler-identity steps")
    parser.add_argument("--out", help="PNG of the fit")
    args = parser.parse_args(argv)

    start = time.perf_counter()
    table = surrogate_table(np.random.default_rng(args.seed), args.n)
    print(f"surrogates against the exact IoU, n = {args.n} pairs per row, seed {args.seed} "
          f"({time.perf_counter() - start:.3f} s):\n")
    print(markdown(table))

    target = ellipsect.Ellipse([0.0, 0.0], [2.0, 0.8], angle=0.3)
    begin = perturbed_start(target, 1.0)
    start = time.perf_counter()
    fit = fit_ellipse(target, begin)
    elapsed = time.perf_counter() - start
    print(f"\nfit: 1 - IoU from {1 - ellipsect.iou(begin, target):.4f} to {fit.loss:.3e} in {fit.iterations} "
          f"iterations ({sum(fit.euler)} Euler-identity steps), {fit.evaluations} IoU evaluations, "
          f"{elapsed * 1e3:.1f} ms")
    print("1 - IoU per iteration: " + ", ".join(f"{x:.2e}" for x in fit.losses))
    for euler_steps in (True, False):
        start = time.perf_counter()
        iterations, evaluations, failed = trials(np.random.default_rng(args.seed), args.trials, euler_steps)
        print(f"{args.trials} random fits, {'Euler-identity and gradient' if euler_steps else 'gradient-only'} steps: "
              f"{failed} not converged in 300 iterations; iterations mean {np.mean(iterations):.1f}, max "
              f"{max(iterations)}; evaluations mean {np.mean(evaluations):.0f}, max {max(evaluations)} "
              f"({time.perf_counter() - start:.2f} s)")
    if args.out:
        draw(target, fit, args.out)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
