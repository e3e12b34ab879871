"""The frictional ball-ball law (laws.ball_ball.frictional) against Alciatore's throw
(TP A-14, with TP A-28's friction fit), and its invariants: momentum, energy, the
frictionless law recovered without friction, gearing english throwing nothing."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS
from billiards.physics.laws.ball_ball import PairContact, frictional, frictionless
from billiards.physics.numerics.arithmetic import exp
from billiards.rules.seed import BALL_FRICTION_A, BALL_FRICTION_B, BALL_FRICTION_C, MASS, RADIUS
from tests.hard_checks import kinetic_energy

R = RADIUS
SETUP = Setup.of([[0.0, 0.0], [1.0, 0.0]], ball_law="frictional", model="spin")
# TP A-14's three speeds: 1, 3 and 7 mph (0.447, 1.341, 3.129 m/s).
SLOW, MEDIUM, FAST = 0.44704, 1.34112, 3.12928
CUTS = [float(degrees) for degrees in range(0, 81, 5)]


def alciatore_mu(slip: float) -> float:
    """TP A-28's fit of Marlow's data: mu = a + b exp(-c v_rel)."""
    return BALL_FRICTION_A + BALL_FRICTION_B * math.exp(-BALL_FRICTION_C * slip)


def alciatore_throw(speed: float, cut: float, topspin: float, sidespin: float) -> float:
    """TP A-14's throw angle (radians) of an object ball at rest hit by a cue ball at
    `speed` with a cut angle `cut`, topspin w_x and side spin w_z (rad/s, TP A-14's
    axes: w_x about the horizontal axis across the cue ball's path):

        v_rel,x = v sin(phi) - R w_z,  v_rel,z = R w_x cos(phi),  v_rel = |v_rel|
        throw = atan(min(mu(v_rel) v cos(phi) / v_rel, 1/7) v_rel,x / (v cos(phi)))
    """
    across = speed * math.sin(cut) - R * sidespin
    vertical = R * topspin * math.cos(cut)
    relative = math.sqrt(across * across + vertical * vertical)
    if relative == 0:
        return 0.0
    normal = speed * math.cos(cut)
    return math.atan(min(alciatore_mu(relative) * normal / relative, 1 / 7) * across / normal)


def collide(
    speed: float,
    cut: float,
    cue_spin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    law: str = "frictional",
    restitution: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, float]:
    """The cue ball (ball 1) moving along +x at `speed` meets the object ball (ball 2),
    at rest with no spin, whose centre lies at `cut` from the cue ball's path (towards
    +y): the line of centres from ball 2 to ball 1 is -(cos cut, sin cut)."""
    normal = -np.array([math.cos(cut), math.sin(cut)])
    velocities = np.array([[speed, 0.0], [0.0, 0.0]])
    spins = np.array([cue_spin, (0.0, 0.0, 0.0)])
    masses = np.array([MASS, MASS])
    return BALL_LAWS[law](PairContact(normal, velocities, spins, masses), restitution, SETUP)


def throw_of(velocities: np.ndarray, cut: float) -> float:
    """How far (radians) the object ball leaves off the line of centres, towards the
    cue ball's side (positive: the cut is made thinner, as friction does)."""
    vx, vy = velocities[1]
    return cut - math.atan2(vy, vx)


def rolling(speed: float) -> tuple[float, float, float]:
    """A cue ball rolling along +x: w = z x v / R."""
    return (0.0, speed / R, 0.0)


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
@pytest.mark.parametrize("cut_degrees", CUTS)
def test_a_stun_shot_throws_the_object_ball_by_alciatores_tp_a14(
    speed: float, cut_degrees: float
) -> None:
    cut = math.radians(cut_degrees)
    velocities, _, _ = collide(speed, cut)
    assert throw_of(velocities, cut) == pytest.approx(
        alciatore_throw(speed, cut, 0.0, 0.0), abs=1e-13
    )


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
@pytest.mark.parametrize("cut_degrees", CUTS)
def test_a_rolling_cue_ball_throws_less_by_alciatores_tp_a14(
    speed: float, cut_degrees: float
) -> None:
    cut = math.radians(cut_degrees)
    velocities, _, _ = collide(speed, cut, rolling(speed))
    throw = throw_of(velocities, cut)
    assert throw == pytest.approx(alciatore_throw(speed, cut, speed / R, 0.0), abs=1e-13)
    if cut_degrees > 0:
        stun, _, _ = collide(speed, cut)
        assert 0 < throw < throw_of(stun, cut)


def test_cut_induced_throw_peaks_near_a_half_ball_hit_and_falls_with_speed() -> None:
    # TP A-14's curves: a slow stun shot throws most, over 5 degrees, near 30-45 degrees.
    slow = [
        math.degrees(throw_of(collide(SLOW, math.radians(c))[0], math.radians(c))) for c in CUTS
    ]
    fast = [
        math.degrees(throw_of(collide(FAST, math.radians(c))[0], math.radians(c))) for c in CUTS
    ]
    assert 5.0 < max(slow) < 6.0 and 25 <= CUTS[int(np.argmax(slow))] <= 45
    assert all(f <= s for f, s in zip(fast, slow, strict=True))
    assert slow[0] == 0 and fast[0] == 0


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
@pytest.mark.parametrize("english", [0.25, 0.5, 1.0])
def test_side_spin_throws_a_head_on_hit_the_other_way(speed: float, english: float) -> None:
    # Spin-induced throw: right english (the tip right of centre as the shooter sees it:
    # w_z > 0 for a ball going +x, spin.motion.tip_spin) throws the object ball left
    # (+y), by TP A-14's formula with phi = 0, and turns it the other way (gears).
    side = 2.5 * speed * (english * 0.5 * R) / R**2  # the tip english x R/2 off centre
    velocities, spins, _ = collide(speed, 0.0, (0.0, 0.0, side))
    throw = throw_of(velocities, 0.0)
    assert throw == pytest.approx(alciatore_throw(speed, 0.0, 0.0, side), abs=1e-13)
    assert throw < 0 and velocities[1, 1] > 0
    assert spins[1, 2] < 0


@pytest.mark.parametrize("cut_degrees", [10.0, 30.0, 60.0])
@pytest.mark.parametrize("speed", [SLOW, FAST])
def test_gearing_english_throws_nothing(cut_degrees: float, speed: float) -> None:
    cut = math.radians(cut_degrees)
    # Outside english that cancels the slip: R w_z = v sin(cut).
    gearing = speed * math.sin(cut) / R
    velocities, spins, _ = collide(speed, cut, (0.0, 0.0, gearing))
    assert abs(throw_of(velocities, cut)) <= 1e-15
    assert np.abs(spins[1]).max() <= 1e-12  # no spin passed on
    assert spins[0, 2] == pytest.approx(gearing, abs=1e-12)


def test_the_contact_passes_spin_to_the_object_ball_and_changes_the_cue_balls() -> None:
    cut = math.radians(30.0)
    _, spins, _ = collide(MEDIUM, cut, rolling(MEDIUM))
    # A cut turns the object ball about z the other way to the cue ball's deflection
    # (gears): the slip at its surface is +y-ish, so w_z < 0 ... and both balls take
    # the same turn (n x F), each by 5/(2 m R) of the impulse.
    assert spins[1, 2] != 0 and spins[0, 2] == pytest.approx(spins[1, 2], rel=1e-12)
    assert spins[0, 1] != pytest.approx(MEDIUM / R, rel=1e-6)
    # Frictionless: spins pass.
    _, unchanged, _ = collide(MEDIUM, cut, rolling(MEDIUM), law="frictionless")
    assert unchanged[1].tolist() == [0.0, 0.0, 0.0]


def test_a_sticking_contact_ends_with_no_horizontal_slip() -> None:
    # A slow thin cut sticks (mu J_n > |u_t| / k_t): the contact point's slip across the
    # line of centres is gone after it.
    cut = math.radians(10.0)
    velocities, spins, _ = collide(SLOW, cut)
    normal = -np.array([math.cos(cut), math.sin(cut)])
    assert abs(slip_across(normal, velocities, spins, R)) <= 1e-15


def test_without_friction_the_frictional_law_is_the_frictionless_one_bit_for_bit() -> None:
    rng = np.random.default_rng(20)
    zero = Setup.of([[0.0, 0.0], [1.0, 0.0]], ball_friction=(0.0, 0.0, 1.088))
    for _ in range(200):
        angle = rng.uniform(0, 2 * math.pi)
        normal = np.array([math.cos(angle), math.sin(angle)])
        velocities = rng.normal(0, 2, (2, 2))
        spins = rng.normal(0, 50, (2, 3))
        masses = rng.uniform(0.1, 0.2, 2)
        e = float(rng.uniform(0, 1))
        with_friction = frictional(PairContact(normal, velocities, spins, masses), e, zero)
        without = frictionless(PairContact(normal, velocities, spins, masses), e, zero)
        assert with_friction[0].tobytes() == without[0].tobytes()
        assert with_friction[1].tobytes() == without[1].tobytes()
        assert with_friction[2] == without[2]


def test_the_friction_fit_is_alciatores_and_the_exp_is_libms_to_an_ulp() -> None:
    for slip in np.linspace(0.0, 20.0, 401):
        ours = BALL_FRICTION_A + BALL_FRICTION_B * exp(-BALL_FRICTION_C * float(slip))
        assert ours == pytest.approx(alciatore_mu(float(slip)), rel=4e-16)
    # TP A-28's fit through Marlow's three points (0.11, 0.06, 0.01 at 0.1, 1, 10 mph x sin 45).
    assert alciatore_mu(0.1 * math.sin(math.pi / 4)) == pytest.approx(0.11, abs=2e-3)
    assert alciatore_mu(10 * math.sin(math.pi / 4)) == pytest.approx(0.01, abs=2e-3)


def random_contact(
    rng: np.random.Generator,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float, Setup]:
    angle = rng.uniform(0, 2 * math.pi)
    normal = np.array([math.cos(angle), math.sin(angle)])
    velocities = rng.normal(0, 3, (2, 2)) * rng.choice([1e-4, 1.0, 5.0])
    spins = rng.normal(0, 80, (2, 3)) * rng.choice([0.0, 0.1, 1.0])
    masses = rng.uniform(0.1, 0.25, 2)
    restitution = float(rng.choice([1.0, rng.uniform(0, 1)]))
    friction = (float(rng.uniform(0, 0.1)), float(rng.uniform(0, 0.5)), float(rng.uniform(0, 3)))
    setup = Setup.of(
        [[0.0, 0.0], [1.0, 0.0]], radius=float(rng.uniform(0.02, 0.04)), ball_friction=friction
    )
    return normal, velocities, spins, masses, restitution, setup


def test_every_frictional_contact_keeps_momentum_and_never_raises_the_energy() -> None:
    rng = np.random.default_rng(2026)
    contacts = 0
    for _ in range(5000):
        normal, velocities, spins, masses, e, setup = random_contact(rng)
        after, turned, approach = frictional(
            PairContact(normal, velocities, spins, masses), e, setup
        )
        if approach == 0:
            assert after is velocities and turned is spins
            continue
        contacts += 1
        scale = float(np.abs(masses[:, None] * velocities).max())
        momentum = masses[:, None] * velocities
        momentum_after = masses[:, None] * after
        assert np.abs(momentum_after.sum(axis=0) - momentum.sum(axis=0)).max() <= 1e-14 * scale
        before = kinetic_energy(masses, velocities, spins, setup.radius)
        energy = kinetic_energy(masses, after, turned, setup.radius)
        assert energy <= before * (1 + 1e-13)
        # The pair parts along the line of centres at least as the frictionless law does.
        assert float((after[0] - after[1]) @ normal) >= 0
    assert contacts > 2000


def slip_across(normal: np.ndarray, velocities: np.ndarray, spins: np.ndarray, r: float) -> float:
    """The horizontal slip of ball 1's contact point over ball 2's, across the normal."""
    tangent = np.array([-normal[1], normal[0]])
    return float((velocities[0] - velocities[1]) @ tangent - r * (spins[0, 2] + spins[1, 2]))


def test_friction_never_reverses_the_slip_across_the_line_of_centres() -> None:
    # Coulomb: the horizontal slip across the normal keeps its sign (it is the
    # 3-D slip's direction, kept through the impulse), or is stopped.
    rng = np.random.default_rng(7)
    for _ in range(3000):
        normal, velocities, spins, masses, e, setup = random_contact(rng)
        after, turned, _ = frictional(PairContact(normal, velocities, spins, masses), e, setup)
        r = setup.radius
        before = slip_across(normal, velocities, spins, r)
        later = slip_across(normal, after, turned, r)
        rounding = 1e-14 * float(np.abs(velocities).max() + r * np.abs(spins).max())
        assert later * before >= -rounding * abs(before)
        assert abs(later) <= abs(before) + rounding


def angle_between(a: np.ndarray, b: np.ndarray) -> float:
    return math.degrees(math.acos(float(a @ b) / (math.hypot(*a) * math.hypot(*b))))


def rolled_out(velocity: np.ndarray, spin: np.ndarray) -> np.ndarray:
    """A sliding ball's velocity once it rolls: v - (2/7) u0, u0 its slip on the cloth
    (docs/spin.md), i.e. 5/7 v + 2/7 R (w_y, -w_x)."""
    return 5 / 7 * velocity + 2 / 7 * R * np.array([spin[1], -spin[0]])


def half_ball_deflection(cut: float) -> float:
    """Alciatore's 30-degree rule (TP A-4): a rolling cue ball's final deflection."""
    return math.degrees(math.atan(math.sin(cut) * math.cos(cut) / (math.sin(cut) ** 2 + 2 / 5)))


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
@pytest.mark.parametrize("cut_degrees", [10.0, 30.0, 45.0, 60.0])
def test_without_friction_the_90_and_30_degree_rules_hold_exactly(
    speed: float, cut_degrees: float
) -> None:
    cut = math.radians(cut_degrees)
    stun, _, _ = collide(speed, cut, law="frictionless")
    assert angle_between(stun[0], stun[1]) == pytest.approx(90.0, abs=1e-12)
    rolled, spins, _ = collide(speed, cut, rolling(speed), law="frictionless")
    final = rolled_out(rolled[0], spins[0])
    deflection = -math.degrees(math.atan2(final[1], final[0]))
    assert deflection == pytest.approx(half_ball_deflection(cut), abs=1e-12)


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
@pytest.mark.parametrize("cut_degrees", [10.0, 30.0, 45.0, 60.0])
def test_with_friction_a_stun_shot_parts_at_90_degrees_less_the_throw(
    speed: float, cut_degrees: float
) -> None:
    # The cue ball still leaves along the tangent line (friction slows it along it and
    # gives it only side spin, which does not bend its path); the object ball is thrown
    # towards it, so the 90-degree rule loses exactly the throw: 1.4 to 4.9 degrees here.
    cut = math.radians(cut_degrees)
    velocities, spins, _ = collide(speed, cut)
    throw = math.degrees(throw_of(velocities, cut))
    assert angle_between(velocities[0], velocities[1]) == pytest.approx(90.0 - throw, abs=1e-9)
    final = rolled_out(velocities[0], spins[0])
    assert -math.degrees(math.atan2(final[1], final[0])) == pytest.approx(
        90.0 - cut_degrees, abs=1e-9
    )


# A half-ball hit (30 degrees) with a rolling cue ball: its final deflection, frictionless
# 33.67 degrees (the 30-degree rule), is bent further by the contact's friction, whose
# vertical part takes some of the cue ball's topspin: measured with this law.
HALF_BALL_WITH_FRICTION = {SLOW: 36.561, MEDIUM: 34.946, FAST: 34.153}


@pytest.mark.parametrize("speed", [SLOW, MEDIUM, FAST])
def test_with_friction_the_30_degree_rule_bends_by_half_a_degree_to_three(speed: float) -> None:
    from tests.physics.test_spin import at, spin_run

    cut = math.radians(30.0)
    start = [5.0, 10.0]
    result = spin_run(
        # 1 mm from the contact: it meets the object ball at (nearly) `speed`.
        [start, [start[0] + 2 * R * math.cos(cut) + 1e-3, start[1] + 2 * R * math.sin(cut)]],
        [[speed, 0.0], [0.0, 0.0]],
        [list(rolling(speed)), [0.0, 0.0, 0.0]],
        ball_law="frictional",
    )
    contact = result.events[0]
    assert contact.kind == "ball"
    rolls_again = next(t for t in result.transitions if t.ball == "0" and t.state == "rolling")
    _, velocity, _ = at(result, rolls_again.time)
    deflection = abs(math.degrees(math.atan2(velocity[0, 1], velocity[0, 0])))
    # The run's contact is the law's, applied to the state the run met.
    _, before, spins_before = at(result, np.nextafter(contact.time, -math.inf))
    positions = result.positions_at(np.array([contact.time]))[0]
    normal = (positions[0] - positions[1]) / math.dist(positions[0], positions[1])
    after, turned, _ = frictional(
        PairContact(normal, before, spins_before, np.array([MASS, MASS])), 1.0, SETUP
    )
    final = rolled_out(after[0], turned[0])
    assert deflection == pytest.approx(abs(math.degrees(math.atan2(final[1], final[0]))), abs=1e-9)
    assert deflection == pytest.approx(HALF_BALL_WITH_FRICTION[speed], abs=0.01)
    assert 0.4 < deflection - half_ball_deflection(cut) < 3.0


# Components as a contact meets them: either zero, rounding-level, ordinary or fast.
component = st.one_of(
    st.sampled_from([0.0, -0.0]),
    st.floats(-1e-12, 1e-12, allow_nan=False),
    st.floats(-30.0, 30.0, allow_nan=False),
    st.floats(-300.0, 300.0, allow_nan=False),
)


@pytest.mark.long
@settings(derandomize=True, database=None, deadline=None, max_examples=600)
@given(
    st.floats(0.0, 2 * math.pi),
    st.lists(component, min_size=4, max_size=4),
    st.lists(component, min_size=6, max_size=6),
    st.lists(st.floats(0.05, 0.5), min_size=2, max_size=2),
    st.sampled_from([0.0, 0.5, 0.95, 1.0]),
    st.floats(0.0, 1e6),
)
def test_zero_friction_is_the_frictionless_law_to_the_bit_signs_of_zero_included(
    angle: float,
    speeds: list[float],
    spin_parts: list[float],
    masses: list[float],
    restitution: float,
    c: float,
) -> None:
    """frictional with a = b = 0 (any c) gives the frictionless law's velocities and
    spins byte for byte, -0.0 against +0.0 included (issue 30), for any contact: a
    normal along an axis or not, velocities and spins with zeros of either sign."""
    normal = np.array([math.cos(angle), math.sin(angle)])
    velocities = np.array(speeds).reshape(2, 2)
    spins = np.array(spin_parts).reshape(2, 3)
    weights = np.array(masses)
    zero = Setup.of([[0.0, 0.0], [1.0, 0.0]], ball_friction=(0.0, 0.0, c))
    with_friction = frictional(PairContact(normal, velocities, spins, weights), restitution, zero)
    without = frictionless(PairContact(normal, velocities, spins, weights), restitution, zero)
    assert with_friction[0].tobytes() == without[0].tobytes()
    assert with_friction[1].tobytes() == without[1].tobytes()
    assert struct.pack("<d", with_friction[2]) == struct.pack("<d", without[2])
