"""Scene files: defaults, and one clear line for each kind of bad input."""

from __future__ import annotations

from pathlib import Path

import pytest

from billiards.scene.reader import SceneError, default_scene_path, load_scene, parse_scene
from tests.commands import run_module


def test_seed_break_defaults_match_the_model() -> None:
    scene = load_scene()
    assert scene.table.length == 2.13 and scene.table.width == 1.065
    assert scene.table.cushion_retention == 0.75
    assert scene.physics.rolling_friction == 0.01 and scene.physics.gravity == 9.81
    assert scene.radius == 0.0286
    assert scene.ball_ids[0] == "cue" and len(scene.balls) == 16
    cue = scene.balls[0]
    assert cue.position == (0.5325, 0.5325) and cue.velocity == (3.0, 0.0) and cue.mass == 0.170
    apex = scene.balls[1]
    assert apex.position == (1.5975, 0.5325) and apex.mass == 0.165


def test_every_shipped_scene_loads() -> None:
    folder = default_scene_path().parent
    names = sorted(path.name for path in folder.glob("*.toml"))
    assert {"break.toml", "hard_break.toml", "bank_shot.toml", "newtons_cradle.toml"} <= set(names)
    for name in names:
        assert load_scene(folder / name).balls


def test_rack_neighbours_sit_two_radii_plus_gap_apart() -> None:
    scene = parse_scene("[rack]\ngap = 0.001")
    positions = [ball.position for ball in scene.balls]
    nearest = min(
        ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5
        for i, a in enumerate(positions)
        for b in positions[i + 1 :]
    )
    assert nearest == pytest.approx(2 * 0.0286 + 0.001, rel=1e-12)


BAD_SCENES = [
    ("[table\nlength = 2", "TOML syntax error"),
    ("[table]\nlenght = 2.0", 'table.lenght: unknown key (did you mean "length"?)'),
    ("[tabel]\nlength = 2.0", 'tabel: unknown key (did you mean "table"?)'),
    ('[table]\nlength = "long"', "table.length = 'long': expected a number in (0, 100] m"),
    ("[balls]\nradius = 0", "balls.radius = 0: expected a number in [0.001, 1] m"),
    (
        "[table]\ncushion_retention = 1.5",
        "table.cushion_retention = 1.5: expected a number in [0, 1]",
    ),
    (
        "[physics]\nball_restitution = -0.1",
        "physics.ball_restitution = -0.1: expected a number in [0, 1]",
    ),
    (
        '[simulation]\nmethod = "rk4"',
        'simulation.method = \'rk4\': expected one of "exact", "event", "naive"',
    ),
    ("[simulation]\ndt = 0", "simulation.dt = 0: expected a number in [1e-06, 1] s"),
    (
        '[[ball]]\nid = "a"\nposition = [5.0, 0.5]',
        'ball[0] (id "a") position = [5, 0.5]: expected a centre inside',
    ),
    (
        '[[ball]]\nid = "a"\nposition = [0.5, 0.5]\n[[ball]]\nid = "b"\nposition = [0.52, 0.5]',
        'ball[0] (id "a") position = [0.5, 0.5]: expected no overlap',
    ),
    (
        '[[ball]]\nid = "a"\nposition = [0.5, 0.5]\n[[ball]]\nid = "a"\nposition = [0.9, 0.5]',
        'ball[1].id = "a": expected a unique id',
    ),
    (
        '[[ball]]\nid = "a"\nposition = [0.5]',
        "ball[0].position = [0.5]: expected an array of 2 finite numbers",
    ),
    ('[[ball]]\nid = "a"', "ball[0].position: missing"),
    ("[[ball]]\nposition = [0.5, 0.5]", "ball[0].id: missing; expected a unique string"),
    ('[[ball]]\nid = "a"\nposition = [0.5, 0.5]\nvelocity = [nan, 0.0]', "ball[0].velocity"),
    # Pockets: a mouth no ball passes, one the cushions cannot hold, a table too small.
    (
        "[table]\npockets = true\ncorner_pocket_width = 0.05",
        "table.corner_pocket_width = 0.05: expected a mouth a ball passes (above 0.0618863 m)",
    ),
    (
        "[table]\npockets = true\nside_pocket_width = 0.06",
        "table.side_pocket_width = 0.06: expected a mouth a ball passes (above 0.0732",
    ),
    (
        "[table]\npockets = true\nside_pocket_width = 2.0",
        "table.side_pocket_width = 2.0: expected mouths the long cushions hold (below 1.96",
    ),
    (
        '[table]\npockets = true\nlength = 0.3\nwidth = 0.15\n[[ball]]\nid = "a"\nposition = [0.1, 0.07]',
        "table.corner_pocket_width = 0.1143: expected mouths the short cushions hold (below 0.106",
    ),
    ('[table]\npockets = "yes"', "table.pockets = 'yes': expected true or false"),
    (
        '[table]\npockets = true\n[[ball]]\nid = "a"\nposition = [0.03, 0.03]',
        'ball[0] (id "a") position = [0.03, 0.03]: expected a centre on the table, not already '
        "in the head-right pocket",
    ),
]


@pytest.mark.parametrize(("text", "message"), BAD_SCENES)
def test_bad_scene_is_one_line_naming_key_value_and_expectation(text: str, message: str) -> None:
    with pytest.raises(SceneError) as caught:
        parse_scene(text, "bad.toml")
    line = str(caught.value)
    assert "\n" not in line
    assert line.startswith("bad.toml: ")
    assert message in line


def test_bad_scene_on_the_command_line_exits_2_without_traceback(tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text("[table]\ncushion_retention = 2.0\n")
    run = run_module("billiards.simulate", str(scene))
    assert run.returncode == 2
    assert run.stdout == ""
    assert run.stderr.strip().count("\n") == 0
    assert "table.cushion_retention = 2.0: expected a number in [0, 1]" in run.stderr
    assert "Traceback" not in run.stderr


@pytest.mark.long
def test_bad_pocket_geometry_on_the_command_line_exits_2_without_traceback(
    tmp_path: Path,
) -> None:
    scene = tmp_path / "narrow.toml"
    scene.write_text("[table]\npockets = true\nside_pocket_width = 0.05\n")
    for module in ("billiards.simulate", "billiards.plot"):
        run = run_module(module, str(scene))
        assert run.returncode == 2
        assert run.stderr.strip().count("\n") == 0
        assert "table.side_pocket_width = 0.05: expected a mouth a ball passes" in run.stderr


def test_pockets_are_off_unless_a_scene_turns_them_on() -> None:
    assert not load_scene().table.pockets
    assert parse_scene("[table]\npockets = true").table.pockets
    assert load_scene("pool_break").table.pockets


def test_a_scene_without_balls_gets_the_seed_cue_ball_and_rack_on_its_table() -> None:
    scene = parse_scene("[table]\nlength = 2.54\nwidth = 1.27\n[physics]\nrolling_friction = 0.02")
    assert scene.ball_ids[0] == "cue" and len(scene.balls) == 16
    cue = scene.balls[0]
    assert cue.position == (2.54 / 4, 1.27 / 2) and cue.velocity == (3.0, 0.0)
    assert scene.balls[1].position[0] == 0.75 * 2.54  # the apex on the foot spot
    assert scene.physics.rolling_friction == 0.02


def test_a_shipped_scene_is_found_by_name_and_an_unknown_name_lists_them() -> None:
    assert load_scene("hard_break").ball_ids == load_scene("hard_break.toml").ball_ids
    with pytest.raises(
        SceneError, match=r"nosuch: no such scene file, nor a shipped scene \(.*break"
    ):
        load_scene("nosuch")
