"""Bad arguments raise TypeError / ValueError naming the argument (and the row for values)."""

import math

import numpy as np
import pytest
from conftest import floors, random_ellipses

import ellipsect


def ok(n=4):
    return dict(centers=np.zeros((n, 2)), radii=np.ones((n, 2)), angles=np.zeros(n))


@pytest.mark.parametrize(
    "change, error, words",
    [
        (dict(centers=np.zeros((4, 2), dtype=complex)), TypeError, "centers: expected real numbers, got dtype complex128"),
        (dict(radii=np.full((4, 2), "1")), TypeError, "radii: expected real numbers, got dtype <U1"),
        (dict(radii=[[1.0, 1.0]] * 3 + [[1.0]]), TypeError, "radii: expected an array_like of real numbers, got list"),
        (dict(angles=[0.0, {}, 0.0, 0.0]), TypeError, "angles: expected an array_like of real numbers, got list"),
        (dict(centers=np.zeros((4, 3))), ValueError, "centers: expected shape (n, 2), got (4, 3)"),
        (dict(angles=np.zeros((4, 1))), ValueError, "angles: expected shape (4,), got (4, 1)"),
        (dict(radii=np.ones((5, 2))), ValueError, "radii: expected 4 rows, as centers, got 5"),
        (dict(rotations=np.tile(np.eye(2), (4, 1, 1))), ValueError, "angles or rotations, not both"),
    ],
)
def test_array_checks(change, error, words):
    with pytest.raises(error) as info:
        ellipsect.Ellipses(**{**ok(), **change})
    assert words in str(info.value)


def test_array_likes_are_converted():
    # numpy's array_like: lists, integer, bool and float32 arrays, strided slices and Fortran
    # order give the bodies their float64 values give.
    want = ellipsect.Ellipses(centers=np.array([[0.0, 1], [2, 3]]), radii=np.array([[1.0, 2], [1, 1]]),
                              angles=np.array([0.5, 0.0]))
    wide = np.zeros((2, 4))
    wide[:, ::2] = [[0, 1], [2, 3]]
    for centers in ([[0, 1], [2, 3]], np.array([[0, 1], [2, 3]], dtype=np.int32), wide[:, ::2],
                    np.asfortranarray([[0.0, 1], [2, 3]]), np.array([[0, 1], [2, 3]], dtype=np.float32),
                    np.array([[0, 1], [2, 3]], dtype=">f8")):
        got = ellipsect.Ellipses(centers=centers, radii=[[1, 2], [True, 1]], angles=(np.float32(0.5), 0))
        for field in ("centers", "radii", "rotations"):
            assert np.array_equal(getattr(got, field), getattr(want, field)), (centers, field)
    a = ellipsect.Ellipses(**ok(4))
    contact = ellipsect.first_contact(a, [[1, 0]] * 4, a, np.zeros((4, 2), dtype=np.float32), [1, 2, 3, 4])
    assert contact.status.tolist() == [ellipsect.ContactStatus.overlapping_at_start] * 4
    want = ellipsect.earliest_contact(a, np.array([[1.0, 0]] * 4), 1.0, angular_velocities=np.array([0.0, 1, 0, 1]))
    got = ellipsect.earliest_contact(a, [[1, 0]] * 4, 1.0, angular_velocities=[0, 1, 0, 1])
    assert got[:3] == want[:3] and got[3].status == want[3].status


@pytest.mark.parametrize("t_max", [np.float32(4.0), np.int64(4), np.array(4.0), 4, 4.0])
def test_t_max_takes_any_number(t_max):
    # A numpy scalar or 0-d array is one window for every pair, as a Python number is.
    a, _ = random_ellipses(5, seed=1)
    b, _ = random_ellipses(5, seed=2)
    v = np.ones((5, 2))
    want = ellipsect.first_contact(a, v, b, -v, np.full(5, 4.0))
    assert all(np.array_equal(x, y, equal_nan=True)
               for x, y in zip(ellipsect.first_contact(a, v, b, -v, t_max), want))
    got = ellipsect.first_contact(ellipsect.pairs(a, b, v, -v, t_max))
    assert all(np.array_equal(x, y, equal_nan=True) for x, y in zip(got, want))


def test_take_rejects_non_integer_indices():
    a, _ = random_ellipses(5, seed=1)
    for indices in ([1.7], np.array([1.0]), np.array([1 + 0j]), ["1"]):
        with pytest.raises(TypeError, match="indices: expected"):
            a.take(indices)
    assert np.array_equal(a.take([-1, np.int8(0)]).centers, a.centers[[4, 0]])
    assert len(a.take([])) == 0
    with pytest.raises(IndexError, match="indices: -6 out of range"):
        a.take([-6])


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
    m = np.tile(np.eye(3), (5, 1, 1))
    m[2, 0, 1] = 0.5
    with pytest.raises(ValueError, match=r"rotations\[2\]"):
        ellipsect.Ellipsoids(centers=np.zeros((5, 3)), radii=np.ones((5, 3)), rotations=m)
    m[2, 0, 1] = 0.0
    m[3, 0, 1] = np.nan
    with pytest.raises(ellipsect.InputError, match=r"rotations\[3, 0, 1\]: must be finite") as info:
        ellipsect.Ellipsoids(centers=np.zeros((5, 3)), radii=np.ones((5, 3)), rotations=m)
    assert info.value.field == "rotations[3, 0, 1]"


def test_query_argument_checks():
    a = ellipsect.Ellipses(**ok(4))
    b = ellipsect.Ellipses(**ok(3))
    with pytest.raises(ValueError, match="b: expected 4 bodies, as a, got 3"):
        ellipsect.overlap(a, b)
    with pytest.raises(ValueError, match=r"velocity_a: expected shape \(4, 2\), got \(4, 3\)"):
        ellipsect.first_contact(a, np.zeros((4, 3)), a, np.zeros((4, 2)), 1.0)
    with pytest.raises(ValueError, match="velocity_b: expected 4 rows, as a, got 2"):
        ellipsect.first_contact(a, np.zeros((4, 2)), a, np.zeros((2, 2)), 1.0)
    with pytest.raises(TypeError, match="t_max: expected real numbers, got dtype complex128"):
        ellipsect.first_contact(a, np.zeros((4, 2)), a, np.zeros((4, 2)), 1j)
    with pytest.raises(ValueError, match=r"t_max: expected 4 rows, as a, got 3"):
        ellipsect.pairs(a, a, np.zeros((4, 2)), np.zeros((4, 2)), [1, 2, 3])
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
