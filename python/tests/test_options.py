"""Options are input: every field rejects what it cannot mean with an InputError naming it."""

import math
import pickle

import numpy as np
import pytest

import ellipsect

BAD_TOLERANCES = [math.nan, math.inf, -math.inf, -1e-12, 5e-324, 9e-15, 1.1e-9, 1e-6, 1.0]
BAD_CAPS = [0, -1, -(2**31), 2**31 - 1, 2**40, 2**64, 10**30, -(10**30)]
# One cap per algorithm, its largest value and its default.
CAPS = {"max_contact_iterations": (100000, 64), "max_distance_iterations": (100000, 64),
        "max_contact_function_iterations": (100000, 64), "max_slide_rounds": (100000, 64),
        "max_motion_steps": (1000000, 10000), "max_slabs": (1000000, 10000)}


def caps_of(o):
    return tuple(getattr(o, field) for field in CAPS)


def test_defaults_and_range_ends():
    o = ellipsect.Options()
    assert o.tolerance == 1e-12 and caps_of(o) == tuple(default for _, default in CAPS.values())
    low = ellipsect.Options(tolerance=1e-14, **{field: np.int64(1) for field in CAPS})
    assert low.tolerance == 1e-14 and caps_of(low) == (1,) * len(CAPS)
    high = ellipsect.Options(tolerance=1e-9, **{field: top for field, (top, _) in CAPS.items()})
    assert high.tolerance == 1e-9 and caps_of(high) == tuple(top for top, _ in CAPS.values())
    again = pickle.loads(pickle.dumps(high))
    assert again.tolerance == 1e-9 and caps_of(again) == caps_of(high)
    # Each cap is its own: setting one leaves the others.
    for field in CAPS:
        one = ellipsect.Options(**{field: 3})
        assert caps_of(one) == tuple(3 if f == field else d for f, (_, d) in CAPS.items())


@pytest.mark.parametrize("value", BAD_TOLERANCES)
def test_bad_tolerance_names_the_field(value):
    with pytest.raises(ellipsect.InputError) as info:
        ellipsect.Options(tolerance=value)
    assert info.value.field == "tolerance" and isinstance(info.value, ValueError)
    o = ellipsect.Options(tolerance=1e-10)
    with pytest.raises(ellipsect.InputError) as info:
        o.tolerance = value
    assert info.value.field == "tolerance"
    assert o.tolerance == 1e-10  # a rejected assignment leaves the old value


def test_message_gives_the_value_and_the_range():
    with pytest.raises(ellipsect.InputError, match=r"tolerance: must be 0 or in \[1e-14, 1e-09\] \(got nan\)"):
        ellipsect.Options(tolerance=math.nan)
    with pytest.raises(ellipsect.InputError, match=r"max_slide_rounds: must be in \[1, 100000\] \(got 10{30}\)"):
        ellipsect.Options(max_slide_rounds=10**30)


@pytest.mark.parametrize("field", list(CAPS))
@pytest.mark.parametrize("value", BAD_CAPS + ["max + 1"])
def test_bad_cap_names_the_field(field, value):
    value = CAPS[field][0] + 1 if value == "max + 1" else value
    with pytest.raises(ellipsect.InputError) as info:
        ellipsect.Options(**{field: value})
    assert info.value.field == field
    o = ellipsect.Options()
    before = getattr(o, field)
    with pytest.raises(ellipsect.InputError) as info:
        setattr(o, field, value)
    assert info.value.field == field and getattr(o, field) == before


@pytest.mark.parametrize("field", list(CAPS))
def test_a_cap_is_an_integer(field):
    with pytest.raises(TypeError):
        ellipsect.Options(**{field: 10.0})
    o = ellipsect.Options()
    setattr(o, field, np.int32(7))
    assert getattr(o, field) == 7


def test_unpickling_validates():
    o = ellipsect.Options.__new__(ellipsect.Options)
    with pytest.raises(ellipsect.InputError) as info:
        o.__setstate__((math.nan, 64, 64, 64, 64, 10000, 10000))
    assert info.value.field == "tolerance"
    with pytest.raises(ellipsect.InputError) as info:
        o.__setstate__((1e-12, 64, 0, 64, 64, 10000, 10000))
    assert info.value.field == "max_distance_iterations"


def test_exact_tangency_is_touching_for_every_query_at_the_smallest_band():
    o = ellipsect.Options(tolerance=1e-14)
    a, b = ellipsect.Ellipse([0, 0], [1, 1]), ellipsect.Ellipse([2, 0], [1, 1])
    assert ellipsect.classify(a, b, o) == ellipsect.Relation.touching
    assert ellipsect.overlap(a, b, o)
    assert ellipsect.first_contact(a, [0, 0], b, [0, 0], 1.0, o).status == ellipsect.ContactStatus.touching_at_start
    assert ellipsect.signed_distance(a, b, o).status == ellipsect.DistanceStatus.touching


def test_exact_mode_answers_the_stored_numbers():
    # Circles of radii 3 and 2 whose centers are 5 apart touch exactly; one ulp farther they
    # are apart, one ulp nearer they overlap: tolerance 0 tells all three, the band cannot.
    exact = ellipsect.Options(tolerance=0)
    assert exact.tolerance == 0.0
    assert pickle.loads(pickle.dumps(exact)).tolerance == 0.0
    a = ellipsect.Ellipse([0, 0], [3, 3])
    want = {5.0: "touching", math.nextafter(5.0, 6.0): "separated", math.nextafter(5.0, 4.0): "overlapping"}
    for x, name in want.items():
        b = ellipsect.Ellipse([x, 0], [2, 2])
        assert ellipsect.classify(a, b, exact) == getattr(ellipsect.Relation, name)
        assert ellipsect.overlap(a, b, exact) == (name != "separated")
        assert ellipsect.classify(a, b) == ellipsect.Relation.touching  # the default band of 1e-12
        many_a = ellipsect.Ellipses(centers=[[0, 0]] * 2, radii=[[3, 3]] * 2)
        many_b = ellipsect.Ellipses(centers=[[x, 0]] * 2, radii=[[2, 2]] * 2)
        assert ellipsect.classify(many_a, many_b, exact).tolist() == [int(getattr(ellipsect.Relation, name))] * 2
