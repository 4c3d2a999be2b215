"""Shared strategies and helpers for the ellipsect tests."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from hypothesis import settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import ellipsect  # noqa: E402

# Derandomized: the same examples on every run and machine, so a CI failure reproduces here
# (and a clean run here is clean there).
settings.register_profile("ellipsect", max_examples=60, deadline=None, derandomize=True, database=None)
settings.register_profile("ellipsect-long", max_examples=5000, deadline=None)
settings.load_profile("ellipsect")

coordinate = st.floats(-10, 10, allow_nan=False)
radius = st.floats(0.1, 10, allow_nan=False)
angle = st.floats(-np.pi, np.pi, allow_nan=False)


@st.composite
def ellipses(draw):
    return ellipsect.Ellipse([draw(coordinate), draw(coordinate)], [draw(radius), draw(radius)], angle=draw(angle))


@st.composite
def ellipsoids(draw):
    q = np.array([draw(st.floats(-1, 1)) for _ in range(4)])
    q = q / np.linalg.norm(q) if np.linalg.norm(q) > 0.1 else np.array([1.0, 0, 0, 0])
    return ellipsect.Ellipsoid([draw(coordinate) for _ in range(3)], [draw(radius) for _ in range(3)], quaternion=q)


def random_ellipses(n, seed, spread=6.0):
    """n random ellipses as a batch and as scalar bodies."""
    rng = np.random.default_rng(seed)
    centers = rng.uniform(-spread, spread, (n, 2))
    radii = rng.uniform(0.2, 3.0, (n, 2))
    angles = rng.uniform(-np.pi, np.pi, n)
    batch = ellipsect.Ellipses(centers=centers, radii=radii, angles=angles)
    return batch, [ellipsect.Ellipse(c, r, angle=a) for c, r, a in zip(centers, radii, angles)]


def random_ellipsoids(n, seed, spread=6.0):
    """n random ellipsoids as a batch and as scalar bodies."""
    rng = np.random.default_rng(seed)
    centers = rng.uniform(-spread, spread, (n, 3))
    radii = rng.uniform(0.2, 3.0, (n, 3))
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    batch = ellipsect.Ellipsoids(centers=centers, radii=radii, quaternions=q)
    return batch, [ellipsect.Ellipsoid(c, r, quaternion=w) for c, r, w in zip(centers, radii, q)]


def same_bits(x, y):
    """True when two float arrays are equal bit for bit (NaNs and signed zeros included)."""
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    return x.shape == y.shape and np.array_equal(x.view(np.uint64), y.view(np.uint64))


def floors(dim):
    """The floor x_dim <= 0 as each shape, by name, its top at x_dim = 0 along the x axis from
    -10 to 10 at least: a half-space, a box, a capsule (its segment along x), a triangle (2D: a
    segment, as three collinear points) and a mesh of two triangles."""
    if dim == 2:
        return {
            "half-space": ellipsect.HalfPlane([0, 0], [0, 1]),
            "box": ellipsect.Box2([0, -1], [10, 1]),
            "capsule": ellipsect.Capsule2([-10, -1], [10, -1], 1),
            "triangle": ellipsect.Triangle2([-10, 0], [10, 0], [0, 0]),
            "mesh": ellipsect.TriangleMesh2(np.array([[-10.0, -1], [10, -1], [10, 0], [-10, 0]]),
                                            np.array([[0, 1, 2], [0, 2, 3]])),
        }
    return {
        "half-space": ellipsect.HalfSpace([0, 0, 0], [0, 0, 1]),
        "box": ellipsect.Box3([0, 0, -1], [10, 10, 1]),
        "capsule": ellipsect.Capsule3([-10, 0, -1], [10, 0, -1], 1),
        "triangle": ellipsect.Triangle3([-10, -10, 0], [10, -10, 0], [0, 10, 0]),
        "mesh": ellipsect.TriangleMesh3(np.array([[-10.0, -10, 0], [10, -10, 0], [10, 10, 0], [-10, 10, 0]]),
                                        np.array([[0, 1, 2], [0, 2, 3]])),
    }
