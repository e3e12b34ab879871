"""The frictional ball-ball law's scene keys ([physics] ball_model, ball_friction_a/b/c),
their one-line errors, and the shipped throw_shot: a cut that drops only by its throw."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.spin.result import SpinMotion
from billiards.rules import seed
from billiards.scene.reader import SceneError, default_scene_path, load_scene, parse_scene
from billiards.simulation import setup_from_scene, simulate_scene
from tests.commands import run_module
from tests.test_fingerprints import fingerprint

SPIN = '[physics]\nmodel = "spin"\n'
BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [2.0, 0.0]\n'


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            '[physics]\nball_model = "frictional"\n' + BALL,
            "physics.ball_model = 'frictional': expected physics.model = \"spin\" first",
        ),
        (
            SPIN + 'ball_model = "sticky"\n' + BALL,
            'physics.ball_model = \'sticky\': expected one of "frictionless", "frictional"',
        ),
        (SPIN + "ball_friction_a = -0.01\n" + BALL, "physics.ball_friction_a = -0.01: expected"),
        (SPIN + 'ball_friction_b = "high"\n' + BALL, "physics.ball_friction_b = 'high': expected"),
        (SPIN + "ball_friction_c = nan\n" + BALL, "physics.ball_friction_c = nan: expected"),
        (SPIN + "ball_frictoin_a = 0.01\n" + BALL, 'did you mean "ball_friction_a"?'),
    ],
)
def test_bad_ball_friction_key_is_one_line_naming_it(text: str, message: str) -> None:
    with pytest.raises(SceneError) as caught:
        parse_scene(text, "s.toml")
    assert message in str(caught.value) and "\n" not in str(caught.value)


@pytest.mark.long
def test_a_frictional_law_in_the_rolling_model_exits_2_in_one_line(tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text('[physics]\nball_model = "frictional"\n' + BALL)
    run = run_module("billiards.simulate", str(scene))
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.strip().count("\n") == 0 and "Traceback" not in run.stderr
    assert "physics.ball_model = 'frictional': expected physics.model = \"spin\" first" in (
        run.stderr
    )


def test_the_keys_reach_the_physics_and_default_to_the_seeds() -> None:
    text = SPIN + 'ball_model = "frictional"\nball_friction_a = 0.02\nball_friction_c = 2.0\n'
    setup = setup_from_scene(parse_scene(text + BALL))
    assert setup.ball_law == "frictional"
    assert setup.ball_friction == (0.02, seed.BALL_FRICTION_B, 2.0)
    assert Setup.ball_friction == (seed.BALL_FRICTION_A, seed.BALL_FRICTION_B, seed.BALL_FRICTION_C)
    default = setup_from_scene(parse_scene(SPIN + BALL))
    assert default.ball_law == "frictionless"


def test_the_frictional_law_without_friction_gives_the_spin_break_bit_for_bit() -> None:
    # Friction 0: the frictional law's normal impulse is the frictionless law's, to the
    # bit, through a whole break (every contact, the pressed and held ones too).
    scene = load_scene("spin_break")
    plain = simulate_scene(scene, method="event")
    without = replace(
        scene.physics, ball_model="frictional", ball_friction_a=0.0, ball_friction_b=0.0
    )
    assert fingerprint(simulate_scene(replace(scene, physics=without), method="event")) == (
        fingerprint(plain)
    )


def test_without_friction_every_anchor_is_the_frictionless_laws_signs_of_zero_included() -> None:
    # Issue 30's repro: the frictional law at a = b = c = 0 once left one anchor's spin
    # -0.0 where the frictionless law keeps +0.0 (a zero friction impulse added).
    scene = load_scene(
        Path(__file__).parent / "physics/scenes/frictional_zero_friction_signed_zero.toml"
    )
    frictional = simulate_scene(scene, method="event").motion
    plain = replace(scene, physics=replace(scene.physics, ball_model="frictionless"))
    frictionless = simulate_scene(plain, method="event").motion
    assert isinstance(frictional, SpinMotion) and isinstance(frictionless, SpinMotion)
    for part in ("ball", "t0", "p0", "v0", "w0", "state"):
        assert getattr(frictional, part).tobytes() == getattr(frictionless, part).tobytes(), part


def test_throw_shot_drops_ball_1_only_by_its_throw() -> None:
    scene = load_scene(default_scene_path().parent / "throw_shot.toml")
    thrown = simulate_scene(scene)
    assert [(p.ball, p.pocket) for p in thrown.pocketed] == [("1", "foot-left")]
    # Along the line of centres (no ball friction), ball 1 meets the long cushion short
    # of the corner, then its jaw, and stays on the table.
    frictionless = replace(scene, physics=replace(scene.physics, ball_model="frictionless"))
    straight = simulate_scene(frictionless)
    assert straight.pocketed == ()
    assert [e.kind for e in straight.events if e.balls == ("1",)] == ["cushion", "cushion"]
    assert thrown.complete and straight.complete
