"""The spin model's scene keys and what `simulate --json` shows of it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from billiards.rules.seed import RADIUS
from billiards.scene.reader import SceneError, default_scene_path, parse_scene
from billiards.simulation import setup_from_scene, simulate_scene
from tests.commands import run_module

SPIN = '[physics]\nmodel = "spin"\n'
BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [2.0, 0.0]\n'


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            BALL + "spin = [0.0, 1.0, 0.0]\n",
            'ball[0].spin = [0.0, 1.0, 0.0]: expected physics.model = "spin" first',
        ),
        (
            BALL + "tip = [0.0, 0.4]\n",
            'ball[0].tip = [0.0, 0.4]: expected physics.model = "spin" first',
        ),
        (
            SPIN + BALL + "spin = [0.0, 1.0, 0.0]\ntip = [0.0, 0.4]\n",
            "expected spin or tip, not both",
        ),
        (
            SPIN + BALL + "tip = [0.9, 0.9]\n",
            "ball[0].tip = [0.9, 0.9]: expected a point on the ball",
        ),
        (SPIN + BALL + "spin = [0.0, 1.0]\n", "ball[0].spin = [0.0, 1.0]: expected an array of 3"),
        (
            '[physics]\nmodel = "skid"\n' + BALL,
            'physics.model = \'skid\': expected one of "rolling", "spin"',
        ),
        (SPIN + "sliding_friction = -1\n" + BALL, "physics.sliding_friction = -1"),
        (
            '[physics]\ncushion_model = "han2005"\n' + BALL,
            "physics.cushion_model = 'han2005': expected physics.model = \"spin\" first",
        ),
        (
            SPIN + 'cushion_model = "han2005"\ncushion_height = 0.06\n' + BALL,
            "physics.cushion_height = 0.06: expected a cushion nose above the ball's equator",
        ),
        (SPIN + "cushion_restitution = 1.5\n" + BALL, "physics.cushion_restitution = 1.5"),
        (
            '[physics]\ncushion_model = "mathavan2010"\n' + BALL,
            "physics.cushion_model = 'mathavan2010': expected physics.model = \"spin\" first",
        ),
        (
            SPIN + 'cushion_model = "mathavan2010"\ncushion_height = 0.02\n' + BALL,
            "physics.cushion_height = 0.02: expected a cushion nose above the ball's equator",
        ),
        (
            SPIN + 'cushion_model = "mathavan2010"\ncushion_friction = 3\n' + BALL,
            "physics.cushion_friction = 3: expected mathavan2010's cushion and cloth frictions",
        ),
    ],
)
def test_bad_spin_key_is_one_line_naming_it(text: str, message: str) -> None:
    with pytest.raises(SceneError) as caught:
        parse_scene(text, "s.toml")
    assert message in str(caught.value) and "\n" not in str(caught.value)


def test_tip_sets_the_spin_a_horizontal_cue_gives() -> None:
    scene = parse_scene(SPIN + BALL + "tip = [0.5, 0.4]\n")
    spins = setup_from_scene(scene).spins
    assert spins is not None
    # Height 0.4: w_y = v / r (natural roll); side 0.5: w_z = 5 v 0.5 / (2 r).
    assert spins[0] == pytest.approx([0.0, 2.0 / RADIUS, 5 * 2.0 * 0.5 / (2 * RADIUS)], abs=1e-9)
    no_key = setup_from_scene(parse_scene(SPIN + BALL)).spins
    assert no_key is not None and np.all(no_key == 0)


def test_draw_shot_json_lists_transitions_and_samples_carry_velocities_and_spins() -> None:
    scene = str(Path(default_scene_path()).parent / "draw_shot.toml")
    done = run_module("billiards.simulate", scene, "--json", "--times", "0,0.1")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    states = {change["state"] for change in data["transitions"]}
    assert states <= {"rolling", "spinning", "rest"} and "rest" in states
    assert [change["t"] for change in data["transitions"]] == sorted(
        change["t"] for change in data["transitions"]
    )
    first = data["samples"][0]
    assert first["velocities"][0] == [2.5, 0.0]
    # Drawn: spinning backwards (w_y < 0) while it slides forwards.
    assert first["spins"][0][1] < 0


@pytest.mark.parametrize("radius", [0.0286, 0.0143])
def test_a_ball_spinning_in_place_stops_at_its_spin_over_5_mu_sp_g_over_2r(radius: float) -> None:
    # spinning_friction is a plain number: with it fixed, halving r doubles the decay.
    text = (
        f"{SPIN}spinning_friction = 0.0127\n[balls]\nradius = {radius}\n"
        '[[ball]]\nid = "top"\nposition = [0.5, 0.5]\nspin = [0.0, 0.0, 20.0]\n'
    )
    result = simulate_scene(parse_scene(text))
    (rest,) = [change.time for change in result.transitions if change.state == "rest"]
    assert rest == pytest.approx(20.0 / (5 * 0.0127 * 9.81 / (2 * radius)), rel=1e-12)


@pytest.mark.parametrize("method", ["exact", "event", "naive"])
@pytest.mark.parametrize("physics", ["", SPIN])
def test_the_result_says_which_model_ran(physics: str, method: str) -> None:
    scene = parse_scene(physics + BALL)
    result = simulate_scene(scene, method=method)
    assert result.model == scene.physics.model
    # Curved between its breaks only where closed-form parabolas are evaluated.
    assert result.curved_paths == (result.model == "spin" and method != "naive")


def test_mathavan2010_takes_the_papers_fit_unless_told() -> None:
    text = SPIN + 'cushion_model = "mathavan2010"\n'
    physics = parse_scene(text + BALL).physics
    assert (physics.cushion_restitution, physics.cushion_friction) == (0.98, 0.14)
    told = parse_scene(text + "cushion_restitution = 0.9\ncushion_friction = 0.2\n" + BALL)
    assert (told.physics.cushion_restitution, told.physics.cushion_friction) == (0.9, 0.2)
    setup = setup_from_scene(parse_scene(text + "sliding_friction = 0.25\n" + BALL))
    assert setup.cushion_law == "mathavan2010" and setup.sliding_friction == 0.25


def test_mathavan2010_ev_takes_its_fit_and_its_speed() -> None:
    text = SPIN + 'cushion_model = "mathavan2010_ev"\n'
    physics = parse_scene(text + BALL).physics
    assert (physics.cushion_restitution, physics.cushion_friction) == (0.9975, 0.14)
    assert physics.cushion_restitution_speed == 4.15
    setup = setup_from_scene(parse_scene(text + "cushion_restitution_speed = 3.0\n" + BALL))
    assert setup.cushion_law == "mathavan2010_ev" and setup.cushion_restitution_speed == 3.0
    with pytest.raises(SceneError, match=r"physics\.cushion_restitution_speed = 0: expected"):
        parse_scene(text + "cushion_restitution_speed = 0\n" + BALL)
