"""Physical facts the simulator must reproduce (the README's model section), one test each."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from billiards.physics.laws.ball_ball import ELASTIC_BELOW, frictionless_impulse, line_of_centres
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene
from tests.scenes import (
    MU_G,
    R,
    assert_sound,
    break_scene,
    contact_velocities,
    min_gap,
    sample_times,
    scene_of,
)

EXACT_METHODS = ("event", "exact")


@pytest.mark.parametrize("method", EXACT_METHODS)
@pytest.mark.parametrize("angle", [0.0, 0.3, math.pi / 4])
def test_stop_distance_and_time_follow_v_squared_over_2_mu_g(method: str, angle: float) -> None:
    speed = 0.4  # stops after 0.82 m, short of every cushion
    velocity = (speed * math.cos(angle), speed * math.sin(angle))
    result = simulate_scene(scene_of([("cue", (0.3, 0.3), velocity)]), method=method)
    travelled = np.hypot(*(result.final_positions[0] - np.array([0.3, 0.3])))
    assert travelled == pytest.approx(speed**2 / (2 * MU_G), rel=1e-14)
    assert result.rest_time == pytest.approx(speed / MU_G, rel=1e-14)
    assert result.events == ()


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_head_on_contact_of_unequal_masses_matches_closed_form(method: str) -> None:
    m1, m2, v = 0.170, 0.165, 2.0
    x1, x2 = 0.4, 1.2
    scene = scene_of(
        [("cue", (x1, 0.5), (v, 0.0)), ("1", (x2, 0.5), (0.0, 0.0))], masses={"cue": m1, "1": m2}
    )
    result = simulate_scene(scene, method=method)
    contact = result.events[0]
    gap = x2 - x1 - 2 * R
    arrival = 2 * gap / (v + math.sqrt(v * v - 2 * MU_G * gap))
    assert contact.kind == "ball" and contact.time == pytest.approx(arrival, rel=1e-14)
    u = v - MU_G * arrival
    after = result.velocities_at(np.array([contact.time]))[0]
    assert after[0, 0] == pytest.approx((m1 - m2) / (m1 + m2) * u, rel=1e-12)
    assert after[1, 0] == pytest.approx(2 * m1 / (m1 + m2) * u, rel=1e-12)
    assert np.all(after[:, 1] == 0.0)


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_thirty_degree_cut_sends_the_object_ball_along_the_line_of_centres(method: str) -> None:
    # Aim so that at contact the line of centres makes 30 degrees with the cue's path.
    offset = 2 * R * math.sin(math.radians(30))
    scene = scene_of([("cue", (0.4, 0.5 + offset), (2.0, 0.0)), ("1", (1.0, 0.5), (0.0, 0.0))])
    result = simulate_scene(scene, method=method)
    contact = result.events[0]
    before = result.velocities_at(np.array([np.nextafter(contact.time, 0)]))[0]
    after = result.velocities_at(np.array([contact.time]))[0]
    speed = np.hypot(*before[0])
    object_velocity = after[1]
    assert np.hypot(*object_velocity) == pytest.approx(speed * math.cos(math.radians(30)), rel=1e-9)
    direction = math.degrees(math.atan2(object_velocity[1], object_velocity[0]))
    assert direction == pytest.approx(-30.0, abs=1e-7)
    # The cue ball leaves at right angles to the object ball (equal masses, elastic).
    assert float(after[0] @ after[1]) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("method", EXACT_METHODS)
@pytest.mark.parametrize("gap", [0.0001, 0.0])
def test_every_elastic_contact_conserves_momentum_and_energy(method: str, gap: float) -> None:
    result = simulate_scene(break_scene(gap=gap), method=method)
    checked = 0
    for event, (before, after) in zip(result.events, contact_velocities(result), strict=True):
        if event.kind != "ball":
            continue
        masses = result.masses[[result.ball_ids.index(b) for b in event.balls]]
        energy_before = 0.5 * masses @ np.sum(before**2, axis=1)
        energy_after = 0.5 * masses @ np.sum(after**2, axis=1)
        assert energy_after == pytest.approx(energy_before, rel=1e-12)
        momentum_before = masses @ before
        assert np.allclose(masses @ after, momentum_before, rtol=0, atol=1e-15)
        checked += 1
    assert checked >= 14


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_cushion_keeps_75_percent_of_energy_and_mirrors_the_angle(method: str) -> None:
    scene = scene_of([("cue", (1.0, 0.5), (1.5, 0.8))])
    result = simulate_scene(scene, method=method)
    first = result.events[0]
    assert first.kind == "cushion"
    before, after = (v[0] for v in contact_velocities(result)[0])
    assert np.sum(after**2) == pytest.approx(0.75 * np.sum(before**2), rel=1e-12)
    # Mirror: the component along the cushion's normal (y here) flips, the other keeps
    # its sign, and both shrink by sqrt(0.75): the angle out equals the angle in.
    assert after[0] == pytest.approx(before[0] * math.sqrt(0.75), rel=1e-14)
    assert after[1] == pytest.approx(-before[1] * math.sqrt(0.75), rel=1e-14)
    # Unclamped (positions_at clamps to the cushion lines): the physics itself.
    assert result.motion.positions_at(np.array([result.rest_time]))[0, 0, 0] <= 2.13 - R


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_balls_touch_at_exactly_two_radii_at_every_ball_contact(method: str) -> None:
    result = simulate_scene(break_scene(), method=method)
    for event in result.events:
        if event.kind != "ball":
            continue
        index = [result.ball_ids.index(b) for b in event.balls]
        positions = result.positions_at(np.array([event.time]))[0][index]
        distance = float(np.hypot(*(positions[0] - positions[1])))
        assert distance == pytest.approx(2 * R, abs=1e-12)


@pytest.mark.parametrize("dt", [1 / 30, 1 / 1000])
def test_exact_method_equals_event_method_at_any_step(dt: float) -> None:
    scene = load_scene()
    reference = simulate_scene(scene, method="event")
    stepped = simulate_scene(scene, method="exact", dt=dt)
    assert [(e.time, e.kind, e.balls) for e in stepped.events] == [
        (e.time, e.kind, e.balls) for e in reference.events
    ]
    assert np.array_equal(stepped.final_positions, reference.final_positions)
    assert stepped.rest_time == reference.rest_time
    assert stepped.steps == math.ceil(reference.rest_time / dt)


@pytest.mark.parametrize("method", ["exact", "event", "naive"])
def test_same_input_gives_bit_identical_output(method: str) -> None:
    first = simulate_scene(load_scene(), method=method)
    second = simulate_scene(load_scene(), method=method)
    assert first.events == second.events
    assert np.array_equal(first.final_positions, second.final_positions)
    times = np.linspace(0, first.rest_time, 97)
    assert np.array_equal(first.positions_at(times), second.positions_at(times))


def test_seed_break_hits_the_rack_and_every_ball_stays_sound() -> None:
    result = simulate_scene(load_scene())
    assert result.events[0].kind == "ball" and result.events[0].balls == ("cue", "1")
    assert sum(e.kind == "ball" for e in result.events) >= 15
    assert_sound(result)


# --- hard cases ----------------------------------------------------------------------


@pytest.mark.parametrize("method", ["exact", "event", "naive"])
@pytest.mark.parametrize("speed", [3.0, 12.0])
def test_frozen_rack_break_stays_sound(method: str, speed: float) -> None:
    result = simulate_scene(break_scene(speed=speed, gap=0.0), method=method)
    assert_sound(result)
    if method != "naive":
        assert sum(e.kind == "ball" for e in result.events) >= 14


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_five_touching_balls_pass_the_hit_down_the_line(method: str) -> None:
    balls = [("cue", (0.4, 0.5), (2.0, 0.0))]
    balls += [(str(k), (0.8 + (k - 1) * 2 * R, 0.5), (0.0, 0.0)) for k in range(1, 6)]
    result = simulate_scene(scene_of(balls), method=method)
    assert_sound(result)
    # Equal masses: the cue stops dead and only the last ball of the line runs on.
    hit_time = result.events[0].time
    after = result.velocities_at(np.array([hit_time]))[0]
    assert np.hypot(*after[0]) == 0.0
    assert np.count_nonzero(np.hypot(after[:, 0], after[:, 1])) == 1
    assert after[5, 0] > 0


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_shot_into_the_exact_corner_meets_both_cushions_at_once(method: str) -> None:
    start = np.array([1.0, 0.5])
    corner = np.array([2.13 - R, 1.065 - R])
    direction = (corner - start) / np.hypot(*(corner - start))
    scene = scene_of([("cue", tuple(start), tuple(2.5 * direction))])
    result = simulate_scene(scene, method=method)
    first, second = result.events[:2]
    assert first.kind == second.kind == "cushion"
    assert second.time - first.time <= 1e-12
    velocities = contact_velocities(result)
    before = velocities[0][0][0]
    after = velocities[1][1][0]
    assert np.allclose(after / np.hypot(*after), -before / np.hypot(*before), atol=1e-6)
    assert np.sum(after**2) == pytest.approx(0.75**2 * np.sum(before**2), rel=1e-9)
    assert_sound(result)


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_ball_resting_against_a_cushion_is_struck_without_crossing_it(method: str) -> None:
    scene = scene_of([("cue", (1.0, 0.5), (2.0, 0.0)), ("1", (2.13 - R, 0.5), (0.0, 0.0))])
    result = simulate_scene(scene, method=method)
    kinds = [e.kind for e in result.events[:2]]
    assert kinds == ["ball", "cushion"]
    assert result.events[1].time == result.events[0].time
    assert_sound(result)


@pytest.mark.parametrize("method", EXACT_METHODS)
@pytest.mark.parametrize(("miss", "contacts"), [(1e-9, 0), (-1e-9, 1)])
def test_contact_missed_or_made_by_a_nanometre(method: str, miss: float, contacts: int) -> None:
    scene = scene_of(
        [("cue", (0.4, 0.5 + 2 * R + miss), (2.0, 0.0)), ("1", (1.0, 0.5), (0.0, 0.0))]
    )
    result = simulate_scene(scene, method=method)
    assert sum(e.kind == "ball" for e in result.events) == contacts
    # Also at the closest approach: when the cue's centre passes x = 1.0.
    distance = 0.6
    closest = 2 * distance / (2.0 + math.sqrt(2.0**2 - 2 * MU_G * distance))
    times = np.append(sample_times(result, 20000), closest)
    assert min_gap(result, times) >= -1e-12
    if contacts == 0:
        assert min_gap(result, np.array([closest])) == pytest.approx(1e-9, abs=1e-12)


@pytest.mark.parametrize("method", ["exact", "naive"])
def test_thirty_metres_per_second_at_a_thirtieth_of_a_second_stays_sound(method: str) -> None:
    result = simulate_scene(break_scene(speed=30.0), method=method, dt=1 / 30)
    assert_sound(result)


@pytest.mark.long
@pytest.mark.parametrize("method", ["exact", "event", "naive"])
def test_hundred_random_balls_stay_sound(method: str) -> None:
    rng = np.random.default_rng(7)
    positions: list[np.ndarray] = []
    while len(positions) < 100:
        candidate = rng.uniform([R, R], [2.13 - R, 1.065 - R])
        if all(np.hypot(*(candidate - p)) >= 2 * R for p in positions):
            positions.append(candidate)
    velocities = rng.normal(size=(100, 2)) * 1.5
    balls = [
        (str(k), tuple(p), tuple(v))
        for k, (p, v) in enumerate(zip(positions, velocities, strict=True))
    ]
    result = simulate_scene(scene_of(balls), method=method)
    assert_sound(result)


def test_physics_imports_numpy_and_the_standard_library_only() -> None:
    code = "import sys, billiards.physics; print(' '.join(sorted(sys.modules)))"
    loaded = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    # An allowlist: anything outside the standard library but numpy is a failure.
    # (Leaving out what Python itself and pip's editable install load at start.)
    startup = {"__main__", "_distutils_hack"}
    outside = {name.split(".")[0] for name in loaded} - set(sys.stdlib_module_names) - startup
    outside = {name for name in outside if not name.startswith("__editable__")}
    assert outside <= {"numpy", "billiards"}
    ours = {name for name in loaded if name.startswith("billiards.")}
    # billiards.version: the package's __init__ says its version (a constant, no imports).
    assert ours <= {
        "billiards.record.trajectory",
        "billiards.record.quaternions",
        "billiards.version",
    } | {n for n in ours if n.startswith("billiards.physics")}


@pytest.mark.parametrize("method", EXACT_METHODS)
def test_without_friction_a_ball_keeps_its_speed_between_cushions_until_max_time(
    method: str,
) -> None:
    scene = scene_of(
        [("cue", (0.5, 0.5), (0.5, 0.2))],
        extra="[physics]\nrolling_friction = 0.0\n[table]\ncushion_retention = 1.0\n"
        "[simulation]\nmax_time = 20.0",
    )
    result = simulate_scene(scene, method=method)
    assert not result.complete and result.rest_time == 20.0
    assert len(result.events) >= 4 and all(e.kind == "cushion" for e in result.events)
    speeds = np.hypot(*result.velocities_at(sample_times(result))[:, 0].T)
    assert np.allclose(speeds, np.hypot(0.5, 0.2), rtol=1e-14, atol=0)
    positions = result.motion.positions_at(sample_times(result))
    assert positions.min() >= R - 1e-12
    assert positions[..., 0].max() <= 2.13 - R + 1e-12
    assert positions[..., 1].max() <= 1.065 - R + 1e-12


@pytest.mark.parametrize(
    ("restitution", "approach", "separation"),
    [
        (0.5, 1.0, 0.5),  # the scene's restitution where it leaves them apart fast enough
        (0.0, 0.01, ELASTIC_BELOW),  # plastic contacts still leave at ELASTIC_BELOW
        (0.0, 0.5 * ELASTIC_BELOW, 0.5 * ELASTIC_BELOW),  # the softest ones are elastic
        (0.9, 0.5 * ELASTIC_BELOW, 0.5 * ELASTIC_BELOW),
    ],
)
def test_restitution_rises_to_one_for_the_softest_contacts(
    restitution: float, approach: float, separation: float
) -> None:
    p1, p2 = np.array([0.0, 0.0]), np.array([2 * R, 0.0])
    v1, v2 = np.array([approach, 0.3]), np.array([0.0, -0.1])
    after1, after2, speed = frictionless_impulse(
        line_of_centres(p1, p2), v1, 0.17, v2, 0.165, restitution
    )
    assert speed == approach
    assert after2[0] - after1[0] == pytest.approx(separation, rel=1e-12)
    assert (after1[1], after2[1]) == (0.3, -0.1)  # tangential parts untouched
    assert 0.17 * after1 + 0.165 * after2 == pytest.approx(0.17 * v1 + 0.165 * v2, abs=1e-15)


@pytest.mark.parametrize("method", ["exact", "naive"])
def test_a_thousand_metres_per_second_never_leaves_the_table(method: str) -> None:
    # The naive step then crosses the whole table and more: it used to mirror a ball
    # back in by too little and leave it outside the cushions.
    result = simulate_scene(break_scene(speed=1000.0), method=method, dt=1 / 30)
    assert_sound(result)
