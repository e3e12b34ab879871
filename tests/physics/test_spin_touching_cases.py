"""The spin model's touching balls (issue 22): generated families of balls that start
touching with spin of their own, each run held to every invariant of
tests/hard_checks.check_spin_case (no overlap beyond 1e-9 m, naive included; nothing
past a cushion, jaw or capture line; the energy never rising; momentum kept at every
ball-ball contact; no RuntimeWarning; under WALL_LIMIT s of CPU for fewer than 20 balls;
ended by itself, not by max_events; `exact` == `event` bit for bit).

- rest_cluster: 2 to 6 balls at rest, touching, with random spins (a slip at rest
  slides a ball into its neighbour);
- cushion_press: a ball held by a cushion, a neighbour touching it that its slip drives
  into it (and sometimes a third behind);
- moving_pair: two touching balls moving together (relative speed 0 to 1e-6 m/s), follow
  behind and draw in front, so their slips press them together;
- tiny: denormal and tiny speeds (5e-324 to 1e-9 m/s) with large spins, alone or
  touching;
- frozen_shot: a cue ball touching an object ball, struck with follow or draw (`tip`),
  straight or cut, sometimes a third ball near.

A seeded sample of each family runs by default; `pytest -m hard` runs them all. The
cases that still fail are strict xfails, each with what fails (XFAIL below), so fixing
one flags it to be unmarked.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.pockets import PocketTable, pocket_of, pocket_table
from billiards.physics.spin.motion import tip_spin
from billiards.rules.seed import GRAVITY
from tests.hard_checks import TABLE, R, check_spin_case, generate_families, make_setup
from tests.physics.test_hard_cases import touching_cluster

FAMILIES = {
    "rest_cluster": 120,
    "cushion_press": 80,
    "moving_pair": 80,
    "tiny": 60,
    "frozen_shot": 100,
}
SAMPLE = {"rest_cluster": 2, "cushion_press": 2, "moving_pair": 2, "tiny": 2, "frozen_shot": 2}
SAMPLE_SEED = 20261201
POCKETS = pocket_table(TABLE, R)

# family -> {case: what still fails}: strict xfails. None now: on the spin model's own
# calendar 235 of the 440 cases failed (overlaps up to 57 mm, runs of up to 14,507
# events); on the one calendar with hold and push 4 (test_the_last_four_... below).
XFAIL: dict[str, dict[int, str]] = {}
# Of those, the cases whose only failure is a CPU time near WALL_LIMIT: not strict.
LENIENT: dict[str, set[int]] = {}


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    generate_families(metafunc, FAMILIES, SAMPLE, SAMPLE_SEED, XFAIL, LENIENT)


# --- building blocks ---------------------------------------------------------------------


def physics(rng: np.random.Generator) -> dict[str, Any]:
    """Random physics for a case: ball restitution, cushion law and retention, sliding
    friction (x0.25 to x2.5 of the default)."""
    law = str(rng.choice(["mirror", "han2005"]))
    return {
        "model": "spin",
        "restitution": float(rng.choice([1.0, 0.95, 0.5, 0.0])),
        "cushion_law": law,
        "retention": float(rng.choice([0.75, 1.0, 0.0])),
        "slide_decel": 0.2 * GRAVITY * float(rng.choice([1.0, 0.25, 2.5])),
    }


def on_table(positions: np.ndarray, pockets: PocketTable | None) -> bool:
    """Every centre inside the cushion lines, and with pockets outside every jaw's reach
    and before every capture line."""
    low = np.array([R, R])
    high = np.array(TABLE) - R
    if not (np.all(positions >= low) and np.all(positions <= high)):
        return False
    if pockets is None:
        return True
    offset = positions[:, None, :] - pockets.jaws[None]
    clear = np.hypot(offset[..., 0], offset[..., 1]) > pockets.jaw_reach
    return bool(clear.all() and np.all(pocket_of(pockets, positions) < 0))


def random_spins(rng: np.random.Generator, count: int, scale: float) -> np.ndarray:
    """Spins (count, 3) up to `scale` rad/s on each axis; a third of the balls none."""
    spins = rng.uniform(-scale, scale, (count, 3))
    spins[rng.random(count) < 1 / 3] = 0.0
    return spins


def slip_spin(direction: np.ndarray, slip: float) -> np.ndarray:
    """w_xy of a ball at rest whose contact point slips at `slip` along `direction`
    (u = R (-w_y, w_x)): friction then drives the ball the other way."""
    u = slip * direction
    return np.array([u[1] / R, -u[0] / R])


def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


# --- the families --------------------------------------------------------------------------


def rest_cluster_case(index: int) -> Setup:
    """2 to 6 balls at rest, touching (a pair, a chain, a clump), anywhere on the table or
    against a cushion, each with a random spin up to 30 to 300 rad/s per axis (or none);
    a fifth of them on a table with pockets."""
    rng = np.random.default_rng([SAMPLE_SEED, 1, index])
    pockets = POCKETS if index % 5 == 4 else None
    count = int(rng.integers(2, 7))
    while True:
        centre = np.array([rng.uniform(0.15, TABLE[0] - 0.15), rng.uniform(0.15, TABLE[1] - 0.15)])
        if index % 4 == 1:  # the first ball on a cushion line
            centre[1] = R
        positions = touching_cluster(rng, count, centre)
        if on_table(positions, pockets):
            break
    spins = random_spins(rng, count, float(rng.choice([30.0, 100.0, 300.0])))
    return make_setup(
        positions, np.zeros_like(positions), spins=spins, pockets=pockets, **physics(rng)
    )


def cushion_press_case(index: int) -> Setup:
    """A ball at rest on a cushion line (perhaps spinning), a neighbour touching it at up
    to 70 degrees off the cushion's normal whose slip (0.05 to 6 m/s, aimed within 70
    degrees of the line of centres) drives it into the held ball; every third case a
    third ball behind the second, driven the same way."""
    rng = np.random.default_rng([SAMPLE_SEED, 2, index])
    pockets = POCKETS if index % 5 == 4 else None
    while True:
        wall = int(rng.integers(4))
        axis, high = wall // 2, wall % 2
        held = np.array([rng.uniform(0.2, TABLE[0] - 0.2), rng.uniform(0.2, TABLE[1] - 0.2)])
        held[axis] = TABLE[axis] - R if high else R
        inward = np.zeros(2)
        inward[axis] = -1.0 if high else 1.0
        bearing = math.atan2(inward[1], inward[0]) + rng.uniform(-1.2, 1.2)
        second = held + 2 * R * unit(bearing)
        positions = [held, second]
        if index % 3 == 0:
            positions.append(second + 2 * R * unit(bearing + rng.uniform(-0.5, 0.5)))
        placed = np.array(positions)
        if on_table(placed, pockets):
            break
    count = len(placed)
    spins = np.zeros((count, 3))
    spins[0] = random_spins(rng, 1, 50.0)[0]
    for k in range(1, count):
        towards = placed[k - 1] - placed[k]
        angle = math.atan2(towards[1], towards[0]) + rng.uniform(-1.2, 1.2)
        # Friction drives the ball against its slip: slip away from the ball in front.
        spins[k, :2] = slip_spin(-unit(angle), float(10 ** rng.uniform(math.log10(0.05), 0.78)))
        spins[k, 2] = rng.uniform(-100.0, 100.0)
    return make_setup(placed, np.zeros_like(placed), spins=spins, pockets=pockets, **physics(rng))


def moving_pair_case(index: int) -> Setup:
    """Two touching balls moving together at 0.02 to 5 m/s, their line of centres within
    60 degrees of the motion, relative speed 0, 1e-12, 1e-9 or 1e-6 m/s in any direction;
    the one behind struck with follow, the one in front with draw or stun, so slip
    drives the back one on and holds the front one back."""
    rng = np.random.default_rng([SAMPLE_SEED, 3, index])
    pockets = POCKETS if index % 5 == 4 else None
    heading = rng.uniform(0, 2 * math.pi)
    while True:
        back = np.array([rng.uniform(0.3, TABLE[0] - 0.3), rng.uniform(0.3, TABLE[1] - 0.3)])
        front = back + 2 * R * unit(heading + rng.uniform(-1.05, 1.05))
        positions = np.array([back, front])
        if on_table(positions, pockets):
            break
    speed = float(10 ** rng.uniform(math.log10(0.02), math.log10(5.0)))
    velocities = np.repeat(speed * unit(heading)[None], 2, axis=0)
    relative = float(rng.choice([0.0, 1e-12, 1e-9, 1e-6]))
    velocities[0] += relative * unit(rng.uniform(0, 2 * math.pi))
    tips = np.array(
        [
            [rng.uniform(-0.3, 0.3), rng.uniform(0.45, 0.8)],
            [rng.uniform(-0.3, 0.3), rng.uniform(-0.8, 0.0)],
        ]
    )
    spins = tip_spin(velocities, tips, R)
    return make_setup(positions, velocities, spins=spins, pockets=pockets, **physics(rng))


TINY_SPEEDS = (5e-324, 1e-320, 1e-310, 1e-300, 1e-200, 1.5e-162, 1e-160, 1e-100, 1e-20, 1e-12, 1e-9)


def tiny_case(index: int) -> Setup:
    """1 to 3 balls (touching when more than one) with denormal or tiny speeds, from
    5e-324 to 1e-9 m/s, and spins of 100 to 1000 rad/s on any axes (one ball's spin
    vertical only, one's horizontal only, in some cases)."""
    rng = np.random.default_rng([SAMPLE_SEED, 4, index])
    pockets = POCKETS if index % 5 == 4 else None
    count = int(rng.integers(1, 4))
    while True:
        centre = np.array([rng.uniform(0.2, TABLE[0] - 0.2), rng.uniform(0.2, TABLE[1] - 0.2)])
        positions = touching_cluster(rng, count, centre)
        if on_table(positions, pockets):
            break
    speeds = rng.choice(TINY_SPEEDS, count)
    angles = rng.uniform(0, 2 * math.pi, count)
    velocities = speeds[:, None] * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    spins = rng.uniform(-1.0, 1.0, (count, 3)) * float(rng.choice([100.0, 1000.0]))
    if index % 3 == 1:
        spins[0, :2] = 0.0
    if index % 3 == 2:
        spins[0, 2] = 0.0
    return make_setup(positions, velocities, spins=spins, pockets=pockets, **physics(rng))


def frozen_shot_case(index: int) -> Setup:
    """A cue ball touching an object ball (gap 0, or 1e-12 m), struck at 0.2 to 8 m/s
    straight through it or cut at up to 60 degrees, with follow (tip height 0.2 to 0.8)
    or draw (-0.8 to -0.1) and some side; every third case a third ball touching the
    object ball or near it; a fifth of them on a table with pockets."""
    rng = np.random.default_rng([SAMPLE_SEED, 5, index])
    pockets = POCKETS if index % 5 == 4 else None
    while True:
        cue = np.array([rng.uniform(0.15, TABLE[0] - 0.15), rng.uniform(0.15, TABLE[1] - 0.15)])
        bearing = rng.uniform(0, 2 * math.pi)
        gap = float(rng.choice([0.0, 0.0, 1e-12]))
        target = cue + (2 * R + gap) * unit(bearing)
        positions = [cue, target]
        if index % 3 == 0:
            near = float(rng.choice([0.0, 0.0, 1e-4, 0.02]))
            positions.append(target + (2 * R + near) * unit(bearing + rng.uniform(-1.0, 1.0)))
        placed = np.array(positions)
        apart = all(
            math.dist(placed[i], placed[j]) >= 2 * R - 1e-15
            for i in range(len(placed))
            for j in range(i)
        )
        if apart and on_table(placed, pockets):
            break
    count = len(placed)
    velocities = np.zeros((count, 2))
    cut = 0.0 if rng.random() < 0.3 else rng.uniform(-1.05, 1.05)
    velocities[0] = float(rng.uniform(0.2, 8.0)) * unit(bearing + cut)
    tips = np.zeros((count, 2))
    height = rng.uniform(0.2, 0.8) if index % 2 else rng.uniform(-0.8, -0.1)
    tips[0] = (0.0 if rng.random() < 0.5 else rng.uniform(-0.5, 0.5), height)
    spins = tip_spin(velocities, tips, R)
    return make_setup(placed, velocities, spins=spins, pockets=pockets, **physics(rng))


# --- the tests -----------------------------------------------------------------------------


def test_touching_balls_at_rest_with_spin_keep_every_invariant(rest_cluster: int) -> None:
    check_spin_case(rest_cluster_case(rest_cluster))


def test_a_ball_pressed_by_slip_against_a_held_ball_keeps_every_invariant(
    cushion_press: int,
) -> None:
    check_spin_case(cushion_press_case(cushion_press))


def test_a_pair_moving_together_pressed_by_slip_keeps_every_invariant(moving_pair: int) -> None:
    check_spin_case(moving_pair_case(moving_pair))


@pytest.mark.long
def test_tiny_speeds_with_large_spins_keep_every_invariant(tiny: int) -> None:
    check_spin_case(tiny_case(tiny))


def test_frozen_follow_and_draw_shots_keep_every_invariant(frozen_shot: int) -> None:
    check_spin_case(frozen_shot_case(frozen_shot))


@pytest.mark.parametrize(
    ("family", "case"),
    [
        ("moving_pair", 67),
        ("moving_pair", 74),
        # 12-24 s of checks each (a minute's run sampled): under -m hard, and test_held's
        # rolling ball slowing into a tangential slider holds their class by default.
        pytest.param("tiny", 25, marks=pytest.mark.hard),
        pytest.param("tiny", 43, marks=pytest.mark.hard),
    ],
)
def test_the_last_four_cases_keep_every_invariant(family: str, case: int) -> None:
    # The last to fail (docs/touching.md, section 6): two pairs moving together, follow
    # behind and draw in front, bounced at ELASTIC_BELOW every few us (3,473 and 14,494
    # contacts) until soft contacts were held too; a rolling ball slowed into a
    # neighbour sliding along their tangent (1.6e-6 m and 1.1 mm deep) until `part`.
    builders = {"moving_pair": moving_pair_case, "tiny": tiny_case}
    check_spin_case(builders[family](case))
