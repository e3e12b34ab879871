"""The families of issue 30's two cascades (tests/physics/test_cascades.py), generated:

- creep: two touching balls, one creeping into, along or away from the other (every
  direction) at 1e-15 to 1e-3 m/s, sliding, rolling or spinning (rolling with a vertical
  spin), the other at rest or creeping too; either ball law, any restitution;
- cushion_held: a ball on a cushion line (every third in a corner), pressed into it by
  its own slip or a creep (or neither), and pressed by one or two touching neighbours,
  each driven into it by its slip or creeping into it; on a cushion of every law
  (mirror; Han 2005, Mathavan 2010 and its speed-dependent variant with friction 0.2
  and without); either ball law.

Each run is held to every invariant of tests/hard_checks.check_spin_case: ended by
itself (not by max_events) within 2 s of CPU, no overlap beyond 1e-9 m (naive's steps
too), nothing past a cushion, the energy never rising, momentum at every contact,
`exact` == `event` bit for bit. A seeded sample of each family runs by default;
`pytest -m hard` runs them all.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import CUSHION_LAWS
from billiards.physics.spin.motion import rolling_spin
from billiards.rules.seed import GRAVITY
from tests.hard_checks import TABLE, R, check_spin_case, generate_families, make_setup

FAMILIES = {"creep": 360, "cushion_held": 280}
SAMPLE = {"creep": 4, "cushion_held": 4}
SAMPLE_SEED = 20261203
MOTIONS = ("sliding", "rolling", "spinning")
# (cushion law, its friction) of the held ball's cushion: every law, with friction and
# without (mirror has none).
CUSHIONS = (
    ("mirror", 0.2),
    *((law, friction) for law in CUSHION_LAWS if law != "mirror" for friction in (0.2, 0.0)),
)


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    generate_families(metafunc, FAMILIES, SAMPLE, SAMPLE_SEED)


def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def creep_speed(rng: np.random.Generator) -> float:
    """1e-15 to 1e-3 m/s, uniform in its logarithm."""
    return float(10 ** rng.uniform(-15.0, -3.0))


def spin_of(velocity: np.ndarray, motion: str, rng: np.random.Generator) -> np.ndarray:
    """A ball's spin (3,) at `velocity`: none (sliding), rolling, or rolling with a
    vertical spin of 1e-3 to 100 rad/s either way (spinning)."""
    spin = np.zeros(3)
    if motion != "sliding":
        spin[:2] = rolling_spin(velocity, R)
    if motion == "spinning":
        spin[2] = float(rng.choice([-1.0, 1.0])) * 10 ** rng.uniform(-3.0, 2.0)
    return spin


def slip_spin(direction: np.ndarray, slip: float) -> np.ndarray:
    """The spin (3,) of a ball at rest whose contact with the cloth slips at `slip`
    along `direction`: its friction drives it the other way."""
    u = slip * direction
    return np.array([u[1] / R, -u[0] / R, 0.0])


def physics(rng: np.random.Generator, ball_law: str) -> dict[str, Any]:
    return {
        "model": "spin",
        "ball_law": ball_law,
        "restitution": float(rng.choice([1.0, 0.9, 0.5, 0.0])),
        "retention": float(rng.choice([0.75, 1.0, 0.0])),
        "slide_decel": 0.2 * GRAVITY * float(rng.choice([1.0, 0.25])),
    }


def creep_case(index: int) -> Setup:
    """Two touching balls anywhere on the table (away from the cushions); the first
    creeps at 1e-15 to 1e-3 m/s in any direction (into, along or away from the
    other), sliding, rolling or spinning by the case; a third of the second balls
    creep too (0.1 to 10 times as fast, any direction, the same motion)."""
    rng = np.random.default_rng([SAMPLE_SEED, 1, index])
    motion = MOTIONS[index % 3]
    ball_law = ("frictionless", "frictional")[index // 3 % 2]
    first = np.array([rng.uniform(0.2, TABLE[0] - 0.2), rng.uniform(0.2, TABLE[1] - 0.2)])
    bearing = rng.uniform(0.0, 2 * math.pi)
    second = first + 2 * R * unit(bearing)
    speed = creep_speed(rng)
    velocities = np.zeros((2, 2))
    velocities[0] = speed * unit(bearing + rng.uniform(-math.pi, math.pi))
    if index // 6 % 3 == 2:
        velocities[1] = speed * 10 ** rng.uniform(-1.0, 1.0) * unit(rng.uniform(0, 2 * math.pi))
    spins = np.array([spin_of(velocity, motion, rng) for velocity in velocities])
    return make_setup(np.array([first, second]), velocities, spins=spins, **physics(rng, ball_law))


def cushion_held_case(index: int) -> Setup:
    """A ball on a cushion line (every third case in a corner, on two), by the case at
    rest, pressed into its cushion by its slip (1e-6 to 3 m/s), or creeping into it
    (1e-15 to 1e-3 m/s, rolling); one or two neighbours touching it within 70 degrees
    of its cushion's inward normal, each pressed into it by its slip (1e-6 to 3 m/s,
    within 70 degrees of the line of centres) or creeping into it (sliding or
    rolling). The cushion is of any law (CUSHIONS), with friction 0.2 or 0."""
    rng = np.random.default_rng([SAMPLE_SEED, 2, index])
    law, friction = CUSHIONS[index % len(CUSHIONS)]
    count = 2 + index // len(CUSHIONS) % 2
    ball_law = ("frictionless", "frictional")[index // (2 * len(CUSHIONS)) % 2]
    while True:
        wall = int(rng.integers(4))
        axis, high = wall // 2, wall % 2
        held = np.array([rng.uniform(0.2, TABLE[0] - 0.2), rng.uniform(0.2, TABLE[1] - 0.2)])
        held[axis] = TABLE[axis] - R if high else R
        inward = np.zeros(2)
        inward[axis] = -1.0 if high else 1.0
        if index % 3 == 0:  # in a corner: on the other cushion line too
            other = 1 - axis
            corner_high = bool(rng.integers(2))
            held[other] = TABLE[other] - R if corner_high else R
            inward[other] = -1.0 if corner_high else 1.0
            inward /= math.sqrt(2.0)
        centre = math.atan2(inward[1], inward[0])
        placed = [held]
        for _ in range(count - 1):
            placed.append(held + 2 * R * unit(centre + rng.uniform(-1.22, 1.22)))
        positions = np.array(placed)
        inside = np.all(positions >= R) and np.all(positions <= np.array(TABLE) - R)
        apart = count < 3 or math.dist(placed[1], placed[2]) >= 2 * R
        if inside and apart:
            break
    velocities = np.zeros((count, 2))
    spins = np.zeros((count, 3))
    way = rng.integers(3)  # the held ball: at rest, pressed by its slip, or creeping
    if way == 1:
        spins[0] = slip_spin(inward, float(10 ** rng.uniform(-6.0, 0.5)))
    elif way == 2:
        velocities[0] = -creep_speed(rng) * inward
        spins[0] = spin_of(velocities[0], "rolling", rng)
    for k in range(1, count):
        into = (held - positions[k]) / (2 * R)
        if rng.random() < 0.5:
            angle = math.atan2(into[1], into[0]) + rng.uniform(-1.22, 1.22)
            spins[k] = slip_spin(-unit(angle), float(10 ** rng.uniform(-6.0, 0.5)))
        else:
            velocities[k] = creep_speed(rng) * into
            spins[k] = spin_of(velocities[k], str(rng.choice(["sliding", "rolling"])), rng)
    return make_setup(
        positions,
        velocities,
        spins=spins,
        cushion_law=law,
        cushion_friction=friction,
        **physics(rng, ball_law),
    )


def test_a_creeping_touching_pair_comes_to_rest(creep: int) -> None:
    """Most pairs make one contact; a rolling or spinning striker, stopped by an elastic
    (soft) contact, is driven on by its spin into the ball it struck, each impact 2/7
    of the last, until the approach falls below the rounding floor (8 eps of the
    speeds): at most log(1 / (8 eps)) / log(7 / 2) = 27 contacts more (24 measured)."""
    result = check_spin_case(creep_case(creep))
    assert len(result.events) <= 30, f"{len(result.events)} contacts"


def test_a_ball_held_on_a_cushion_and_pressed_comes_to_rest(cushion_held: int) -> None:
    result = check_spin_case(cushion_held_case(cushion_held))
    assert len(result.events) <= 120, f"{len(result.events)} contacts"  # 80 measured
