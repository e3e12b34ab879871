"""Every number the scene reader accepts gives a finite run; one past a bound is refused.

The bounds and their reasons are billiards.scene.bounds.BOUNDS (docs/scene_bounds.md).
A scene at a bound simulates (and, for the film's keys, films: its camera poses) with
every number finite; a scene just past it is a SceneError naming the key. The issue's
measured cases (a ball at 1e300 or 1e160 m/s, radius 1e-300, plot --width 100000) are
commands here, and the commands fail in one line when a run still goes non-finite.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from billiards.record.window import film_trajectory
from billiards.scene.bounds import BOUNDS, DOCS, MAX_SPEED, MAX_SURFACE_SPEED
from billiards.scene.reader import Scene, SceneError, load_scene, scene_from_dict
from billiards.simulation import NonFiniteRun, simulate_batch, simulate_scene
from billiards.stage.cameras import CameraTimeline, Stage, default_shots
from tests.commands import run_module

ROOT = Path(__file__).resolve().parent.parent

# The keys only the spin model reads (a rolling scene refuses spin, tip and cue).
SPIN_KEYS = {key for key in BOUNDS if key.startswith(("ball.cue.", "ball.spin"))} | {
    "physics.sliding_friction",
    "physics.spinning_friction",
    "physics.cushion_friction",
    "physics.cushion_restitution_speed",
    "physics.ball_friction_a",
    "physics.ball_friction_b",
    "physics.ball_friction_c",
}
VECTOR_KEYS = {"ball.velocity", "ball.spin", "camera.eye", "camera.target"}
FILM_KEYS = {key for key in BOUNDS if key.startswith(("render.", "camera."))}


def base_scene(model: str, method: str) -> dict[str, Any]:
    """Two balls, the cue ball into the other: a short run that takes every contact
    kind (ball, cushion) and, in the spin model, every law that has a friction."""
    data: dict[str, Any] = {
        "physics": {"model": model},
        "ball": [
            {"id": "cue", "position": [0.5, 0.5], "velocity": [2.0, 0.3]},
            {"id": "1", "position": [1.5, 0.55]},
        ],
        "simulation": {"method": method, "max_time": 0.5},
    }
    if model == "spin":
        data["physics"] |= {"cushion_model": "han2005", "ball_model": "frictional"}
    return data


def with_value(data: dict[str, Any], key: str, value: Any) -> dict[str, Any]:
    """The scene's tables with `key` (a BOUNDS key) set to `value`."""
    data = copy.deepcopy(data)
    section, *rest = key.split(".")
    if section == "ball":
        cue = data["ball"][0]
        if rest[0] == "cue":
            del cue["velocity"]
            cue["cue"] = {"speed": 2.0, rest[1]: value}
        else:
            cue[rest[0]] = value
    elif section == "camera":
        # An overhead shot, then one from an eye that eases in (and orbits).
        shot: dict[str, Any] = {
            "start": 0.1,
            "eye": [1.0, -2.0, 1.5],
            "target": [1.0, 0.5, 0.0],
            "transition": "ease",
            "ease": 0.5,
            "orbit": 30.0,
        }
        data["camera"] = [{"preset": "overhead"}, shot | {rest[0]: value}]
    else:
        data.setdefault(section, {})[rest[0]] = value
    if key == "physics.cushion_restitution_speed":
        data["physics"]["cushion_model"] = "mathavan2010_ev"  # the law that reads it
    if key == "rack.gap":
        # A rack whose widest gap still fits: on a 10 m table, the cue ball before it.
        data["table"] = {"length": 10.0, "width": 10.0}
        data["rack"]["apex"] = [3.0, 5.0]
        data["ball"] = [{"id": "cue", "position": [0.5, 5.0], "velocity": [2.0, 0.0]}]
    if key == "simulation.dt":
        data["simulation"]["max_time"] = max(value, 0.5)  # a step within the run
    if key == "simulation.max_time":
        data["simulation"]["dt"] = max(min(value, 1 / 240), BOUNDS["simulation.dt"].low)
    if key == "balls.radius":
        # The cushion nose at its usual share of the ball's height (han2005 wants it
        # between the equator and the top), and for a large ball a table to match.
        data["physics"]["cushion_height"] = 1.27 * value
        if value > 0.1:
            data["table"] = {"length": 21.3, "width": 10.65}
            for ball in data["ball"]:
                ball["position"] = [10 * ball["position"][0], 10 * ball["position"][1]]
    if key in ("table.length", "table.width") and 0 < value < 0.1:
        # The ball's own floor under a tiny table: it must fit (a diameter less).
        data["balls"] = {"radius": 0.001}
        data["physics"]["cushion_height"] = 0.00127
        data["ball"] = [{"id": "cue", "position": [value / 2, value / 2], "velocity": [1.0, 1.0]}]
        other = "width" if key == "table.length" else "length"
        data["table"][other] = value
    return data


def at_and_past(key: str, side: str, sign: float) -> tuple[Any, Any]:
    """A value at the bound's `side` ("low" or "high") and one just past it: the
    value as a vector along an axis (sign -1: the other way) for a vector key."""
    bound = BOUNDS[key]
    if key == "ball.velocity":
        high = MAX_SPEED
        return [sign * high, 0.0], [sign * math.nextafter(high, math.inf), 0.0]
    if key == "ball.spin":
        # The surface speed |spin| r at the bound: rounding may land the product on
        # either side, so a hair inside and a hair outside.
        spin = MAX_SURFACE_SPEED / 0.0286
        return [0.0, 0.0, sign * spin * (1 - 1e-12)], [0.0, 0.0, sign * spin * (1 + 1e-12)]
    if side == "low":
        if bound.low_open:
            at, past = math.nextafter(bound.low, math.inf), bound.low
        else:
            at, past = bound.low, math.nextafter(bound.low, -math.inf)
        if key in ("table.length", "table.width"):
            at = 0.002 * (1 + 1e-9)  # the smallest table: the smallest ball's diameter
    else:
        at, past = bound.high, math.nextafter(bound.high, math.inf)
    if key in VECTOR_KEYS:  # camera eye, target: each coordinate
        return [at, 0.5, 1.0], [past, 0.5, 1.0]
    return at, past


def sides(key: str) -> list[str]:
    return ["high"] if key in ("ball.velocity", "ball.spin") else ["low", "high"]


CASES = [(key, side) for key in sorted(BOUNDS) for side in sides(key)]


def assert_runs_finite(scene: Scene) -> None:
    result = simulate_scene(scene)  # NonFiniteRun if any number went wrong
    assert np.isfinite(result.final_positions).all()
    if scene.render.cameras or scene.render.lead or scene.render.tail:
        trajectory = film_trajectory(result, scene.render)
        assert np.isfinite(trajectory.positions).all()
        shots = scene.render.cameras or default_shots(trajectory)
        cameras = CameraTimeline(shots, Stage.of(trajectory), 16 / 9)
        times = [float(trajectory.times[0]), float(trajectory.times[-1])]
        for shot in scene.render.cameras:
            start = shot.start if shot.start is not None else times[0]
            times += [start, start + shot.ease / 2, start + shot.ease]
        for time in times:
            pose = cameras.pose(time)
            assert np.isfinite(pose.view_projection(16 / 9)).all(), (time, pose)


def check_bound(
    key: str, side: str, model: str, method: str, sign: float, pockets: bool = False
) -> None:
    if key in SPIN_KEYS:
        model = "spin"
    if key == "simulation.dt" and side == "low":
        method = "exact"  # naive at a microsecond: 5e5 steps, finite but slow
    if key == "ball.cue.elevation" and method == "naive":
        method = "exact"  # the steepest stroke jumps: a ball in the air is not naive's
    at, past = at_and_past(key, side, sign)
    data = base_scene(model, method)
    if pockets and not key.startswith(("table.", "balls.radius", "rack.")):
        data["table"] = {"pockets": True}  # the jaws and the drops too
    scene = scene_from_dict(with_value(data, key, at), "at.toml")
    assert_runs_finite(scene)
    with pytest.raises(SceneError) as refused:
        scene_from_dict(with_value(data, key, past), "past.toml")
    assert f"{key.split('.')[-1]} = " in str(refused.value)
    assert "\n" not in str(refused.value)


@pytest.mark.parametrize(("key", "side"), CASES)
def test_a_scene_at_a_bound_runs_finite_and_one_past_it_is_refused(key: str, side: str) -> None:
    check_bound(key, side, "rolling", "event", 1.0)


BOUND_DRAWS = st.tuples(
    st.sampled_from(CASES),
    st.sampled_from(["rolling", "spin"]),
    st.sampled_from(["exact", "event", "naive"]),
    st.sampled_from([1.0, -1.0]),
    st.booleans(),
)


@settings(derandomize=True, database=None, deadline=None, max_examples=12)
@given(BOUND_DRAWS)
def test_drawn_scenes_at_and_past_the_bounds(draw: tuple[Any, str, str, float, bool]) -> None:
    (key, side), model, method, sign, pockets = draw
    check_bound(key, side, model, method, sign, pockets)


@pytest.mark.hard
@settings(derandomize=True, database=None, deadline=None, max_examples=600)
@given(BOUND_DRAWS)
def test_many_drawn_scenes_at_and_past_the_bounds(
    draw: tuple[Any, str, str, float, bool],
) -> None:
    (key, side), model, method, sign, pockets = draw
    check_bound(key, side, model, method, sign, pockets)


def test_the_docs_page_gives_every_bound_and_its_reason() -> None:
    page = (ROOT / DOCS).read_text(encoding="utf-8")
    for key, bound in BOUNDS.items():
        assert f"`{key}`" in page, key
        assert bound.reason.split(";")[0][:40] in " ".join(page.split()), key


def test_the_shipped_scenes_are_within_the_bounds() -> None:
    from billiards.scene.reader import shipped_scene_names

    for name in shipped_scene_names():
        load_scene(name)  # a SceneError would name the key


# --- the measured cases, as a user meets them -------------------------------------


def scene_file(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "s.toml"
    path.write_text(text)
    return path


FAST = '[[ball]]\nid = "cue"\nposition = [0.5, 0.6]\nvelocity = [{speed}, 0.0]\n'


@pytest.mark.long
@pytest.mark.parametrize("speed", ["1e300", "1e160"])
@pytest.mark.parametrize("command", ["billiards.simulate", "billiards.render"])
def test_an_absurd_ball_speed_is_one_line_and_exit_2(
    command: str, speed: str, tmp_path: Path
) -> None:
    path = scene_file(tmp_path, FAST.format(speed=speed))
    args = ["--json"] if command == "billiards.simulate" else ["-o", str(tmp_path / "f.mp4")]
    run = run_module(command, str(path), *args)
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.count("\n") == 1, run.stderr
    assert f"ball[0].velocity = [{float(speed)!r}, 0.0]: expected a speed" in run.stderr
    assert "nan" not in run.stderr.lower() and list(tmp_path.iterdir()) == [path]


def test_a_vanishing_radius_is_one_line_and_exit_2(tmp_path: Path) -> None:
    run = run_module("billiards.simulate", str(scene_file(tmp_path, "[balls]\nradius = 1e-300\n")))
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr
    assert "balls.radius = 1e-300: expected a number in [0.001, 1] m" in run.stderr


def test_a_vanishing_cushion_restitution_speed_is_one_line_and_exit_2(tmp_path: Path) -> None:
    # Any v_c > 0 runs finite, but 1e-300 m/s makes every rebound dead: a typo, refused.
    scene = '[physics]\nmodel = "spin"\ncushion_model = "mathavan2010_ev"\n'
    run = run_module(
        "billiards.simulate",
        str(scene_file(tmp_path, scene + "cushion_restitution_speed = 1e-300\n")),
    )
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr
    assert (
        "physics.cushion_restitution_speed = 1e-300: expected a number in [0.01, 1000] m/s"
        in run.stderr
    )


@pytest.mark.long
def test_plot_refuses_a_huge_picture_at_once(tmp_path: Path) -> None:
    run = run_module("billiards.plot", "--width", "100000", cwd=tmp_path, timeout=30)
    assert run.returncode == 2 and list(tmp_path.iterdir()) == []
    assert run.stderr == (
        "error: --width 100000: expected a picture at most 4096 px a side "
        "(this table's would be 100000 x 65383 px)\n"
    )


def runaway_scene() -> Scene:
    """A scene past the reader's bounds (a cue ball at 1e300 m/s), built as only code
    can build it: its run overflows into nan."""
    scene = load_scene()
    cue = dataclasses.replace(scene.balls[0], velocity=(1e300, 0.0))
    return dataclasses.replace(scene, balls=(cue, *scene.balls[1:]))


def test_a_non_finite_run_is_an_error_not_a_result() -> None:
    with np.errstate(all="ignore"), pytest.raises(NonFiniteRun, match="not finite"):
        simulate_scene(runaway_scene())


def test_a_non_finite_run_in_a_batch_fails_alone() -> None:
    scene = load_scene()
    with np.errstate(all="ignore"):
        outcomes = list(simulate_batch([scene, runaway_scene(), scene]))
    assert isinstance(outcomes[1], NonFiniteRun)
    assert not isinstance(outcomes[0], Exception) and not isinstance(outcomes[2], Exception)


def test_a_division_by_zero_in_a_run_is_a_non_finite_run(monkeypatch: pytest.MonkeyPatch) -> None:
    import billiards.simulation

    def divide(*args: object) -> None:
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(billiards.simulation, "run", divide)
    with pytest.raises(NonFiniteRun, match=r"arithmetic failed \(float division by zero\)"):
        simulate_scene(load_scene())


@pytest.mark.parametrize(
    ("module", "args"),
    [
        ("billiards.simulate", ["--json"]),
        ("billiards.simulate", []),
        ("billiards.plot", ["-o", "p.png"]),
        ("billiards.render", ["-o", "f.mp4"]),
    ],
)
def test_a_command_whose_run_goes_non_finite_fails_in_one_line(
    module: str,
    args: list[str],
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
) -> None:
    import importlib

    import billiards.scene.reader

    command = importlib.import_module(
        module if module != "billiards.render" else module + ".__main__"
    )
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(billiards.scene.reader, "load_scene", lambda path=None: runaway_scene())
    if hasattr(command, "load_scene"):
        monkeypatch.setattr(command, "load_scene", lambda path=None: runaway_scene())
    assert command.main(args) == 1
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "not finite" in err, err
    assert "nan" not in (out + err).lower() and list(tmp_path.iterdir()) == []


def test_simulate_prints_only_strict_json() -> None:
    from billiards.record.result_json import result_json

    scene = load_scene()
    data = result_json(simulate_scene(scene), [0.5], scene)
    json.loads(json.dumps(data, allow_nan=False))  # no NaN, no Infinity


def test_a_step_longer_than_the_run_is_refused() -> None:
    # A naive run stepping by more than max_time took no step, and its one sample
    # divided 0 by 0 when asked for the final positions.
    text = '[simulation]\nmethod = "naive"\ndt = 1.0\nmax_time = 0.5\n'
    with pytest.raises(SceneError, match=r"simulation.dt = 1.0: expected a step no longer"):
        scene_from_dict(tomllib.loads(text), "s.toml")


@pytest.mark.long
@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--dt", "1e-300"], "--dt '1e-300': expected seconds in [1e-06, 1] s"),
        (["--dt", "1e300"], "--dt '1e300': expected seconds in [1e-06, 1] s"),
        (["s.toml", "--dt", "1"], "--dt 1: expected a step no longer than s.toml's max_time"),
    ],
)
def test_simulate_bounds_its_step_as_the_reader_does(
    args: list[str], expected: str, tmp_path: Path
) -> None:
    scene_file(tmp_path, "[simulation]\nmax_time = 0.5\n")
    run = run_module("billiards.simulate", *args, cwd=tmp_path)
    assert run.returncode == 2 and run.stdout == "" and run.stderr.count("\n") == 1
    assert expected in run.stderr, run.stderr
