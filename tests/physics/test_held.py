"""The held contacts (billiards/physics/laws/held.py, docs/touching.md section 6): a ball
that its own slip drives into what it touches turns in place against it, or pushes it,
and never passes through it; the slip's normal part is gone after, and energy falls."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.laws.held import hold, part, push
from billiards.physics.methods.entry import run
from billiards.physics.spin.motion import slip_velocity
from billiards.rules.seed import MASS, RADIUS
from tests.hard_checks import check_no_overlap, kinetic_energy, sample_times


def normal_slip(velocity: np.ndarray, spin: np.ndarray, into: np.ndarray) -> float:
    return float(slip_velocity(velocity[None], spin[None], RADIUS)[0] @ into)


def energy(velocities: np.ndarray, spins: np.ndarray, masses: np.ndarray) -> float:
    return kinetic_energy(masses, velocities, spins, RADIUS)


def test_hold_leaves_no_normal_slip_and_never_raises_the_energy_over_random_balls() -> None:
    rng = np.random.default_rng(22)
    for _ in range(2000):
        angle = rng.uniform(0, 2 * np.pi)
        into = np.array([np.cos(angle), np.sin(angle)])
        velocity = rng.uniform(-2, 2, 2)
        spin = rng.uniform(-200, 200, 3)
        holder = float(velocity @ into)  # touching, not closing: moving with the holder
        along = np.array([-into[1], into[0]])
        if abs(holder) > RADIUS * abs(float(spin[:2] @ along)):
            continue  # the push's case
        held_v, held_w = hold(velocity, spin, into, holder, RADIUS)
        assert normal_slip(held_v, held_w, into) == pytest.approx(0.0, abs=1e-12)
        assert held_v @ into == pytest.approx(holder, abs=1e-15)
        assert held_w[2] == spin[2]
        before = energy(velocity[None], spin[None], np.array([MASS]))
        assert energy(held_v[None], held_w[None], np.array([MASS])) <= before * (1 + 1e-12)


def test_push_leaves_no_normal_slip_one_normal_speed_and_less_energy() -> None:
    rng = np.random.default_rng(2022)
    pushes = 0
    for _ in range(2000):
        angle = rng.uniform(0, 2 * np.pi)
        into = np.array([np.cos(angle), np.sin(angle)])
        velocity = rng.uniform(-2, 2, 2)
        # Moving together, to rounding, each with a spin of its own.
        velocities = np.array([velocity, velocity + rng.uniform(-1, 1, 2) * 1e-17])
        spins = rng.uniform(-50, 50, (2, 3))
        if normal_slip(velocities[0], spins[0], into) >= 0:
            continue  # the first ball's slip does not drive it into the second
        masses = rng.uniform(0.15, 0.3, 2)
        both = push(velocities, spins, masses, into, RADIUS)
        if both is None:
            continue  # the contact would pull: no push
        pushes += 1
        after, turned = both
        for ball in range(2):
            assert normal_slip(after[ball], turned[ball], into) == pytest.approx(0.0, abs=1e-12)
        assert after[0] @ into == pytest.approx(after[1] @ into, abs=1e-12)  # one speed
        # Along the pair's tangent nothing changes; the cloth takes only the normal part.
        along = np.array([-into[1], into[0]])
        assert after @ along == pytest.approx(velocities @ along, abs=1e-12)
        assert np.all(turned[:, 2] == spins[:, 2])
        assert energy(after, turned, masses) <= energy(velocities, spins, masses) * (1 + 1e-12)
    assert pushes > 200


def test_a_stun_ball_ahead_of_a_rolling_follower_takes_it_along_at_six_sevenths() -> None:
    # Touching along x, both at 1 m/s along -x: the front ball (0) slides without spin
    # and so slows at mu_s g, the follower (1) rolls and slows at mu_r g: pressed. The
    # pushed phase ends with both rolling at sum m (v - 2/5 s) / (7/5 sum m) = 6/7 m/s
    # (integrating it with the contact force gives (1 - (5 mu_s + 7 mu_r) / (35 mu_s +
    # 7 mu_r)) V = 0.849 V at mu_s = 0.2, mu_r = 0.01; 6/7 as mu_r -> 0).
    speed = 1.0
    roll = [0.0, -speed / RADIUS, 0.0]  # w = z x v / R for v = (-1, 0)
    setup = Setup.of(
        [(1.0, 0.5), (1.0 + 2 * RADIUS, 0.5)],
        [(-speed, 0.0), (-speed, 0.0)],
        model="spin",
        spins=[[0.0, 0.0, 0.0], roll],
    )
    result = run(setup, ("front", "follower"), "event", 1 / 30)
    first = result.events[0]
    assert (first.time, first.kind, first.balls) == (0.0, "ball", ("front", "follower"))
    after = result.velocities_at(np.array([0.0]))[0]
    assert after[:, 0] == pytest.approx([-6 / 7 * speed] * 2, rel=1e-12)
    assert any(change.time == 0.0 and change.ball == "front" for change in result.transitions)
    check_no_overlap(result, sample_times(result))


@pytest.mark.parametrize("method", ["event", "exact"])
def test_a_spinning_ball_at_rest_against_its_neighbour_turns_in_place(method: str) -> None:
    # Ball 1 at rest with backspin-like w_y < 0: its slip (-R w_y, 0) points +x, so the
    # cloth drives it along -x, into ball 0, which it touches. It is held: no speed
    # given to either, and it no longer slides into ball 0.
    setup = Setup.of(
        [(1.0, 0.5), (1.0 + 2 * RADIUS, 0.5)],
        model="spin",
        spins=[[0.0, 0.0, 0.0], [0.0, -60.0, 0.0]],
    )
    result = run(setup, ("0", "1"), method, 1 / 240)
    assert [(event.time, event.kind) for event in result.events] == [(0.0, "ball")]
    assert np.all(result.final_positions == setup.positions)
    assert result.spins_at(np.array([0.0]))[0, 1, 1] == 0.0
    check_no_overlap(result, sample_times(result))


def test_part_leaves_the_pair_parting_at_its_speed_paid_by_the_slip_and_never_raises_the_energy() -> (
    None
):
    rng = np.random.default_rng(20261202)
    for case in range(2000):
        angle = rng.uniform(0, 2 * np.pi)
        normal = np.array([np.cos(angle), np.sin(angle)])  # from ball 1 to ball 0
        velocity = rng.uniform(-2, 2, 2)
        velocities = np.array([velocity, velocity + rng.uniform(-1, 1, 2) * 1e-17])
        # Every third payer has a slip too small to pay for 1 mm/s apart.
        scale = 1e-5 if case % 3 == 0 else 50.0
        spins = rng.uniform(-scale, scale, (2, 3))
        masses = rng.uniform(0.15, 0.3, 2)
        payer = int(rng.integers(2))
        slip = slip_velocity(velocities[payer][None], spins[payer][None], RADIUS)[0]
        after, turned = part(velocities, spins, masses, normal, payer, RADIUS, 1e-3)
        parting = float((after[0] - after[1]) @ normal)
        if case % 3:
            assert parting == pytest.approx(1e-3, rel=1e-9)
        else:
            assert 0 < parting <= 1e-3 * (1 + 1e-9)
        assert energy(after, turned, masses) <= energy(velocities, spins, masses) * (1 + 1e-13)
        # Momentum changes only by the cloth's impulse on the payer, against its slip.
        cloth = masses @ after - masses @ velocities
        assert float(cloth @ slip) <= 0
        # (the difference of momenta carries their rounding: a few ulps of m |v|)
        rounding = 1e-15 * float(masses @ np.abs(velocities).sum(axis=1)) + 1e-300
        cross = float(cloth[0] * slip[1] - cloth[1] * slip[0])
        assert abs(cross) <= rounding * float(np.abs(slip).sum())
        after_slip = slip_velocity(after[payer][None], turned[payer][None], RADIUS)[0]
        assert float(after_slip @ slip) >= 0  # the slip shrinks along itself, never turns
        assert np.all(turned[:, 2] == spins[:, 2])
        other = 1 - payer
        assert np.all(turned[other] == spins[other])


@pytest.mark.parametrize("method", ["event", "exact"])
def test_a_rolling_ball_slowing_into_a_neighbour_sliding_along_their_tangent_never_overlaps(
    method: str,
) -> None:
    # Both at 0.05 m/s along +x, touching along x: ball 0 in front rolls and slows at
    # mu_r g; ball 1 behind slides with a slip along y (the pair's tangent), so its
    # friction has no part along the line of centres: ball 0 slows into it, with no
    # relative motion to turn and no slip driving either into the other (issue 22's
    # tiny[43], 1.1 mm deep before). The pair is parted at 1 mm/s, paid by ball 1's slip.
    speed = 0.05
    behind_spin = [-3.0 / RADIUS, speed / RADIUS, 0.0]  # slip u = v + R (-w_y, w_x) = (0, -3)
    setup = Setup.of(
        [(1.0 + 2 * RADIUS, 0.5), (1.0, 0.5)],
        [(speed, 0.0), (speed, 0.0)],
        model="spin",
        spins=[[0.0, speed / RADIUS, 0.0], behind_spin],
    )
    result = run(setup, ("front", "behind"), method, 1 / 240)
    assert result.complete
    assert result.events[0].balls == ("front", "behind") and result.events[0].time == 0.0
    check_no_overlap(result, sample_times(result))
