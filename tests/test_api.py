"""The library (`import billiards`): its examples run, its results are the commands'
bit for bit, and its errors name the key and the value."""

from __future__ import annotations

import doctest
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import billiards
import billiards.api
from billiards.scene.reader import load_scene as read_scene_file
from billiards.simulation import simulate_scene
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
