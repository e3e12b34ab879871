"""Mathavan et al. 2010's cushion (laws.mathavan2010, laws.cushion.mathavan2010):
energy never rises, the frictionless limits, the step converges, the paper's rolling
shots, symmetry, whole runs that keep every invariant of the spin model, and the
integration's bits: those it gave as first written, on random impacts (by digest) and
on a step whose stage lands on a zero slip."""

from __future__ import annotations

import hashlib
import math
from dataclasses import replace

import numpy as np
import pytest

from billiards.physics.laws import cushion
from billiards.physics.laws.cushion import CushionConstants, CushionContact, mathavan2010
from billiards.physics.laws.mathavan2010 import STEPS_PER_MOMENTUM, rebound
from billiards.rules.seed import CUSHION_HEIGHT, MASS, RADIUS
from tests.hard_checks import kinetic_energy
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


# --- the integration's bits ----------------------------------------------------------------


def random_impacts(seed: int, count: int) -> dict[str, np.ndarray]:
    """`count` rows of cushion impacts (mathavan2010_rows' arguments by name, each
    constant one a row, v_c too), drawn to reach every branch of the integration: any direction
    and speed, spins from none to +-200 rad/s, rolling (with and without side), stun,
    square on; the four cushions' normals and oblique ones (a jaw's); e_e, mu_w and mu_s
    over their ranges and at their ends; noses from the equator up; a few rows moving
    away or along the cushion. Only + - * / and sqrt: the same rows on every machine."""
    rng = np.random.default_rng(seed)
    axes = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])[rng.integers(0, 4, count)]
    oblique = rng.uniform(-1.0, 1.0, (count, 2)) + 1e-3
    oblique /= np.sqrt(oblique[:, 0] * oblique[:, 0] + oblique[:, 1] * oblique[:, 1])[:, None]
    into = np.where((rng.random(count) < 0.75)[:, None], axes, oblique)
    along = np.stack((-into[:, 1], into[:, 0]), axis=1)
    radius = rng.choice([PAPER_R, 0.028575, 0.03075], count)
    mass = rng.choice([PAPER_M, 0.17, 0.21], count)
    height = radius * rng.choice([1.0, 1.2033, 1.4, 1.0 + rng.uniform(0.0, 0.7)], count)
    speed = rng.uniform(0.02, 6.0, count)
    share = rng.uniform(-1.0, 1.0, count)  # of the speed along the cushion
    velocity = (np.sqrt(1.0 - share * share) * speed)[:, None] * into
    velocity += (share * speed)[:, None] * along
    kind = rng.integers(0, 6, count)  # square on rolling, rolling, rolling with side, stun
    velocity[kind == 0] = speed[kind == 0, None] * into[kind == 0]
    away = rng.random(count) < 0.05
    velocity[away] = -velocity[away]
    grazing = rng.random(count) < 0.02
    velocity[grazing] = speed[grazing, None] * along[grazing]
    spin = rng.uniform(-200.0, 200.0, (count, 3))
    rolling = np.stack((-velocity[:, 1], velocity[:, 0], np.zeros(count)), axis=1) / radius[:, None]
    spin[kind <= 2, :2] = rolling[kind <= 2, :2]
    spin[kind <= 1, 2] = 0.0
    spin[kind == 3] = 0.0
    ends = rng.random((count, 3))
    restitution = np.where(ends[:, 0] < 0.05, 0.0, rng.uniform(0.0, 1.0, count))
    restitution[ends[:, 0] > 0.95] = 1.0
    friction = np.where(ends[:, 1] < 0.1, 0.0, rng.uniform(0.0, 0.35, count))
    table_friction = np.where(ends[:, 2] < 0.1, 0.0, rng.uniform(0.0, 0.35, count))
    restitution_speed = rng.uniform(0.5, 6.0, count)
    return {
        "velocities": velocity, "spins": spin, "into": into, "masses": mass, "radius": radius,
        "restitution": restitution, "friction": friction, "height": height,
        "table_friction": table_friction, "restitution_speed": restitution_speed,
    }  # fmt: skip


def mathavan2010_rows(
    velocities: np.ndarray,
    spins: np.ndarray,
    into: np.ndarray,
    masses: np.ndarray,
    radius: float | np.ndarray,
    restitution: float | np.ndarray,
    friction: float | np.ndarray,
    height: float | np.ndarray,
    table_friction: float | np.ndarray,
    restitution_speed: float | np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The law on rows given by name, as the digests were first taken (mathavan2010_ev
    when a restitution speed is given)."""
    constants = CushionConstants(
        radius, 0.75, restitution, friction, height, table_friction,
        1.0 if restitution_speed is None else restitution_speed,
    )  # fmt: skip
    balls = CushionContact(velocities, spins, into, masses)
    return mathavan2010(balls, constants, speed_dependent=restitution_speed is not None)


def impacts_digest(count: int, speed_dependent: bool) -> str:
    """The sha256 of mathavan2010_rows' results (or mathavan2010_ev's) on random_impacts,
    taken in calls of 1, 2, 3, 5, 8, ... rows, then of every row with the shipped carom
    table's constants (numbers, not rows)."""
    impacts = random_impacts(31, count)
    if not speed_dependent:
        del impacts["restitution_speed"]
    digest = hashlib.sha256()
    start, size, previous = 0, 1, 1
    while start < count:
        part = slice(start, start + size)
        out = mathavan2010_rows(**{name: value[part] for name, value in impacts.items()})
        for value in out:
            digest.update(np.ascontiguousarray(value, dtype="<f8").tobytes())
        start, size, previous = start + size, size + previous, size
    out = mathavan2010_rows(impacts["velocities"], impacts["spins"], impacts["into"],
                            impacts["masses"], 0.03075, 0.8725, 0.185, 0.037, 0.14125,
                            2.5 if speed_dependent else None)  # fmt: skip
    for value in out:
        digest.update(np.ascontiguousarray(value, dtype="<f8").tobytes())
    return digest.hexdigest()[:32]


# The digests of the integration as first written (row by row, a method call a stage,
# before it was written out for speed): every bit of every result is kept.
IMPACT_DIGESTS = {
    False: "e5edd80a5f830d610ddad2a549673df5",
    True: "17e7ab444f21c76fa7943a287474e5a7",
}


@pytest.mark.long
@pytest.mark.parametrize("speed_dependent", [False, True])
def test_random_impacts_keep_every_bit_of_the_first_integration(speed_dependent: bool) -> None:
    assert impacts_digest(600, speed_dependent) == IMPACT_DIGESTS[speed_dependent]


def test_a_slip_that_a_stage_lands_on_exactly_is_held_there_as_first_written() -> None:
    # Square on, no side: every slip keeps its line, and this top spin puts the cloth's
    # slip exactly at zero at the first step's second stage (its half step along the
    # first slope, which depends only on the slips' signs here). Both contacts slide at
    # the step's start, so the written-out step meets the zero (a division by it) and
    # hands the step to the one that holds that contact at rest: the first integration's
    # bits.
    mass, radius, height, mu_w, mu_s = 0.21, 0.03075, 0.037, 0.14, 0.2
    wx = float.fromhex("-0x1.03ce0fb1418d4p+5")
    s = height / radius - 1.0
    c = math.sqrt(1.0 - s * s)
    half = 0.5 * (mass * 1.0 / STEPS_PER_MOMENTUM)
    f2, g2 = -mu_w, mu_s * (s + c * -mu_w)  # the slip at the nose points down, the cloth's up
    a1, a2 = -(c - s * f2 + g2) / mass, -5.0 / (2.0 * mass * radius) * (f2 + g2)
    assert 1.0 + radius * wx > 0.0  # it slides at the start...
    assert (1.0 + half * a1) + radius * (wx + half * a2) == 0.0  # ...and is held a stage on
    out = rebound((0.0, 1.0), (wx, 0.0, 0.0), mass, radius, height, 0.9, mu_w, mu_s)
    assert [part.hex() for part in out] == [
        "0x0.0p+0", "-0x1.ccc6b5115c71ep-1", "-0x1.15a2339b99719p+3", "0x0.0p+0", "0x0.0p+0",
    ]  # fmt: skip
