"""Every value type of the module pickles bit for bit (results by their named fields); bodies and shapes compare by value and
their reprs rebuild them; every public function, class, method and property has a docstring."""

import inspect
import pickle
import re

import numpy as np
import pytest
from conftest import floors, random_ellipses, random_ellipsoids

import ellipsect


def examples():
    """One value of every class of the module (two where the dimension differs), by class name."""
    out = {}
    for dim, body in ((2, ellipsect.Ellipse([1, 2], [3, 1], angle=0.3)),
                      (3, ellipsect.Ellipsoid([1, 2, 3], [3, 2, 1], quaternion=[0.5, 0.5, 0.5, 0.5]))):
        v, far = np.zeros(dim), np.eye(dim)[0]
        other = type(body).ball(8 * far, 1)
        shapes = floors(dim)
        out.update({type(s).__name__: s for s in shapes.values()})
        mesh = shapes["mesh"]
        out.update({type(x).__name__: x for x in (
            body, ellipsect.first_contact(body, -far, other, v, 10.0), ellipsect.distance(body, other),
            ellipsect.closest_point(body, 5 * far), ellipsect.closest_approach(body, other, far),
            ellipsect.first_contact(body, -np.eye(dim)[-1], mesh, v, 10.0), ellipsect.distance(body, mesh),
            ellipsect.collide_and_slide(body, -3 * np.eye(dim)[-1], mesh))})
        batch, _ = (random_ellipses if dim == 2 else random_ellipsoids)(30, seed=dim)
        moving = np.random.default_rng(dim).normal(size=(30, dim))
        out[type(batch).__name__] = batch
        for dtype in (np.float64, np.float32):
            p = ellipsect.pairs(batch, batch.take(np.arange(30)[::-1]), moving, -moving, 3.0, dtype=dtype)
            out[type(p).__name__] = p
    e, f = out["Ellipse"], ellipsect.Ellipse([2, 2], [2, 1], angle=1.0)
    circle = ellipsect.Circle([4, 2], 1.5)
    out.update({type(x).__name__: x for x in (
        circle, ellipsect.Options(), ellipsect.perram_wertheim(e, f), ellipsect.intersect_boundaries(e, f),
        ellipsect.overlap_area(e, f), ellipsect.segment_circle([0, 0], [5, 2], circle),
        ellipsect.polygonal_overlap(e, circle), ellipsect.closest_point_quartic(e, [6, 2]),
        ellipsect.classify(e, floors(2)["mesh"]))})
    return out


def module_classes():
    return {name: c for name, c in vars(ellipsect).items()
            if inspect.isclass(c) and type(c).__name__ == "pybind11_type"}


def state(x):
    """What a value holds, for comparison bit for bit: its properties (arrays as bytes), or for
    prepared pairs the answers of their queries."""
    if type(x).__name__.startswith("Pairs"):
        return [state(np.asarray(a)) for a in (ellipsect.overlap(x), ellipsect.classify(x),
                                               *ellipsect.first_contact(x))]
    if isinstance(x, (np.ndarray, float, int, np.generic)):
        a = np.asarray(x)
        return (a.dtype.str, a.shape, a.tobytes())
    if isinstance(x, (list, tuple)):
        return [state(v) for v in x]
    if type(type(x)).__name__ == "pybind11_type":
        return {name: state(getattr(x, name)) for name, p in vars(type(x)).items() if isinstance(p, property)}
    return x


def test_every_value_type_pickles_bit_for_bit():
    values = examples()
    assert set(module_classes()) <= set(values), "a class without an example"
    for name, x in values.items():
        again = pickle.loads(pickle.dumps(x))
        assert type(again) is type(x) and state(again) == state(x) != {}, name


RESULTS = ["Contact2", "Contact3", "Slide2", "Slide3", "MeshContact2", "MeshContact3", "MeshDistance2", "MeshDistance3",
           "Distance2", "Distance3", "ClosestPoint2", "ClosestPoint3", "ClosestApproach2", "ClosestApproach3",
           "BoundaryIntersection", "OverlapArea", "SegmentCircle", "PolygonalOverlap", "QuarticPoint", "MeshRelation",
           "ContactFunction"]


def test_results_pickle_by_named_fields():
    # A result's state is a dict of its fields (statuses by name, vectors as tuples, bodies and
    # nested results as objects), not its bytes: it loads in a later version and on another
    # machine. A state with a field more (a later version's) loads; one with a field less is
    # an error naming it, as is an unknown status.
    values = examples()
    for name in RESULTS:
        x = values[name]
        s = x.__getstate__()
        assert isinstance(s, dict) and s, name
        later = dict(s, a_field_of_a_later_version=1.0)
        again = type(x).__new__(type(x))
        again.__setstate__(later)
        assert state(again) == state(x), name
        for field in s:
            fewer = {k: v for k, v in s.items() if k != field}
            with pytest.raises(ValueError, match=rf"pickled {name}\.{field}: missing"):
                type(x).__new__(type(x)).__setstate__(fewer)
    ball = ellipsect.Ellipsoid.ball([0, 0, 0], 1)
    contact = ellipsect.first_contact(ball, [1, 0, 0], ellipsect.Ellipsoid.ball([8, 0, 0], 1), [0, 0, 0], 10.0)
    s = contact.__getstate__()
    assert pickle.loads(pickle.dumps(contact)).time == 6.0
    assert s["status"] == "hit" and isinstance(s["point"], tuple) and len(s["point"]) == 3
    assert s["time"] == contact.time and s["iterations"] == contact.iterations
    with pytest.raises(ValueError, match="unknown status 'hot'"):
        type(contact).__new__(type(contact)).__setstate__(dict(s, status="hot"))
    with pytest.raises(ValueError, match=r"pickled Contact3\.point: expected 3 items"):
        type(contact).__new__(type(contact)).__setstate__(dict(s, point=(1.0, 2.0)))
    slide = values["Slide3"].__getstate__()
    assert type(slide["body"]).__name__ == "Ellipsoid" and slide["status"] in ("moved", "slid", "blocked")
    assert type(values["MeshContact2"].__getstate__()["contact"]).__name__ == "Contact2"


def test_bodies_and_shapes_compare_by_value_and_repr_rebuilds_them():
    values = examples()
    names = ["Ellipse", "Ellipsoid", "Circle", "HalfPlane", "HalfSpace", "Box2", "Box3", "Capsule2", "Capsule3",
             "Triangle2", "Triangle3"]
    for name in names:
        x = values[name]
        again = eval(repr(x), vars(ellipsect))
        assert again == x and hash(again) == hash(x) and not again != x, name
        assert pickle.loads(pickle.dumps(x)) == x, name
        if name != "Circle":
            dim = 3 if name in ("Ellipsoid", "HalfSpace", "Box3", "Capsule3", "Triangle3") else 2
            assert x != x.translated(np.full(dim, 1e-9)), name
        assert (x == "x") is False and x != values["Ellipse" if name != "Ellipse" else "Ellipsoid"], name
    e = ellipsect.Ellipse([0, 0], [3, 1], angle=0.5)
    assert "rotation=[[" in repr(e) and repr(ellipsect.Ellipse([0, 0], [3, 1])) != repr(e)
    assert ellipsect.Ellipse([0, 0], [3, 1], angle=0.5) == e != ellipsect.Ellipse([0, 0], [3, 1], angle=0.6)
    assert len({e, ellipsect.Ellipse([0, 0], [3, 1], angle=0.5), ellipsect.Ellipse([0, 0], [1, 3])}) == 2
    assert "axes=[[" in repr(values["Box3"])


def overload_texts(function):
    """The text of each overload's docstring, without its signature lines."""
    doc = function.__doc__ or ""
    name = function.__name__
    numbered = r"\d+\. " if "\nOverloaded function.\n" in doc else ""
    sections = re.split(rf"^{numbered}{name}\(.*$", doc, flags=re.M)
    return [t.strip() for t in sections[1:]] if len(sections) > 1 else [doc.strip()]


def test_everything_public_has_a_docstring():
    missing = []
    for name in ellipsect.__all__ if hasattr(ellipsect, "__all__") else dir(ellipsect):
        x = getattr(ellipsect, name)
        if name.startswith("_") or inspect.ismodule(x):
            continue
        if callable(x) and not inspect.isclass(x):
            missing += [f"{name} overload {k + 1}" for k, t in enumerate(overload_texts(x)) if not t]
            continue
        if not inspect.isclass(x):
            continue
        if not (x.__doc__ or "").strip():
            missing.append(name)
        if type(x).__name__ != "pybind11_type":
            continue
        for member, value in vars(x).items():
            if member.startswith("_") and member not in ("__init__", "__getitem__", "__len__"):
                continue
            if name == "Options":
                continue  # its binding is documented with options.hpp
            target = value.fget if isinstance(value, property) else getattr(value, "__func__", value)
            texts = [(value.__doc__ or "").strip()] if isinstance(value, property) else overload_texts(target)
            missing += [f"{name}.{member}" for t in texts if not t]
    assert missing == []


def test_docstrings_say_what_goes_in_and_out():
    for f in (ellipsect.classify, ellipsect.first_contact, ellipsect.Ellipses.take, ellipsect.pairs,
              ellipsect.Ellipsoids.__init__):
        for text in overload_texts(f):
            assert "Args:" in text and "Returns:" in text, (f.__name__, text)
