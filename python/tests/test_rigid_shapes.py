"""A body in rigid motion against half-spaces, boxes, capsules, triangles and meshes
(first_contact's angular_velocity_a): the turning rod's closed form, the translational
answer without spin, and a spinning ball's translational time (hypothesis)."""

import math

import numpy as np
import pytest
from conftest import floors, same_bits
from hypothesis import given
from hypothesis import strategies as st

import ellipsect

SHAPES = ["half-space", "box", "capsule", "triangle", "mesh"]


def contact_of(answer):
    """The Contact of an answer (a mesh's MeshContact holds one)."""
    return getattr(answer, "contact", answer)


def turning(dim, w):
    """Angular velocity of rate w that turns x towards the up axis x_dim (2D: counterclockwise)."""
    return w if dim == 2 else [0.0, -w, 0.0]


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("w", [0.5, 3.0])
def test_rod_tips_onto_every_floor(dim, w):
    # A rod of radii 2 and 0.1 (0.1, 0.1 in 3D) along x, its center at height 1, turning at rate
    # w. At angle phi = w t its axes along x and up have components sin(phi) and cos(phi) on the
    # up direction, so its lowest point is sqrt((2 sin phi)^2 + (0.1 cos phi)^2) below the
    # center; that is 1 when 3.99 sin^2 phi = 0.99: t = asin(sqrt(0.99 / 3.99)) / w. The point
    # there is the -x end's support point, 3.99 sin(phi) cos(phi) to the left of the center.
    center = np.zeros(dim)
    center[-1] = 1.0
    radii = np.full(dim, 0.1)
    radii[0] = 2.0
    rod = (ellipsect.Ellipse if dim == 2 else ellipsect.Ellipsoid)(center, radii)
    phi = math.asin(math.sqrt(0.99 / 3.99))
    point = np.zeros(dim)
    point[0] = -3.99 * math.sin(phi) * math.cos(phi)
    down = -np.eye(dim)[-1]
    for name, floor in floors(dim).items():
        answer = ellipsect.first_contact(rod, np.zeros(dim), floor, np.zeros(dim), 10.0,
                                         angular_velocity_a=turning(dim, w))
        c = contact_of(answer)
        assert c.status == ellipsect.ContactStatus.hit, name
        assert abs(c.time - phi / w) <= 1e-11 * (phi / w), name
        np.testing.assert_allclose(c.point, point, rtol=0, atol=1e-9, err_msg=name)
        np.testing.assert_allclose(c.normal, down, rtol=0, atol=1e-9, err_msg=name)
        if name == "mesh":
            assert answer.triangle >= 0


def same_answer(x, y):
    """Equal bit for bit: status, time, point, normal, iterations (and a mesh's triangle)."""
    if hasattr(x, "triangle"):
        return x.triangle == y.triangle and same_answer(x.contact, y.contact)
    return (x.status == y.status and x.iterations == y.iterations and same_bits(x.time, y.time)
            and same_bits(x.point, y.point) and same_bits(x.normal, y.normal))


@pytest.mark.parametrize("dim", [2, 3])
def test_no_spin_is_translational(dim):
    # A tilted rod falling and drifting onto a rising floor: angular_velocity_a None makes the
    # translational call, and a zero angular velocity gives its answer bit for bit (contact.hpp).
    if dim == 2:
        rod = ellipsect.Ellipse([0.3, 2], [2, 0.1], angle=0.4)
        zero = 0.0
    else:
        q = np.array([0.9, 0.1, 0.2, 0.3])
        rod = ellipsect.Ellipsoid([0.3, -0.2, 2], [2, 0.1, 0.1], quaternion=q / np.linalg.norm(q))
        zero = [0.0, 0.0, 0.0]
    va, vb = np.linspace(0.1, -0.3, dim), np.eye(dim)[-1] * 0.05
    for name, floor in floors(dim).items():
        want = ellipsect.first_contact(rod, va, floor, vb, math.inf)
        assert contact_of(want).status == ellipsect.ContactStatus.hit, name
        assert same_answer(ellipsect.first_contact(rod, va, floor, vb, math.inf, angular_velocity_a=None), want), name
        assert same_answer(ellipsect.first_contact(rod, va, floor, vb, math.inf, angular_velocity_a=zero), want), name


spin = st.floats(-20, 20, allow_nan=False)


@given(st.sampled_from([2, 3]), st.sampled_from(SHAPES), st.floats(0.1, 2), st.floats(-3, 3), st.floats(-0.5, 0.5),
       st.floats(0.5, 10), st.floats(0.5, 5), st.tuples(spin, spin, spin))
def test_spinning_ball_takes_the_translational_time(dim, shape, radius, x, y, height, speed, w):
    # A ball is the same set at every turn: falling onto a floor while it spins, it meets the
    # floor when it would without spin, to the advancement's accuracy.
    center = [x, radius + height] if dim == 2 else [x, y, radius + height]
    ball = (ellipsect.Ellipse if dim == 2 else ellipsect.Ellipsoid).ball(center, radius)
    v = -speed * np.eye(dim)[-1]
    floor = floors(dim)[shape]
    want = contact_of(ellipsect.first_contact(ball, v, floor, np.zeros(dim), 100.0))
    got = contact_of(ellipsect.first_contact(ball, v, floor, np.zeros(dim), 100.0,
                                             angular_velocity_a=w[0] if dim == 2 else list(w)))
    assert want.status == got.status == ellipsect.ContactStatus.hit
    assert abs(got.time - want.time) <= 1e-11 * want.time
