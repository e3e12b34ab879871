"""Mathavan et al. 2010's cushion (laws.mathavan2010, laws.cushion.mathavan2010):
energy never rises, the frictionless limits, the step converges, the paper's rolling
shots, symmetry, and whole runs that keep every invariant of the spin model."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from billiards.physics.laws import cushion
from billiards.physics.laws.cushion import CushionConstants, CushionContact, mathavan2010
from billiards.physics.laws.mathavan2010 import STEPS_PER_MOMENTUM, rebound
from billiards.physics.spin.motion import kinetic_energy
from billiards.seed import CUSHION_HEIGHT, MASS, RADIUS
from tests.physics.test_spin_hard_cases import check_spin_invariants, english

# The paper's snooker ball, its nose at 7R/5, e_e = 0.98, mu_w = 0.14 (and mu_s = 0.2).
PAPER_R, PAPER_M = 0.02625, 0.1406
PAPER_H = 7 * PAPER_R / 5
INTO = np.array([0.0, 1.0])  # the far long cushion (+y)


def bounce(
    velocity: list[float],
    spin: list[float],
    restitution: float = 0.98,
    friction: float = 0.14,
    table_friction: float = 0.2,
) -> tuple[np.ndarray, np.ndarray, float]:
    constants = CushionConstants(
        RADIUS, 1.0, restitution, friction, CUSHION_HEIGHT, table_friction, 1.0
    )
    balls = CushionContact(np.array([velocity]), np.array([spin]), INTO[None], np.array([MASS]))
    velocities, spins, approaches = mathavan2010(balls, constants)
    return velocities[0], spins[0], float(approaches[0])


def energy(velocity: np.ndarray, spin: np.ndarray) -> float:
    return kinetic_energy(np.array([MASS]), velocity[None], spin[None], RADIUS)


def rolling(speed: float, steps: int = STEPS_PER_MOMENTUM) -> tuple[float, ...]:
    """The paper's shot: a rolling ball square into the cushion (its frame: y into it)."""
    return rebound((0.0, speed), (-speed / PAPER_R, 0.0, 0.0), PAPER_M, PAPER_R, PAPER_H,
                   0.98, 0.14, 0.2, steps)  # fmt: skip


def test_energy_never_rises_over_random_strikes() -> None:
    rng = np.random.default_rng(2010)
    for _ in range(150):
        velocity = rng.uniform(-4, 4, 2)
        velocity[1] = abs(velocity[1]) + 1e-2  # into the cushion
        spin = rng.uniform(-150, 150, 3)
        after_v, after_w, approach = bounce(
            velocity.tolist(), spin.tolist(), rng.uniform(0, 1), rng.uniform(0, 0.3),
            rng.uniform(0, 0.3),
        )  # fmt: skip
        assert approach == velocity[1]
        assert energy(after_v, after_w) <= energy(velocity, spin) * (1 + 1e-12)
        assert after_v[1] <= 0  # it leaves (or slides along), never on into the cushion


def test_without_friction_it_is_newtons_rebound_and_the_spin_passes() -> None:
    velocity, spin = [0.7, 1.9], [12.0, -30.0, 45.0]
    after_v, after_w, _ = bounce(velocity, spin, 0.9, 0.0, 0.0)
    assert after_v[1] == pytest.approx(-0.9 * 1.9, rel=1e-13)
    assert after_v[0] == velocity[0] and list(after_w) == spin


def test_without_cushion_friction_the_side_spin_passes() -> None:
    # Only the cushion's friction has an arm about the vertical; the cloth's has none.
    _, after_w, _ = bounce([0.7, 1.9], [12.0, -30.0, 45.0], 0.9, 0.0, 0.2)
    assert after_w[2] == 45.0


def test_friction_only_takes_energy_away() -> None:
    plain_v, plain_w, _ = bounce([0.7, 1.9], [12.0, -30.0, 45.0], 0.98, 0.0, 0.0)
    gripped_v, gripped_w, _ = bounce([0.7, 1.9], [12.0, -30.0, 45.0], 0.98, 0.14, 0.2)
    assert energy(gripped_v, gripped_w) < energy(plain_v, plain_w)


def test_a_ball_moving_away_passes_unchanged() -> None:
    after_v, after_w, approach = bounce([0.5, -1.0], [1.0, 2.0, 3.0])
    assert list(after_v) == [0.5, -1.0] and list(after_w) == [1.0, 2.0, 3.0] and approach == 0.0


def test_a_rolling_ball_square_on_comes_straight_back_without_side_spin() -> None:
    # pooltool takes atan2(0, 0) = 0 for the cloth's slip, which starts at zero for a
    # rolling ball: a sideways push. Here a slip at rest takes the friction that holds it.
    vx, vy, _wx, wy, wz = rolling(1.0)
    assert (vx, wy, wz) == (0.0, 0.0, 0.0) and vy < 0


def test_mirror_english_mirrors_the_rebound() -> None:
    left, left_w, _ = bounce([0.4, 1.5], [-10.0, 5.0, 40.0])
    right, right_w, _ = bounce([-0.4, 1.5], [-10.0, -5.0, -40.0])
    assert left[0] == pytest.approx(-right[0], abs=1e-12)
    assert left[1] == pytest.approx(right[1], abs=1e-12)
    assert left_w[2] == pytest.approx(-right_w[2], abs=1e-9)


@pytest.mark.parametrize("speed", [0.263, 1.3, 3.0])
def test_the_rolling_shots_are_exact_at_any_step(speed: float) -> None:
    # Square on, every slip keeps its line: the slopes are constant between the slips'
    # zeros, which the step is split at, so the step size changes only roundings.
    coarse, fine = rolling(speed, 16), rolling(speed, 1024)
    assert max(abs(a - b) for a, b in zip(coarse, fine, strict=True)) <= 1e-12 * speed / PAPER_R


def test_an_oblique_spinning_shot_converges_as_the_step_halves() -> None:
    def shot(steps: int) -> np.ndarray:
        return np.array(rebound((1.0, 1.2), (-45.0, 11.0, 25.0), PAPER_M, PAPER_R, PAPER_H,
                                0.98, 0.14, 0.2, steps))  # fmt: skip

    default, half = shot(STEPS_PER_MOMENTUM), shot(2 * STEPS_PER_MOMENTUM)
    assert np.abs(default[:2] - half[:2]).max() <= 1e-9  # m/s
    assert np.abs(default[2:] - half[2:]).max() * PAPER_R <= 1e-9  # the spins, as m/s
    # And it is a converging scheme, not a frozen one: a coarse step is visibly off.
    assert np.abs(shot(16)[:2] - half[:2]).max() > 1e-7


def test_the_rebound_ratio_does_not_depend_on_speed() -> None:
    # The equations are linear in the impulse, the step a share of the ball's momentum:
    # a constant e_e gives one ratio at every speed (the data bend: docs/validation.md).
    ratios = [-rolling(speed)[1] / speed for speed in (0.3, 1.0, 2.5)]
    assert max(ratios) - min(ratios) <= 1e-13


def test_the_papers_fit_reproduces_its_slow_rolling_rebounds() -> None:
    # Fig. 7(a)'s markers below 1.3 m/s, the shots e_e = 0.98 and mu_w = 0.14 were fitted
    # to (../shared/data/measured/mathavan2010_cushion_rebounds.csv): within 3.5% each.
    measured = [(0.262999, 0.234401), (0.354983, 0.323511), (0.418037, 0.383074),
                (0.650776, 0.583087), (0.704133, 0.665104), (0.844922, 0.790892),
                (1.153559, 1.068803), (1.299180, 1.236813)]  # fmt: skip
    errors = [abs(-rolling(v)[1] - out) / out for v, out in measured]
    assert max(errors) < 0.05 and sum(errors) / len(errors) < 0.025


def test_the_cushion_throws_a_rolling_ball_with_back_spin_off_it() -> None:
    # The nose above the centre stops the top spin harder than the ball: it leaves with
    # spin against its new path (the paper's Fig. 5), yet still turning the old way.
    _, vy, wx, _, _ = rolling(1.0)
    assert vy < 0 and -1.0 / PAPER_R < wx < 0


@pytest.mark.parametrize("case", [1, 3, 6])
def test_english_into_mathavan_cushions_keeps_every_invariant(case: int) -> None:
    check_spin_invariants(replace(english(case), cushion_law="mathavan2010"))


def test_an_angle_comes_from_the_nose_height_alone() -> None:
    # sin theta = h / R - 1: a nose at the equator is a wall, square on (no cloth push).
    _vx, vy, wx, _wy, _wz = rebound((0.0, 1.0), (0.0, 0.0, 0.0), PAPER_M, PAPER_R, PAPER_R,
                                 0.5, 0.0, 0.2, 64)  # fmt: skip
    assert vy == pytest.approx(-0.5, rel=1e-12) and wx == 0.0


def test_the_speed_dependent_restitution_bends_the_ratio_down_with_speed() -> None:
    def ratio(speed: float) -> float:
        velocities, _, _ = cushion.mathavan2010_ev(
            CushionContact(np.array([[0.0, speed]]), np.array([[-speed / PAPER_R, 0.0, 0.0]]),
                           INTO[None], np.array([PAPER_M])),
            CushionConstants(PAPER_R, 1.0, 0.9975, 0.14, PAPER_H, 0.2, 4.15),
        )  # fmt: skip
        return -float(velocities[0, 1]) / speed

    slow, middling, fast = ratio(0.3), ratio(1.5), ratio(3.2)
    assert slow > middling > fast
    # Slow, it is the constant law at e_e = e_0 (within (0.3 / 4.15)^4 / 2 of it).
    assert slow == pytest.approx(-rebound((0.0, 0.3), (-0.3 / PAPER_R, 0.0, 0.0), PAPER_M,
                                          PAPER_R, PAPER_H, 0.9975, 0.14, 0.2)[1] / 0.3,
                                 rel=2e-5)  # fmt: skip
    # At v_c, e_e is e_0 / sqrt(2): as the constant law there.
    at_vc = ratio(4.15)
    constant = -rebound((0.0, 4.15), (-4.15 / PAPER_R, 0.0, 0.0), PAPER_M, PAPER_R, PAPER_H,
                        0.9975 / math.sqrt(2.0), 0.14, 0.2)[1] / 4.15  # fmt: skip
    assert at_vc == pytest.approx(constant, rel=1e-12)


def test_mathavan2010_ev_keeps_energy_and_every_invariant() -> None:
    setup = replace(english(5), cushion_law="mathavan2010_ev", cushion_restitution=0.9975)
    check_spin_invariants(setup)


def test_the_noses_friction_moves_and_turns_the_ball_by_one_impulse() -> None:
    # On a frictionless cloth only the nose's friction acts along the cushion (x): it
    # moves the ball by -F/m and turns its side spin by R cos(theta) F / I, one F.
    cos_t = math.sqrt(1.0 - (CUSHION_HEIGHT / RADIUS - 1.0) ** 2)
    rng = np.random.default_rng(12)
    for _ in range(20):
        velocity = [rng.uniform(-2, 2), rng.uniform(0.1, 3)]
        spin = rng.uniform(-80, 80, 3).tolist()
        after_v, after_w, _ = bounce(velocity, spin, rng.uniform(0.5, 1), 0.2, 0.0)
        moved, turned = after_v[0] - velocity[0], after_w[2] - spin[2]
        assert turned == pytest.approx(-2.5 * cos_t / RADIUS * moved, rel=1e-9, abs=1e-9)


def test_the_cloths_friction_keeps_the_angular_momentum_about_the_contact() -> None:
    # With a frictionless nose, the nose pushes along its normal (no part along the
    # cushion) and the cloth's friction keeps v - (2/5) R z x w: along the cushion
    # v_x + (2/5) R w_y is kept while the cloth takes the ball's slip.
    rng = np.random.default_rng(13)
    for _ in range(20):
        velocity = [rng.uniform(-2, 2), rng.uniform(0.1, 3)]
        spin = rng.uniform(-80, 80, 3).tolist()
        after_v, after_w, _ = bounce(velocity, spin, rng.uniform(0.5, 1), 0.0, 0.3)
        kept = velocity[0] + 0.4 * RADIUS * spin[1]
        assert after_v[0] + 0.4 * RADIUS * after_w[1] == pytest.approx(kept, abs=1e-12)
