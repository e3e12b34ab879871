"""A cue that strikes (`[[ball]] cue = {...}`): Alciatore's TP A-30 and A-31, massé,
the level stroke's agreement with `tip`, and one line for every bad stroke."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from billiards.physics.spin.motion import ROLLING, SLIDING, classify, tip_spin
from billiards.rules.seed import MASS, RADIUS, STICK_END_MASS, STICK_MASS, TABLE_RESTITUTION
from billiards.scene.reader import SceneError, parse_scene
from billiards.scene.stroke import Stroke, jump_height, sin_cos_degrees, strike
from billiards.simulation import setup_from_scene, simulate_scene
from tests.commands import run_module

SPIN = '[physics]\nmodel = "spin"\n'
BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\n'


def scene_text(stroke: str, physics: str = SPIN) -> str:
    return f"{physics}{BALL}cue = {{ {stroke} }}\n"


def test_sine_and_cosine_from_arithmetic_match_libm_to_1e_15() -> None:
    # Over a quarter turn (an elevation's range) against libm; over two turns each way
    # the reference's own conversion to radians rounds by up to 720 pi/180 ulp(1)/2
    # = 1.4e-15 (ours reduces exactly, in degrees), so there the bound is 2e-15.
    def worst(angles: list[float]) -> float:
        return max(
            max(abs(s - math.sin(math.radians(a))), abs(c - math.cos(math.radians(a))))
            for a in angles
            for s, c in [sin_cos_degrees(a)]
        )

    assert worst(np.linspace(0.0, 90.0, 9001).tolist()) < 1e-15
    assert worst((np.linspace(-720.0, 720.0, 14401) + 0.0123).tolist()) < 2e-15
    assert [sin_cos_degrees(a) for a in (0.0, 90.0, 180.0, 270.0, 360.0)] == [
        (0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0), (0.0, 1.0),
    ]  # fmt: skip
    assert sin_cos_degrees(-1e-20) == (0.0, 1.0)  # -1e-20 % 360 is 360.0: a full turn


@pytest.mark.parametrize("tip", [(0.0, 0.0), (0.0, 0.5), (0.0, -0.6), (0.3, 0.2), (-0.5, -0.1)])
@pytest.mark.parametrize("elevation", [0.0, 20.0, 55.0])
def test_ball_speed_and_spin_follow_tp_a30(tip: tuple[float, float], elevation: float) -> None:
    # v = 2 V / (1 + m/M + (5 / (2 R^2)) b^2), b^2 = R^2 (side^2 + height^2), along the
    # cue; w = (5 v / (2R)) (side (cos(el) z + sin(el) d) + height (z x d)); the cloth
    # keeps v cos(el). Checked in the ball's own frame (d: its direction after squirt).
    side, height = tip
    cue_speed, mass, stick = 2.5, 0.17, 0.567
    struck = strike(Stroke(cue_speed, 0.0, elevation, tip, stick), mass, RADIUS)
    v = 2 * cue_speed / (1 + mass / stick + 2.5 * (side**2 + height**2))
    el = math.radians(elevation)
    assert struck.ball_speed == pytest.approx(v, rel=1e-15)
    d = np.array(struck.velocity) / np.hypot(*struck.velocity)
    assert np.hypot(*struck.velocity) == pytest.approx(v * math.cos(el), rel=1e-15)
    k = 5 * v / (2 * RADIUS)
    w = np.array(struck.spin)
    assert w[0] * d[0] + w[1] * d[1] == pytest.approx(k * side * math.sin(el), abs=1e-12)
    assert -w[0] * d[1] + w[1] * d[0] == pytest.approx(k * height, abs=1e-12)
    assert w[2] == pytest.approx(k * side * math.cos(el), abs=1e-12)
    assert struck.drive_down == pytest.approx(v * math.sin(el), rel=1e-15, abs=1e-300)


def pooltool_cue_strike(
    m: float, cue_mass: float, R: float, V0: float, phi: float, theta: float, a: float, b: float
) -> tuple[np.ndarray, np.ndarray]:
    """pooltool 0.6's instantaneous_point (cue_strike and InstantaneousPoint3D.solve,
    squirt aside), written out with libm's trig: a = -side (its +1 is the ball's left)."""
    t, p = math.radians(theta), math.radians(phi) + math.pi / 2
    cc = math.sqrt(1 - a * a - b * b)
    qa, qc, qb = (
        R * a,
        R * (math.cos(t) * cc - math.sin(t) * b),
        R * (math.sin(t) * cc + math.cos(t) * b),
    )
    i_m = 2 / 5 * R * R
    temp = qa**2 + (qb * math.cos(t)) ** 2 + (qc * math.sin(t)) ** 2
    temp -= 2 * qb * qc * math.cos(t) * math.sin(t)
    v = 2 * V0 / (1 + m / cue_mass + temp / i_m)
    v_b = -v * np.array([0, math.cos(t), math.sin(t)])
    w_b = (
        v
        / i_m
        * np.array([-qc * math.sin(t) + qb * math.cos(t), qa * math.sin(t), -qa * math.cos(t)])
    )
    turn = np.array([[math.cos(p), -math.sin(p), 0], [math.sin(p), math.cos(p), 0], [0, 0, 1]])
    return turn @ v_b, turn @ w_b


def test_a_stroke_is_pooltools_instantaneous_point_strike() -> None:
    # The same law by another route (pooltool turns the tip point into the ball's
    # frame); squirt off (an end mass of 1e-100 kg). Velocity, spin and the speed into
    # the cloth agree to rounding over 500 random strokes.
    rng = np.random.default_rng(20)
    for _ in range(500):
        side, height = rng.uniform(-0.6, 0.6, 2)
        phi, theta, speed = rng.uniform(-180, 180), rng.uniform(0, 85), rng.uniform(0.5, 4)
        v, w = pooltool_cue_strike(0.17, 0.567, RADIUS, speed, phi, theta, -side, height)
        struck = strike(Stroke(speed, phi, theta, (side, height), 0.567, 1e-100), 0.17, RADIUS)
        assert struck.velocity == pytest.approx(v[:2], abs=1e-14)
        assert struck.spin == pytest.approx(w, abs=1e-12)
        assert struck.drive_down == pytest.approx(-v[2], abs=1e-14)


def test_a_centre_hit_by_a_cue_far_heavier_than_the_ball_sends_it_at_twice_the_cues_speed() -> None:
    struck = strike(Stroke(1.5, mass=1e12), 0.17, RADIUS)  # A-30 with m/M -> 0, b = 0
    assert struck.velocity == pytest.approx((3.0, 0.0), rel=1e-11) and struck.spin == (0, 0, 0)


def test_squirt_is_1_19936_degrees_at_end_mass_ratio_20_and_a_fifth_of_r_side() -> None:
    # TP A-31: tan a = (5/2) x sqrt(1 - x^2) / (1 + m_b/m_e + (5/2)(1 - x^2)).
    struck = strike(Stroke(2.0, tip=(0.2, 0.0), end_mass=0.17 / 20), 0.17, RADIUS)
    sin_a, cos_a = struck.squirt
    assert math.degrees(math.atan2(sin_a, cos_a)) == pytest.approx(1.19936, abs=5e-6)
    # Right of centre (side > 0) squirts the ball left of the cue's line, and back.
    assert math.degrees(math.atan2(*struck.velocity[::-1])) == pytest.approx(1.19936, abs=5e-6)
    left = strike(Stroke(2.0, tip=(-0.2, 0.0), end_mass=0.17 / 20), 0.17, RADIUS)
    assert left.squirt == (-sin_a, cos_a)


def test_a_tip_at_four_tenths_of_r_above_centre_rolls_from_the_start() -> None:
    for side in (0.0, 0.3, -0.5):  # with english too: the squirt turns the spin with the path
        struck = strike(Stroke(2.0, 40.0, tip=(side, 0.4)), MASS, RADIUS)
        states, _, _ = classify(np.array([struck.velocity]), np.array([struck.spin]), RADIUS)
        assert states[0] == ROLLING
    below = strike(Stroke(2.0, tip=(0.0, 0.3)), MASS, RADIUS)
    states, _, _ = classify(np.array([below.velocity]), np.array([below.spin]), RADIUS)
    assert states[0] == SLIDING


@pytest.mark.parametrize("tip", [(0.0, 0.0), (0.0, 0.4), (0.5, -0.3), (-0.2, 0.7)])
def test_a_level_stroke_gives_the_spin_tip_gives_its_velocity_to_the_bit(
    tip: tuple[float, float],
) -> None:
    # Elevation 0: the stroke's spin is `tip`'s for the velocity the stroke gives (TP A-30
    # and the tip law are the same impulse; the stroke adds the cue's and end masses).
    stroked = parse_scene(scene_text(f"speed = 2.0, direction = 25.0, tip = {list(tip)}"))
    ball = stroked.balls[0]
    by_tip = parse_scene(f"{SPIN}{BALL}velocity = {list(ball.velocity)}\ntip = {list(tip)}\n")
    a, b = setup_from_scene(stroked), setup_from_scene(by_tip)
    assert a.spins is not None and b.spins is not None
    assert np.array_equal(a.velocities, b.velocities) and np.array_equal(a.spins, b.spins)
    assert np.array_equal(a.spins, tip_spin(a.velocities, np.array([tip]), RADIUS))


@pytest.mark.parametrize("side", [0.5, -0.5])
def test_masse_curves_the_ball_towards_the_side_struck(side: float) -> None:
    # An elevated cue right of centre tilts the spin axis forward: the slip points left,
    # friction pushes right, and the path bends right (the shooter's right: -y for +x)
    # until the slip is gone and the ball rolls straight.
    scene = parse_scene(
        scene_text(f"speed = 2.0, direction = 0, elevation = 40, tip = [{side}, 0.0]")
    )
    result = simulate_scene(scene)
    rolls = result.transitions[0]
    assert rolls.state == "rolling"
    assert not result.events or result.events[0].time > rolls.time  # no cushion on the way
    heading = np.arctan2(*result.velocities_at(np.array([0.0, rolls.time]))[:, 0, ::-1].T)
    turn = math.degrees(heading[1] - heading[0])
    assert turn * side < 0 and 15 < abs(turn) < 45
    # Still a parabola while it slides, so exact == event to the bit.
    assert np.array_equal(simulate_scene(scene, "event").final_positions, result.final_positions)


def test_the_jump_limit_is_the_bed_rebound_lifting_the_ball_a_radius() -> None:
    # Hop h = (e_t v sin(el))^2 / (2 g), e_t = 0.5: a radius is reached at v sin(el) =
    # sqrt(2 g R) / e_t = 1.498 m/s.
    limit = math.sqrt(2 * 9.81 * RADIUS) / TABLE_RESTITUTION
    assert jump_height(limit, 9.81) == pytest.approx(RADIUS, rel=1e-14)
    below = "speed = 1.0, elevation = 60, tip = [0.5, 0.0]"
    assert jump_height(strike(Stroke(1.0, 0, 60, (0.5, 0.0)), MASS, RADIUS).drive_down, 9.81) < (
        RADIUS
    )
    parse_scene(scene_text(below))  # accepted


BAD = [
    (
        "speed = 2.0",
        "ball[0].cue = a table: expected physics.model = \"spin\" first",
        "",
    ),
    ("speed = 2.0, tip = [0.8, 0.7]", "ball[0].cue.tip = [0.8, 0.7]: expected a point on the ball", SPIN),
    ("speed = 2.0, elevation = 90", "ball[0].cue.elevation = 90: expected degrees in [0, 90)", SPIN),
    ("speed = 2.0, elevation = -5", "ball[0].cue.elevation = -5: expected degrees in [0, 90)", SPIN),
    ("speed = 2.0, elevation = 30", "physics.gravity = 0: expected > 0 m/s^2 for a stroke that lifts the ball (ball[0].cue.elevation = 30", SPIN + "gravity = 0\n"),
    ("speed = 2.0, elevation = 90", "ball[0].cue.elevation = 90: expected degrees in [0, 90) (0: a level cue; 90 and more drive the ball through the bed)", SPIN),
    ("direction = 10", "ball[0].cue.speed: missing; expected the cue's speed in m/s", SPIN),
    ("speed = 0", "ball[0].cue.speed = 0: expected a number in (0, 500] m/s", SPIN),
    ("speed = 2.0, mass = 0", "ball[0].cue.mass = 0: expected a number in [0.001, 1000] kg", SPIN),
    ("speed = 2.0, end_mass = -1", "ball[0].cue.end_mass = -1: expected a number in [0.001, 1000] kg", SPIN),
    ("speed = 2.0, direction = 'up'", "ball[0].cue.direction = 'up': expected degrees", SPIN),
    ("speed = 2.0, elevaton = 30", 'ball[0].cue.elevaton: unknown key (did you mean "elevation"?)', SPIN),
]  # fmt: skip


@pytest.mark.long
@pytest.mark.parametrize(("stroke", "message", "physics"), BAD, ids=[b[0] for b in BAD])
def test_a_bad_stroke_is_one_line_and_exit_2(
    stroke: str, message: str, physics: str, tmp_path: Path
) -> None:
    path = tmp_path / "s.toml"
    path.write_text(scene_text(stroke, physics))
    run = run_module("billiards.simulate", str(path))
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.count("\n") == 1 and message in run.stderr, run.stderr


@pytest.mark.parametrize("given", ["velocity = [1.0, 0.0]", "spin = [0.0, 0.0, 1.0]", "tip = [0.0, 0.4]"])  # fmt: skip
def test_a_stroke_with_a_velocity_spin_or_tip_is_one_line(given: str) -> None:
    with pytest.raises(SceneError) as caught:
        parse_scene(f"{SPIN}{BALL}{given}\ncue = {{ speed = 2.0 }}\n", "s.toml")
    name = given.split(" ")[0]
    assert f"expected a stroke or a {name}, not both" in str(caught.value)
    assert "\n" not in str(caught.value)


def test_simulate_json_reports_each_struck_balls_velocity_spin_and_squirt(tmp_path: Path) -> None:
    path = tmp_path / "s.toml"
    path.write_text(
        scene_text("speed = 1.0, direction = 90, elevation = 30, tip = [-0.3, 0.2]")
        + '[[ball]]\nid = "1"\nposition = [1.5, 0.5]\n'
    )
    run = run_module("billiards.simulate", str(path), "--json")
    assert run.returncode == 0, run.stderr
    strokes = json.loads(run.stdout)["strokes"]
    struck = strike(Stroke(1.0, 90.0, 30.0, (-0.3, 0.2)), 0.165, RADIUS)
    assert strokes == [
        {
            "ball": "cue",
            "velocity": list(struck.velocity),
            "spin": list(struck.spin),
            "squirt": pytest.approx(-math.degrees(math.atan(
                2.5 * 0.3 * math.sqrt(0.91) / (1 + 0.165 / STICK_END_MASS + 2.5 * 0.91)
            )), abs=1e-12),
        }
    ]  # fmt: skip
    assert Stroke(1.0).mass == STICK_MASS
