"""The spin model against textbook closed forms (Alciatore's technical proofs), and its
invariants: energy, no overlap or cushion crossing, exact == event, bit-identical reruns."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods.entry import run
from billiards.physics.spin.motion import tip_spin
from billiards.rules.seed import RADIUS
from tests.hard_checks import (
    check_inside_cushions,
    check_no_overlap,
    fingerprint,
    kinetic_energy,
    sample_times,
)

R = RADIUS
G = 9.81
MU_S = 0.2
MU_R = 0.01
# A table long enough that nothing meets a cushion unless a test wants it to.
LONG = (40.0, 20.0)


def spin_run(
    positions: list[list[float]],
    velocities: list[list[float]],
    spins: list[list[float]] | None = None,
    method: str = "event",
    dt: float = 1 / 240,
    **options: object,
) -> SimulationResult:
    setup = Setup.of(
        positions,
        velocities,
        model="spin",
        spins=spins,
        table_size=options.pop("table_size", LONG),
        slide_decel=MU_S * G,
        decel=MU_R * G,
        **options,  # type: ignore[arg-type]
    )
    return run(setup, tuple(str(i) for i in range(len(positions))), method, dt)


def at(result: SimulationResult, time: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    times = np.array([time])
    return result.positions_at(times)[0], result.velocities_at(times)[0], result.spins_at(times)[0]


@pytest.mark.parametrize("speed", [0.7, 2.0, 5.5])
def test_centre_ball_hit_slides_12_v0_squared_over_49_mu_g_and_leaves_at_five_sevenths(
    speed: float,
) -> None:
    result = spin_run([[1.0, 10.0]], [[speed * 0.6, speed * 0.8]])
    slide_end = 2 * speed / (7 * MU_S * G)
    assert result.transitions[0].state == "rolling"
    assert result.transitions[0].time == pytest.approx(slide_end, abs=1e-12)
    position, velocity, spin = at(result, slide_end)
    assert math.dist(position[0], (1.0, 10.0)) == pytest.approx(
        12 * speed**2 / (49 * MU_S * G), abs=1e-9
    )
    assert math.hypot(*velocity[0]) == pytest.approx(5 / 7 * speed, abs=1e-12)
    # Rolling: the contact point is at rest.
    assert velocity[0, 0] - R * spin[0, 1] == pytest.approx(0, abs=1e-12)
    assert velocity[0, 1] + R * spin[0, 0] == pytest.approx(0, abs=1e-12)


def test_natural_roll_tip_rolls_from_the_start_and_stops_where_the_rolling_model_does() -> None:
    velocity = np.array([[1.3, -0.4]])
    spins = tip_spin(velocity, np.array([[0.0, 0.4]]), R)
    spin = spin_run([[5.0, 10.0]], velocity.tolist(), spins.tolist())
    rolling = run(
        Setup.of([[5.0, 10.0]], velocity, table_size=LONG, decel=MU_R * G), ("0",), "event", 1
    )
    assert [t.state for t in spin.transitions] == ["rest"]
    assert spin.final_positions == pytest.approx(rolling.final_positions, abs=1e-9)
    assert spin.rest_time == pytest.approx(rolling.rest_time, abs=1e-12)


def stun_into(cut_offset: float, speed: float = 2.0, impact_time: float = 0.1) -> SimulationResult:
    """A cue ball that reaches the object ball at `impact_time` with no spin at all (a
    stun shot): it starts with the backspin its slide will have taken off by then. The
    object ball sits 2r sin(cut) off the cue ball's line, along +x."""
    decel = MU_S * G
    travel = speed * impact_time - 0.5 * decel * impact_time**2
    backspin = -2.5 * decel * impact_time / R  # w_y grows at 5 mu_s g / (2r) while it slides
    start = np.array([5.0, 10.0])
    object_x = start[0] + travel + math.sqrt((2 * R) ** 2 - cut_offset**2)
    return spin_run(
        [start.tolist(), [object_x, start[1] + cut_offset]],
        [[speed, 0.0], [0.0, 0.0]],
        [[0.0, backspin, 0.0], [0.0, 0.0, 0.0]],
    )


def test_stun_shot_head_on_stops_the_cue_ball_dead() -> None:
    result = stun_into(0.0)
    contact = result.events[0]
    assert contact.kind == "ball" and contact.time == pytest.approx(0.1, abs=1e-12)
    position, velocity, spin = at(result, contact.time)
    assert np.abs(velocity[0]).max() <= 1e-12 and np.abs(spin[0]).max() <= 1e-9
    assert result.final_positions[0] == pytest.approx(position[0], abs=1e-9)


@pytest.mark.parametrize("cut_degrees", [10.0, 30.0, 45.0, 70.0])
def test_stun_shot_at_any_cut_leaves_the_balls_at_90_degrees(cut_degrees: float) -> None:
    result = stun_into(2 * R * math.sin(math.radians(cut_degrees)))
    contact = result.events[0]
    start = result.positions_at(np.array([contact.time]))[0]
    moved = result.final_positions - start
    cosine = moved[0] @ moved[1] / (np.linalg.norm(moved[0]) * np.linalg.norm(moved[1]))
    assert abs(math.acos(cosine) - math.pi / 2) <= 1e-9


def test_half_ball_hit_with_natural_roll_deflects_by_the_30_degree_rule() -> None:
    speed = 1.5
    cut = math.radians(30.0)  # a half-ball hit: the object ball r off the line
    start = [5.0, 10.0]
    velocity = np.array([[speed, 0.0]])
    spins = tip_spin(velocity, np.array([[0.0, 0.4]]), R)
    result = spin_run(
        [start, [start[0] + 0.5, start[1] + 2 * R * math.sin(cut)]],
        [[speed, 0.0], [0.0, 0.0]],
        [spins[0].tolist(), [0.0, 0.0, 0.0]],
    )
    assert result.events[0].kind == "ball"
    rolls_again = next(t for t in result.transitions if t.ball == "0" and t.state == "rolling")
    _, velocity_after, _ = at(result, rolls_again.time)
    deflection = abs(math.atan2(velocity_after[0, 1], velocity_after[0, 0]))
    expected = math.atan(
        math.sin(cut) * math.cos(cut) / (math.sin(cut) ** 2 + 2 / 5)
    )  # Alciatore's 30-degree rule
    assert deflection == pytest.approx(expected, abs=1e-9)


def test_draw_shot_reverses_and_returns_in_closed_form() -> None:
    speed, backspin = 1.0, -150.0  # R |w| > 5/2 v0: the ball reverses while it slides
    start = 20.0
    result = spin_run([[start, 10.0]], [[speed, 0.0]], [[0.0, backspin, 0.0]])
    decel = MU_S * G
    reverse_time = speed / decel
    slide_end = 2 * (speed - R * backspin) / (7 * decel)
    assert reverse_time < slide_end
    position, velocity, _ = at(result, reverse_time)
    assert position[0, 0] - start == pytest.approx(speed**2 / (2 * decel), abs=1e-9)
    assert abs(velocity[0, 0]) <= 1e-12
    back = speed - decel * slide_end  # negative: rolling back from here
    slid = speed * slide_end - 0.5 * decel * slide_end**2
    rolled = back * abs(back) / (2 * MU_R * G)
    assert result.final_positions[0, 0] - start == pytest.approx(slid + rolled, abs=1e-9)
    assert [t.state for t in result.transitions] == ["rolling", "rest"]


def test_side_spin_alone_spins_in_place_then_rests() -> None:
    result = spin_run([[5.0, 10.0]], [[0.0, 0.0]], [[0.0, 0.0, 30.0]], spin_decel=10.0)
    assert [(t.time, t.state) for t in result.transitions] == [(3.0, "rest")]
    assert result.spins_at(np.array([1.0]))[0, 0, 2] == pytest.approx(20.0, abs=1e-12)


def spin_break(speed: float = 8.0, backspin: float = -200.0) -> Setup:
    from billiards.scene.reader import rack_positions

    positions = [[0.5325, 0.5325], *[list(p) for p in rack_positions((1.5975, 0.5325), R, 1e-4)]]
    velocities = np.zeros((16, 2))
    velocities[0] = (speed, 0.01)
    spins = np.zeros((16, 3))
    spins[0] = (0.0, backspin, 5.0)
    return Setup.of(
        positions, velocities, model="spin", spins=spins, restitution=0.95, slide_decel=MU_S * G
    )


@pytest.fixture(scope="module")
def break_result() -> SimulationResult:
    return run(spin_break(), tuple(str(i) for i in range(16)), "event", 1 / 240)


def energy_at(result: SimulationResult, times: np.ndarray) -> np.ndarray:
    velocities = result.velocities_at(times)
    spins = result.spins_at(times)
    return np.array(
        [kinetic_energy(result.masses, v, w, R) for v, w in zip(velocities, spins, strict=True)]
    )


def test_spin_break_energy_never_rises_and_balls_stay_apart_and_on_the_table(
    break_result: SimulationResult,
) -> None:
    times = sample_times(break_result)
    check_no_overlap(break_result, times)
    check_inside_cushions(break_result, times)
    # Just before and just after every anchor, and on the grid between.
    before = np.nextafter(times, -np.inf)
    energy = energy_at(break_result, np.sort(np.concatenate([times, before])))
    assert np.all(np.diff(energy) <= 1e-12 * energy[0])
    assert break_result.complete and len(break_result.events) > 20


@pytest.mark.parametrize("dt", [1 / 30, 1 / 240, 1 / 1000])
def test_spin_exact_equals_event_at_any_step(break_result: SimulationResult, dt: float) -> None:
    stepped = run(spin_break(), tuple(str(i) for i in range(16)), "exact", dt)
    assert fingerprint(stepped) == fingerprint(break_result)
    assert stepped.transitions == break_result.transitions


def test_spin_reruns_are_bit_identical(break_result: SimulationResult) -> None:
    again = run(spin_break(), tuple(str(i) for i in range(16)), "event", 1 / 240)
    assert fingerprint(again) == fingerprint(break_result)
    assert again.transitions == break_result.transitions


def test_naive_spin_is_near_the_exact_draw_shot_and_not_exact() -> None:
    exact = spin_run([[20.0, 10.0]], [[1.0, 0.0]], [[0.0, -150.0, 0.0]])
    errors = [
        abs(
            spin_run(
                [[20.0, 10.0]], [[1.0, 0.0]], [[0.0, -150.0, 0.0]], "naive", dt
            ).final_positions[0, 0]
            - exact.final_positions[0, 0]
        )
        for dt in (1 / 30, 1 / 1000)
    ]
    # First order in dt: 1.6 mm at 1/30 s, 0.17 mm at 1/1000 s (measured).
    assert errors[0] > 1e-6 and errors[1] < 1e-3


@pytest.mark.parametrize("law", ["mirror", "han2005"])
def test_a_ball_its_slip_presses_into_a_cushion_slides_along_it_without_crossing(
    law: str,
) -> None:
    width = 1.065
    setup = Setup.of(
        [[0.5, width - R]], [[1.0, 0.0]], model="spin", spins=[[-20.0, 0.0, 0.0]], cushion_law=law
    )
    result = run(setup, ("0",), "event", 1 / 240)
    times = sample_times(result)
    assert result.motion.positions_at(times)[..., 1].max() <= width - R
    assert result.complete and result.final_positions[0, 1] == width - R


# --- the rolling model loads none of the spin model -------------------------------------

LOADED_SPIN_MODULES = """
import json, sys
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import simulate_scene

def spin_modules():
    return sorted(name for name in sys.modules if name.startswith("billiards.physics.spin"))

for method in ("event", "exact", "naive"):
    simulate_scene(load_scene(), method=method)
rolling = spin_modules()
for name in ("spin_break", "english_bank"):  # the compiled loop's, the numpy engine's
    simulate_scene(load_scene(default_scene_path().parent / f"{name}.toml"), method="event")
print(json.dumps({"rolling": rolling, "spin": spin_modules()}))
"""


@pytest.mark.long
def test_a_rolling_run_imports_no_spin_module() -> None:
    """The seed break by every method, in a fresh interpreter, leaves no
    billiards.physics.spin module in sys.modules but spin.motion, whose state numbers
    the one compiled loop of both models reads (billiards.physics.compiled); a spin scene
    run afterwards in the same process loads its result (so the probe sees a spin
    module when there is one)."""
    done = subprocess.run(
        [sys.executable, "-c", LOADED_SPIN_MODULES],
        capture_output=True,
        text=True,
        check=False,
        cwd=Path(__file__).resolve().parents[2],
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    loaded = json.loads(done.stdout)
    assert loaded["rolling"] == ["billiards.physics.spin", "billiards.physics.spin.motion"]
    # A spin run goes through the compiled loop too: only the spin model's result is new.
    assert "billiards.physics.spin.result" in loaded["spin"]
