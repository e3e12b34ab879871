"""Han 2005's cushion (laws.cushion.han2005): energy never rises, english changes the
rebound angle symmetrically, and a ball without spin comes straight back."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.laws.cushion import CushionConstants, CushionContact, han2005
from billiards.rules.seed import CUSHION_HEIGHT, MASS, RADIUS
from tests.hard_checks import kinetic_energy

INTO = np.array([0.0, 1.0])  # the far long cushion (+y)


def bounce(
    velocity: list[float], spin: list[float], friction: float = 0.2
) -> tuple[np.ndarray, np.ndarray, float]:
    constants = CushionConstants(RADIUS, 1.0, 0.85, friction, CUSHION_HEIGHT, 0.0, 1.0)
    balls = CushionContact(np.array([velocity]), np.array([spin]), INTO[None], np.array([MASS]))
    velocities, spins, approaches = han2005(balls, constants)
    return velocities[0], spins[0], float(approaches[0])


def energy(velocity: np.ndarray, spin: np.ndarray) -> float:
    return kinetic_energy(np.array([MASS]), velocity[None], spin[None], RADIUS)


def test_energy_never_rises_over_random_strikes() -> None:
    rng = np.random.default_rng(2005)
    for _ in range(2000):
        velocity = rng.uniform(-5, 5, 2)
        velocity[1] = abs(velocity[1]) + 1e-3  # into the cushion
        spin = rng.uniform(-300, 300, 3)
        after_v, after_w, approach = bounce(velocity.tolist(), spin.tolist(), rng.uniform(0, 1))
        assert approach == pytest.approx(velocity[1])
        assert energy(after_v, after_w) <= energy(velocity, spin) * (1 + 1e-12)
        assert after_v[1] <= 0  # it leaves (or slides along), never on into the cushion


def test_a_ball_without_spin_head_on_comes_straight_back() -> None:
    after_v, _, _ = bounce([0.0, 2.0], [0.0, 0.0, 0.0])
    assert after_v[0] == 0.0 and after_v[1] < 0


def test_english_changes_the_rebound_angle_and_mirror_english_mirrors_it() -> None:
    plain, _, _ = bounce([0.0, 2.0], [0.0, 0.0, 0.0])
    left, _, _ = bounce([0.0, 2.0], [0.0, 0.0, 40.0])
    right, _, _ = bounce([0.0, 2.0], [0.0, 0.0, -40.0])
    assert abs(left[0]) > 0.05 and left[0] == pytest.approx(-right[0], abs=1e-12)
    assert left[1] == pytest.approx(right[1], abs=1e-12) and plain[0] == 0.0
    # Counter-clockwise spin (seen from above) grips the +y cushion and throws the ball
    # towards +x, as the contact point slips towards -x.
    assert left[0] > 0
