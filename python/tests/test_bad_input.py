"""Bad arguments raise TypeError / ValueError naming the argument (and the row for values)."""

import math

import numpy as np
import pytest
from conftest import floors

import ellipsect


def ok(n=4):
    return dict(centers=np.zeros((n, 2)), radii=np.ones((n, 2)), angles=np.zeros(n))


@pytest.mark.parametrize(
    "change, error, words",
    [
        (dict(centers=[[0.0, 0.0]] * 4), TypeError, "centers: expected a numpy array"),
        (dict(radii=np.ones((4, 2), dtype=np.float32)), TypeError, "radii: expected dtype float64"),
        (dict(centers=np.zeros((4, 3))), ValueError, "centers: expected shape (n, 2), got (4, 3)"),
        (dict(angles=np.zeros((4, 1))), ValueError, "angles: expected shape (4,), got (4, 1)"),
        (dict(radii=np.ones((5, 2))), ValueError, "radii: expected 4 rows, as centers, got 5"),
        (dict(centers=np.zeros((4, 4))[:, ::2]), ValueError, "centers: must be C-contiguous"),
        (dict(rotations=np.tile(np.eye(2), (4, 1, 1))), ValueError, "angles or rotations, not both"),
    ],
)
def test_array_checks(change, error, words):
    with pytest.raises(error) as info:
        ellipsect.Ellipses(**{**ok(), **change})
    assert words in str(info.value)


def test_bad_values_name_the_first_bad_row():
    centers = np.zeros((6, 2))
    centers[4, 1] = np.nan
    centers[5, 0] = np.inf
    with pytest.raises(ellipsect.InputError, match=r"centers\[4, 1\]: must be finite") as info:
        ellipsect.Ellipses(**{**ok(6), "centers": centers})
    assert info.value.field == "centers[4, 1]" and isinstance(info.value, ValueError)
    radii = np.ones((6, 2))
    radii[2, 1] = 0.0
    with pytest.raises(ValueError, match=r"radii\[2, 1\]: must be > 0"):
        ellipsect.Ellipses(**{**ok(6), "radii": radii})
    radii[2] = [1e9, 1.0]
    with pytest.raises(ValueError, match=r"radii\[2\]: aspect ratio"):
        ellipsect.Ellipses(**{**ok(6), "radii": radii})
    angles = np.zeros(6)
    angles[3] = np.nan
    with pytest.raises(ValueError, match=r"angles\[3\]"):
        ellipsect.Ellipses(**{**ok(6), "angles": angles})
    q = np.tile([1.0, 0, 0, 0], (3, 1))
    q[1] = [2.0, 0, 0, 0]
    with pytest.raises(ValueError, match=r"quaternions\[1\]: must have unit norm"):
        ellipsect.Ellipsoids(centers=np.zeros((3, 3)), radii=np.ones((3, 3)), quaternions=q)
    q[1] = [1.0, np.nan, 0, 0]
    with pytest.raises(ValueError, match=r"quaternions\[1, 1\]"):
        ellipsect.Ellipsoids(centers=np.zeros((3, 3)), radii=np.ones((3, 3)), quaternions=q)
    m = np.tile(np.eye(3), (3, 1, 1))
    m[2, 0, 1] = 0.5
    with pytest.raises(ValueError, match=r"rotations\[2\]"):
        ellipsect.Ellipsoids(centers=np.zeros((3, 3)), radii=np.ones((3, 3)), rotations=m)


def test_query_argument_checks():
    a = ellipsect.Ellipses(**ok(4))
    b = ellipsect.Ellipses(**ok(3))
    with pytest.raises(ValueError, match="b: expected 4 bodies, as a, got 3"):
        ellipsect.overlap(a, b)
    with pytest.raises(ValueError, match=r"velocity_a: expected shape \(4, 2\), got \(4, 3\)"):
        ellipsect.first_contact(a, np.zeros((4, 3)), a, np.zeros((4, 2)), 1.0)
    with pytest.raises(ValueError, match="velocity_b: expected 4 rows, as a, got 2"):
        ellipsect.first_contact(a, np.zeros((4, 2)), a, np.zeros((2, 2)), 1.0)
    with pytest.raises(TypeError, match="t_max: expected dtype float64"):
        ellipsect.first_contact(a, np.zeros((4, 2)), a, np.zeros((4, 2)), np.ones(4, dtype=np.int64))
    with pytest.raises(TypeError):
        ellipsect.overlap(a, ellipsect.Ellipsoids(centers=np.zeros((4, 3)), radii=np.ones((4, 3))))


def test_scalar_factories_name_the_field():
    with pytest.raises(ellipsect.InputError, match=r"radii\[1\]") as info:
        ellipsect.Ellipse([0, 0], [1, -1])
    assert info.value.field == "radii[1]"
    with pytest.raises(ValueError, match="quaternion.w"):
        ellipsect.Ellipsoid([0, 0, 0], [1, 1, 1], quaternion=[np.nan, 0, 0, 0])
    with pytest.raises(ValueError, match="radius"):
        ellipsect.Circle([0, 0], -1)
    with pytest.raises(ValueError, match="M"):
        ellipsect.Ellipse.from_quadric([0, 0], [[1, 0], [0, -1]])


@pytest.mark.parametrize("dim", [2, 3])
def test_angular_velocity_checks(dim):
    # The body pair and every shape take angular_velocity_a alike: a rate in 2D, a 3-vector in
    # 3D. A value of the wrong shape or kind matches no overload: pybind11's TypeError, which
    # names the argument among those it was called with. A NaN is the library's invalid_input.
    body = ellipsect.Ellipse if dim == 2 else ellipsect.Ellipsoid
    a, v = body.ball(3 * np.eye(dim)[-1], 1), np.zeros(dim)
    nan, wrong = (math.nan, [0.0, 1.0]) if dim == 2 else ([0.0, math.nan, 0.0], [0.0, 1.0])
    for b in [body.ball(np.full(dim, 5.0), 1), *floors(dim).values()]:
        bad = ellipsect.first_contact(a, v, b, v, 1.0, angular_velocity_a=nan)
        assert getattr(bad, "contact", bad).status == ellipsect.ContactStatus.invalid_input
        for w in (wrong, "fast", [0.0, "fast", 0.0]):
            with pytest.raises(TypeError, match=r"(?s)incompatible function arguments.*kwargs: angular_velocity_a="):
                ellipsect.first_contact(a, v, b, v, 1.0, angular_velocity_a=w)
