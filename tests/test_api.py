"""The library (`import billiards`): its examples run, its results are the commands'
bit for bit, and its errors name the key and the value."""

from __future__ import annotations

import doctest
import json
import math
import subprocess
import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any, cast

import numpy as np
import pytest
from PIL import Image

import billiards
import billiards.api
from billiards.scene.reader import find_scene
from billiards.scene.reader import load_scene as read_scene_file
from billiards.simulation import simulate_scene
from tests.commands import run_module
from tests.render.fixtures import needs_gl


def test_the_api_docstrings_examples_run_as_written() -> None:
    outcome = doctest.testmod(
        billiards.api, extraglobs={"billiards": billiards}, optionflags=doctest.ELLIPSIS
    )
    assert outcome.attempted >= 15  # the examples were found
    assert outcome.failed == 0


def test_every_public_name_is_there_and_typed_in_the_api() -> None:
    for name in billiards.__all__:
        assert getattr(billiards, name) is not None
        assert name in dir(billiards)
    assert {"Any", "annotations", "TYPE_CHECKING"} & set(dir(billiards)) == set()
    with pytest.raises(AttributeError, match="no attribute 'simulat'"):
        billiards.simulat  # noqa: B018 (the attribute lookup is the test)


def test_no_public_name_is_hidden_by_a_module_of_the_same_name() -> None:
    """Importing billiards.X sets the attribute X on the package: a function named like
    a module (billiards.simulate, the command) would be replaced by it."""
    modules = {path.stem for path in Path(billiards.__file__).parent.iterdir()}
    assert set(billiards.__all__) & modules == set()


def test_importing_the_package_loads_none_of_the_library() -> None:
    """The commands and the physics import billiards: it must stay light."""
    code = "import sys, billiards.scene.reader; print('billiards.api' in sys.modules, 'PIL' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


def test_a_result_is_the_commands_simulation_bit_for_bit() -> None:
    result = billiards.run("pool_break")
    alone = simulate_scene(read_scene_file("pool_break"))
    assert result.events == alone.events
    assert result.final_positions.tobytes() == alone.final_positions.tobytes()
    assert [drop.ball for drop in result.pocketed] == ["12"]  # pool_break's drop


def test_simulate_many_gives_each_scene_what_simulate_gives_it() -> None:
    speeds = (1.5, 3.0, 4.5)
    scenes = [billiards.vary("hard_break", {"ball.cue.velocity": speed}) for speed in speeds]
    together = list(billiards.run_many(scenes))
    for scene, outcome in zip(scenes, together, strict=True):
        assert isinstance(outcome, billiards.Result)
        assert outcome.scene is scene
        alone = billiards.run(scene)
        assert outcome.events == alone.events
        assert outcome.final_positions.tobytes() == alone.final_positions.tobytes()


def test_a_state_is_the_simulations_motion_at_that_time() -> None:
    result = billiards.run("draw_shot")
    state = result.state_at(0.3)
    times = np.array([0.3])
    cue = result.ball_ids.index("cue")
    assert state.ball("cue").position == tuple(result.simulation.positions_at(times)[0, cue])
    assert state.ball("cue").spin == tuple(result.simulation.spins_at(times)[0, cue])
    with pytest.raises(KeyError, match="'16': no such ball"):
        state.ball("16")


def test_a_changed_table_dict_is_read_as_the_file_would_be() -> None:
    tables = billiards.scene_tables("break")
    tables["physics"]["rolling_friction"] = 0.02
    slower = billiards.run(tables)
    assert slower.rest_time < billiards.run("break").rest_time  # more friction, sooner
    assert billiards.load_scene(slower.scene) is slower.scene


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: billiards.load_scene({"physics": {"model": "spinning"}}),
            'physics.model = \'spinning\': expected one of "rolling", "spin"',
        ),
        (
            lambda: billiards.load_scene({"table": {"lenght": 2.0}}),
            'table.lenght: unknown key (did you mean "length"?)',
        ),
        (lambda: billiards.load_scene("no_such_scene"), "no_such_scene: no such scene file"),
        (
            lambda: billiards.vary("break", {"physics.ball_restitution": 1.5}),
            "physics.ball_restitution = 1.5: expected a number in [0, 1]",
        ),
        (lambda: billiards.run("break", method="rk4"), "method = 'rk4': expected one of"),
        (
            lambda: billiards.render_film(billiards.run("bank_shot"), "x.mp4", width=641),
            "width = 641: expected an even whole number >= 16",
        ),
        (
            lambda: billiards.render_still(billiards.run("bank_shot"), 99.0, "x.png"),
            "time = 99: expected a time in s within the film",
        ),
    ],
)
def test_bad_input_is_a_scene_error_naming_the_key_and_value(call: object, message: str) -> None:
    assert callable(call)
    with pytest.raises(billiards.SceneError) as caught:
        call()
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_the_top_view_is_saved_and_shown_in_a_notebook(tmp_path: Path) -> None:
    result = billiards.run("pocket_shot")
    image = billiards.plot_top_view(result, tmp_path / "shot.png", width=400)
    assert image.width == 400
    with Image.open(tmp_path / "shot.png") as saved:
        assert saved.size == image.size
    png = result._repr_png_()
    assert png.startswith(b"\x89PNG")
    assert "pocketed: 1 (foot-left)" in repr(result)


@pytest.mark.gl
@needs_gl
def test_a_still_is_rendered_at_the_size_asked(tmp_path: Path) -> None:
    result = billiards.run("pocket_shot")
    path = billiards.render_still(result, 0.5, tmp_path / "still.png", width=160, height=90)
    with Image.open(path) as still:
        assert still.size == (160, 90)
        # Not a blank frame: the cloth, the rails and the balls differ.
        colours = np.asarray(still.convert("RGB")).reshape(-1, 3)
        assert len(np.unique(colours, axis=0)) > 50


# --- every function takes what its siblings take, and refuses the rest in one line -------


def test_every_function_takes_a_scene_a_dict_a_name_or_a_path() -> None:
    scene = billiards.load_scene("pocket_shot")
    tables = billiards.scene_tables("pocket_shot")
    path = find_scene("pocket_shot")
    for source in (scene, tables, "pocket_shot", path, str(path)):
        assert billiards.load_scene(source).balls == scene.balls
        assert billiards.scene_tables(source)["ball"][0]["id"] == "cue"
        faster = billiards.vary(source, {"ball.cue.velocity": 2.0})
        assert math.isclose(math.sqrt(sum(v * v for v in faster.balls[0].velocity)), 2.0)
        assert billiards.plot_top_view(source, width=64).width == 64
    assert billiards.run(scene) == billiards.run("pocket_shot")
    runs = [billiards.run(source) for source in (scene, tables, path)]
    assert len({(result.events, result.final_positions.tobytes()) for result in runs}) == 1


def test_a_varied_scene_keeps_its_film_settings() -> None:
    scene = billiards.load_scene("three_cushion")
    assert billiards.vary(scene, {"physics.rolling_friction": 0.02}).render == scene.render
    assert billiards.vary("three_cushion", {"physics.rolling_friction": 0.02}).render == (
        scene.render
    )


def _natural_mistakes() -> list[tuple[str, Callable[[], object], str]]:
    """The issue's list (42, item 3): what each call must say instead of a traceback
    from deep inside."""
    # Any: these calls are wrong on purpose, as a user's first tries are.
    scene = billiards.load_scene("pocket_shot")
    result: Any = billiards.run("newtons_cradle")
    library: Any = billiards
    return [
        ("vary a Scene", lambda: library.vary(scene, {"physics.gravity": -1.0}), "-1"),
        (
            "vary a pair",
            lambda: library.vary("pocket_shot", {"ball.cue.velocity": (1.0, 0.5)}),
            "values['ball.cue.velocity'] = (1.0, 0.5): expected a finite number",
        ),
        (
            "vary a list",
            lambda: library.vary("pocket_shot", [("ball.cue.velocity", 1.0)]),
            "values = [('ball.cue.velocity', 1.0)]: expected a dict",
        ),
        (
            "state_at many times",
            lambda: result.state_at(np.linspace(0, 2, 5)),
            "time = array([0. , 0.5, 1. , 1.5, 2. ]): expected one time in s",
        ),
        ("state_at nan", lambda: result.state_at(math.nan), "time = nan: expected a finite"),
        ("state_at -1", lambda: result.state_at(-1.0), "time = -1: expected a time in s from 0"),
        ("state_at a word", lambda: result.state_at("1"), "time = '1': expected a finite"),
        ("an svg", lambda: library.plot_top_view(result, "x.svg"), "path = 'x.svg': expected"),
        ("a float width", lambda: library.plot_top_view(result, width=64.5), "width = 64.5"),
        ("run 42", lambda: library.run(42), "scene = 42: expected a shipped scene's name"),
        ("run a long name", lambda: library.run("x" * 300), "no such scene file"),
        ("run dt", lambda: library.run(scene, dt="0.1"), "dt = '0.1': expected a finite"),
        ("run dt 5", lambda: library.run(scene, dt=5.0), "dt = 5: expected seconds in"),
        ("run_many a name", lambda: library.run_many("break"), "scenes = 'break': expected"),
        ("run_many 3", lambda: library.run_many(3), "scenes = 3: expected a list"),
        ("a film in .avi", lambda: library.render_film(result, "x.avi"), "path = 'x.avi'"),
        (
            "a still at noon",
            lambda: library.render_still(result, "noon", "x.png"),
            "time = 'noon': expected a finite number",
        ),
        ("positions of words", lambda: result.positions(["a"]), "times = ['a']: expected"),
        ("positions at nan", lambda: result.positions([0.0, math.nan]), "times: nan: expected"),
        (
            "too many positions",
            lambda: result.positions(np.zeros(billiards.api.MAX_TIMES + 1)),
            "times: 100,001 of them: expected at most 100,000",
        ),
    ]


@pytest.mark.parametrize(
    ("call", "says"),
    [(call, says) for _, call, says in _natural_mistakes()],
    ids=[name for name, _, _ in _natural_mistakes()],
)
def test_a_natural_mistake_is_one_line_naming_the_argument_and_the_value(
    call: Callable[[], object], says: str
) -> None:
    with pytest.raises((billiards.SceneError, TypeError, ValueError)) as caught:
        call()
    assert says in str(caught.value)
    assert "\n" not in str(caught.value)


def test_a_bad_scene_among_many_is_that_scenes_outcome() -> None:
    sources: list[Any] = ["bank_shot", 42, {"table": {"length": -1}}]
    outcomes = list(billiards.run_many(sources))
    assert [type(outcome).__name__ for outcome in outcomes] == [
        "Result",
        "TypeError",
        "SceneError",
    ]


def test_results_and_states_compare_by_their_bits() -> None:
    one, again = billiards.run("pocket_shot"), billiards.run("pocket_shot")
    assert one == again and hash(one) == hash(again)
    assert one != billiards.run("pocket_shot", method="event")
    assert one != billiards.run("bank_shot")
    assert one.state_at(0.5) == again.state_at(0.5)
    assert one.state_at(0.5) != one.state_at(0.6)
    assert {one, again} == {one}


# --- a Scene changed in Python is checked as its file would be ------------------------


@pytest.mark.parametrize("name", billiards.shipped_scenes())
def test_every_shipped_scene_reads_back_from_its_own_tables(name: str) -> None:
    scene = billiards.load_scene(name)
    assert billiards.load_scene(scene) is scene
    assert billiards.load_scene(billiards.scene_tables(scene)).balls == scene.balls


def test_a_scene_changed_in_python_is_checked_as_its_file_would_be() -> None:
    scene = billiards.load_scene("pocket_shot")
    cue, one = scene.balls[:2]
    off_table = replace(scene, balls=(replace(cue, position=(5.0, 5.0)), *scene.balls[1:]))
    with pytest.raises(billiards.SceneError, match=r"position = \[5, 5\]: expected a centre"):
        billiards.run(off_table)
    overlapping = replace(scene, balls=(replace(cue, position=one.position), *scene.balls[1:]))
    with pytest.raises(billiards.SceneError, match="expected no overlap"):
        billiards.run(overlapping)
    wrong_table = replace(scene, table=replace(scene.table, length=cast(Any, "2.5")))
    with pytest.raises(billiards.SceneError, match=r"table\.length = '2\.5': expected a number"):
        billiards.plot_top_view(wrong_table)
    with pytest.raises(billiards.SceneError, match=r"balls = \(\): expected at least one ball"):
        billiards.run(replace(scene, balls=()))
    with pytest.raises(TypeError, match=r"scene\.balls\[0\] = 'cue': expected"):
        billiards.run(replace(scene, balls=cast(Any, ("cue",))))
    moved = replace(scene, balls=(replace(cue, position=(0.5, 0.5)), *scene.balls[1:]))
    assert billiards.run(moved).state_at(0.0).ball("cue").position == (0.5, 0.5)


def test_a_scene_the_reader_made_is_not_read_again_for_each_run(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A batch of scenes from the reader (vary's, say) costs no second reading; a scene
    changed in Python is read again, once."""
    from billiards.scene import reader

    read_again: list[str] = []
    tables_of = reader.scene_tables_of

    def counted(scene: billiards.Scene) -> dict[str, Any]:
        read_again.append(scene.source)
        return tables_of(scene)

    monkeypatch.setattr(reader, "scene_tables_of", counted)
    faster = [billiards.vary("break", {"ball.cue.velocity": speed}) for speed in (3.5, 4.0)]
    assert all(isinstance(result, billiards.Result) for result in billiards.run_many(faster))
    assert read_again == []
    cue = faster[0].balls[0]
    billiards.run(
        replace(faster[0], balls=(replace(cue, position=(0.5, 0.5)), *faster[0].balls[1:]))
    )
    assert len(read_again) == 1


def test_a_struck_balls_velocity_comes_from_its_stroke() -> None:
    scene = billiards.load_scene("masse_shot")
    struck = next(ball for ball in scene.balls if ball.stroke is not None)
    changed = replace(struck, velocity=(1.0, 0.0))
    balls = tuple(changed if ball is struck else ball for ball in scene.balls)
    with pytest.raises(billiards.SceneError, match="expected the velocity and spin its stroke"):
        billiards.run(replace(scene, balls=balls))


def test_the_scene_type_is_documented_and_its_example_runs() -> None:
    assert billiards.Scene.__doc__ and "dataclasses.replace" in billiards.Scene.__doc__
    page = (Path(__file__).parent.parent / "docs" / "reference" / "api.md").read_text()
    assert f"::: {billiards.Scene.__module__}.Scene" in page
    finder = doctest.DocTestFinder(recurse=False)
    runner = doctest.DocTestRunner()
    for test in finder.find(billiards.Scene, globs={"billiards": billiards}):
        runner.run(test)
    assert runner.summarize(verbose=False) == (0, 5)


# --- a trajectory as numbers -----------------------------------------------------------


def test_positions_velocities_and_spins_are_the_motion_at_many_times() -> None:
    result = billiards.run("draw_shot")
    times = np.linspace(0.0, result.rest_time + 1.0, 50)
    assert result.positions(times).tobytes() == result.simulation.positions_at(times).tobytes()
    assert result.velocities(times).tobytes() == result.simulation.velocities_at(times).tobytes()
    assert result.spins(times).tobytes() == result.simulation.spins_at(times).tobytes()
    grid = times.reshape(5, 10)
    assert result.positions(grid).shape == (5, 10, len(result.ball_ids), 2)
    assert result.spins(0.3).shape == (len(result.ball_ids), 3)
    state = result.state_at(0.3)
    assert result.velocities(0.3).tobytes() == state.velocities.tobytes()


@pytest.mark.long
def test_to_dict_is_what_simulate_json_prints() -> None:
    result = billiards.run("pocket_shot")
    out = run_module("billiards.simulate", "pocket_shot", "--json", "--times", "0.5,1")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == result.to_dict(times=[0.5, 1.0])
    assert json.dumps(result.to_dict(), allow_nan=False)  # strict JSON as it is
    assert "samples" not in result.to_dict()
