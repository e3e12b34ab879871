"""Single contacts, for any approaching pair and any masses (hypothesis).

The examples are derandomized (the same ones every run, no example database), so
the suite stays bit-for-bit repeatable like the simulator it tests.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from billiards.physics.laws.ball_ball import frictionless_impulse, line_of_centres
from tests.hard_checks import (
    TABLE,
    R,
    check_no_overlap,
    check_sound,
    kinetic_energy,
    make_setup,
    run,
    sample_times,
)

REPEATABLE = settings(derandomize=True, database=None, deadline=None, max_examples=300)

speed = st.floats(-20.0, 20.0, allow_nan=False)
mass = st.floats(0.01, 10.0, allow_nan=False)
angle = st.floats(0.0, 2 * math.pi, allow_nan=False)
restitution = st.floats(0.0, 1.0, allow_nan=False)


def contact(
    normal_angle: float, v1: tuple[float, float], v2: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]:
    """Two touching balls (ball 1 at the origin side) and their closing speed."""
    normal = np.array([math.cos(normal_angle), math.sin(normal_angle)])
    p1 = np.array([1.0, 0.5]) + R * normal
    p2 = np.array([1.0, 0.5]) - R * normal
    u1, u2 = np.array(v1), np.array(v2)
    return p1, u1, p2, u2, float((u1 - u2) @ normal)


@REPEATABLE
@given(angle, speed, speed, speed, speed, mass, mass, restitution)
def test_any_contact_conserves_momentum_and_never_adds_energy(
    normal_angle: float,
    v1x: float,
    v1y: float,
    v2x: float,
    v2y: float,
    m1: float,
    m2: float,
    e: float,
) -> None:
    p1, v1, p2, v2, closing = contact(normal_angle, (v1x, v1y), (v2x, v2y))
    assume(closing < -1e-9)
    after1, after2, approach = frictionless_impulse(line_of_centres(p1, p2), v1, m1, v2, m2, e)
    scale = m1 * float(np.abs(v1).sum()) + m2 * float(np.abs(v2).sum())
    assert np.allclose(m1 * after1 + m2 * after2, m1 * v1 + m2 * v2, rtol=0, atol=1e-14 * scale)
    masses = np.array([m1, m2])
    before_energy = kinetic_energy(masses, np.array([v1, v2]))
    after_energy = kinetic_energy(masses, np.array([after1, after2]))
    assert after_energy <= before_energy * (1 + 1e-14)
    # The closing speed rounds like the velocities it comes from (the normal is read
    # from rounded positions), not like its own, possibly tiny, value.
    speeds = float(np.abs(v1).sum() + np.abs(v2).sum())
    assert math.isclose(approach, -closing, rel_tol=1e-12, abs_tol=1e-14 * speeds)


@REPEATABLE
@given(angle, speed, speed, speed, speed, mass, mass)
def test_elastic_contact_conserves_energy_and_reverses_the_closing_speed(
    normal_angle: float, v1x: float, v1y: float, v2x: float, v2y: float, m1: float, m2: float
) -> None:
    p1, v1, p2, v2, closing = contact(normal_angle, (v1x, v1y), (v2x, v2y))
    assume(closing < -1e-9)
    after1, after2, _ = frictionless_impulse(line_of_centres(p1, p2), v1, m1, v2, m2, 1.0)
    masses = np.array([m1, m2])
    before_energy = kinetic_energy(masses, np.array([v1, v2]))
    after_energy = kinetic_energy(masses, np.array([after1, after2]))
    assert math.isclose(after_energy, before_energy, rel_tol=1e-13)
    normal = (p1 - p2) / np.hypot(*(p1 - p2))
    separating = float((after1 - after2) @ normal)
    speeds = float(np.abs(v1).sum() + np.abs(v2).sum())
    assert math.isclose(separating, -closing, rel_tol=0, abs_tol=1e-14 * speeds)
    tangent = np.array([-normal[1], normal[0]])
    assert math.isclose(float(after1 @ tangent), float(v1 @ tangent), abs_tol=1e-14 * speeds)


@settings(derandomize=True, database=None, deadline=None, max_examples=60)
@given(
    st.floats(0.0, 0.5),  # distance rolled before the contact, m
    st.floats(-0.999, 0.999),  # where the line of centres meets the cue's path (sin of cut)
    st.floats(0.2, 15.0),  # cue speed, m/s
    mass,
    mass,
    st.floats(-3.0, 3.0),  # object ball's own speed along y, m/s
)
def test_simulated_two_ball_contact_keeps_every_invariant(
    distance: float, cut: float, cue_speed: float, m1: float, m2: float, object_vy: float
) -> None:
    # The cue rolls along +x towards the object ball; `cut` offsets it sideways so the
    # contact is anywhere from head-on to a bare graze; the object ball may be moving.
    start = np.array([0.4, TABLE[1] / 2])
    target = start + np.array([distance + 2 * R * math.sqrt(1 - cut * cut), 2 * R * cut])
    setup = make_setup(
        np.array([start, target]),
        np.array([(cue_speed, 0.0), (0.0, object_vy)]),
        np.array([m1, m2]),
    )
    result = run(setup)
    check_sound(result, setup)
    check_no_overlap(result, sample_times(result))
