"""One pocket rule (billiards.rules.pocket_rule) for the scene reader and the physics: a
table the reader accepts is one the physics builds and simulates, also at the rule's
boundary, where rounding decides."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from billiards.physics.pockets import pocket_of, pocket_table
from billiards.rules.pocket_rule import corner_captures, corner_pocket_of, cushion_segments
from billiards.scene.reader import parse_scene, scene_from_dict
from billiards.scene.tables import SceneError
from billiards.simulation import simulate_scene
from tests.commands import run_module

REPEATABLE = settings(derandomize=True, database=None, deadline=None, max_examples=200)
LIMITS = ("corner_passes", "side_passes", "short_cushions", "long_cushions")

# The issue's file: the reader of the time accepted it, the physics refused it.
ISSUE_17_SCENE = """\
[table]
length = 2.1435825371889816
width = 0.9747187953365135
pockets = true
corner_pocket_width = 0.14302615058824117
side_pocket_width = 1.9413130152530742
[[ball]]
id = "cue"
position = [0.5, 0.5]
velocity = [1.0, 0.0]
"""


def _ulps(value: float, steps: int) -> float:
    for _ in range(abs(steps)):
        value = math.nextafter(value, math.copysign(math.inf, steps))
    return value


@st.composite
def tables_near_a_limit(draw: st.DrawFn) -> dict[str, Any]:
    """A [table] (and radius) with one pocket width within a few ulps of one of the
    rule's limits, computed in exact arithmetic."""
    length = draw(st.floats(0.3, 4.0))
    width = draw(st.floats(0.15, 2.0))
    radius = draw(st.floats(0.01, 0.06))
    rho = draw(st.sampled_from([0.0, 0.008, draw(st.floats(0.0, 0.03))]))
    limit = draw(st.sampled_from(LIMITS))
    corner = draw(st.floats(2 * radius + rho, max(2 * radius + rho, 0.6 * width)))
    side = draw(st.floats(2 * (radius + rho), max(2 * (radius + rho), 0.5 * length)))
    steps = draw(st.integers(-4, 4))
    if limit == "corner_passes":
        corner = _ulps(2 * radius + (2 - math.sqrt(2.0)) * rho, steps)
    elif limit == "side_passes":
        side = _ulps(2 * (radius + rho), steps)
    elif limit == "short_cushions":
        corner = _ulps(width / math.sqrt(2.0), steps)
    else:
        side = _ulps(length - math.sqrt(2.0) * corner, steps)
    table = {"length": length, "width": width, "pockets": True, "jaw_radius": rho}
    table |= {"corner_pocket_width": corner, "side_pocket_width": side}
    return {"table": table, "balls": {"radius": radius}}


def _pocket_table_of(data: dict[str, Any]) -> Any:
    table = data["table"]
    return pocket_table(
        (table["length"], table["width"]),
        data["balls"]["radius"],
        table["corner_pocket_width"],
        table["side_pocket_width"],
        table["jaw_radius"],
    )


@REPEATABLE
@given(tables_near_a_limit(), st.floats(0.0, 2 * math.pi))
def test_the_reader_accepts_a_pocket_table_exactly_when_the_physics_builds_it(
    data: dict[str, Any], heading: float
) -> None:
    table = data["table"]
    cue = [table["length"] / 2, table["width"] / 2]
    velocity = [math.cos(heading), math.sin(heading)]
    scene_data = {**data, "ball": [{"id": "cue", "position": cue, "velocity": velocity}]}
    try:
        scene_from_dict(scene_data, "t.toml")
    except SceneError as error:
        refused: str | None = str(error)
    else:
        refused = None
    try:
        pockets = _pocket_table_of(data)
    except ValueError as error:
        key = str(error).split(" = ")[0]  # the physics names the same key
        assert refused is not None and f"table.{key} = " in refused, (refused, error)
        return
    assert refused is None or "pocket_width" not in refused, refused
    # Every cushion the physics lays out keeps a length.
    for segments in pockets.segments:
        assert bool(np.all(segments[:, 0] < segments[:, 1]))


@settings(derandomize=True, database=None, deadline=None, max_examples=60)
@given(
    tables_near_a_limit(),
    st.floats(0.0, 2 * math.pi),
    st.sampled_from(["rolling", "spin"]),
    st.sampled_from(["exact", "naive"]),
    st.floats(0.3, 0.7),
    st.integers(-3, 3),
)
def test_a_scene_the_reader_accepts_near_a_pocket_limit_simulates(
    data: dict[str, Any], heading: float, model: str, method: str, along: float, steps: int
) -> None:
    table = data["table"]
    cue = [table["length"] / 2, table["width"] / 2]
    velocity = [2 * math.cos(heading), 2 * math.sin(heading)]
    balls = [{"id": "cue", "position": cue, "velocity": velocity}]
    # A second ball on the head-right pocket's capture line, moved by a few ulps (the
    # reader takes it where the mouth is wide enough for a centre inside the cushions).
    a, rho = table["corner_pocket_width"] / math.sqrt(2.0), table["jaw_radius"]
    x = _ulps(a + along * (-rho - a), steps)
    balls.append({"id": "1", "position": [x, a - rho - x], "velocity": [-0.5, -0.5]})
    scene_data = {
        **data,
        "physics": {"model": model},
        "simulation": {"method": method, "max_time": 5.0},
        "ball": balls,
    }
    try:
        scene = scene_from_dict(scene_data, "t.toml")
    except SceneError as error:
        if "ball[1]" not in str(error):
            return
        scene = scene_from_dict({**scene_data, "ball": balls[:1]}, "t.toml")  # the cue alone
    result = simulate_scene(scene)
    assert result.rest_time > 0


@REPEATABLE
@given(tables_near_a_limit(), st.floats(0.0, 1.0), st.integers(-3, 3), st.integers(0, 3))
def test_the_reader_and_the_physics_agree_on_a_centre_at_a_corner_capture_line(
    data: dict[str, Any], along: float, steps: int, corner: int
) -> None:
    table = data["table"]
    size = (table["length"], table["width"])
    try:
        pockets = _pocket_table_of(data)
    except ValueError:
        return
    lines = corner_captures(size, table["corner_pocket_width"], table["jaw_radius"])
    name = lines[corner][0]
    # A point on the capture line (between its jaw centres), moved by a few ulps.
    first, second = pockets.jaws[pockets.jaw_pocket == pockets.names.index(name)]
    x0, y0 = (first + along * (second - first)).tolist()
    x, y = _ulps(x0, steps), _ulps(y0, -steps)
    in_pocket = corner_pocket_of(size, table["corner_pocket_width"], table["jaw_radius"], (x, y))
    # The physics' own test, on its corner pockets (a centre the reader lets through
    # is inside the cushions, where no side pocket's line reaches).
    corners = [pockets.names.index(corner_name) for corner_name, _, _ in lines]
    corner_pockets = dataclasses.replace(
        pockets,
        capture_normal=pockets.capture_normal[corners],
        capture_level=pockets.capture_level[corners],
    )
    physics = int(pocket_of(corner_pockets, np.array([[x, y]]))[0])
    assert in_pocket == (None if physics < 0 else lines[physics][0])
    assert in_pocket in (None, name)


@REPEATABLE
@given(tables_near_a_limit())
def test_the_rule_lays_out_the_cushions_and_capture_lines_the_physics_uses(
    data: dict[str, Any],
) -> None:
    table = data["table"]
    size = (table["length"], table["width"])
    try:
        pockets = _pocket_table_of(data)
    except ValueError:
        return
    short, long = cushion_segments(size, table["corner_pocket_width"], table["side_pocket_width"])
    assert pockets.segments[0].tolist() == [list(short)]
    assert pockets.segments[2].tolist() == [list(segment) for segment in long]
    for name, normal, level in corner_captures(
        size, table["corner_pocket_width"], table["jaw_radius"]
    ):
        index = pockets.names.index(name)
        assert pockets.capture_normal[index].tolist() == list(normal)
        assert pockets.capture_level[index] == level


def test_the_issue_17_table_is_one_line_and_exit_2(tmp_path: Path) -> None:
    scene = tmp_path / "near.toml"
    scene.write_text(ISSUE_17_SCENE)
    run = run_module("billiards.simulate", str(scene))
    assert run.returncode == 2, run.stderr
    assert run.stderr.strip().count("\n") == 0 and "Traceback" not in run.stderr
    # The limit it names is the rule's own, so the value stands above it.
    assert run.stderr == (
        f"error: {scene}: table.side_pocket_width = 1.9413130152530742: expected mouths "
        "the long cushions hold (below 1.941313015253074 m)\n"
    )


def test_the_named_limit_is_refused_and_the_width_below_it_simulates() -> None:
    limit = 1.941313015253074
    with pytest.raises(SceneError, match="long cushions hold"):
        parse_scene(ISSUE_17_SCENE.replace("1.9413130152530742", repr(limit)))
    below = repr(math.nextafter(limit, 0.0))
    scene = parse_scene(ISSUE_17_SCENE.replace("1.9413130152530742", below))
    assert simulate_scene(scene).rest_time > 0
