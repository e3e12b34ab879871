"""`python -m billiards.simulate`: the summary and the JSON contract."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path

import pytest

from billiards.record.trajectory import Trajectory
from billiards.record.window import SHUTTER_STEPS
from tests.commands import run_module


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return run_module("billiards.simulate", *args)


def test_json_output_lists_balls_events_rest_time_and_samples() -> None:
    run = _run("--json", "--times", "0,0.5,2")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["balls"][0] == "cue" and len(data["balls"]) == 16
    first = data["events"][0]
    assert first["kind"] == "ball" and first["balls"] == ["cue", "1"]
    gap = 1.5975 - 0.5325 - 2 * 0.0286  # cue to apex, rolling at 3 m/s, slowing at mu g
    assert first["t"] == pytest.approx(
        2 * gap / (3.0 + math.sqrt(9.0 - 2 * 0.0981 * gap)), rel=1e-12
    )
    assert all(event["kind"] in ("ball", "cushion") for event in data["events"])
    assert data["rest_time"] > first["t"]
    assert len(data["final_positions"]) == 16
    assert [sample["t"] for sample in data["samples"]] == [0, 0.5, 2]
    assert data["samples"][0]["positions"][0] == [0.5325, 0.5325]


@pytest.mark.long
def test_method_and_step_options_agree_for_exact_methods() -> None:
    event = json.loads(_run("--json", "--method", "event").stdout)
    exact = json.loads(_run("--json", "--method", "exact", "--dt", "0.03").stdout)
    assert exact["final_positions"] == event["final_positions"]
    assert exact["events"] == event["events"]


@pytest.mark.long
def test_summary_names_the_contacts_and_the_rest_time() -> None:
    run = _run()
    assert run.returncode == 0
    assert "ball-ball and" in run.stdout and "the last ball stops at" in run.stdout
    assert run.stdout.count("\n") >= 18


@pytest.mark.long
@pytest.mark.parametrize("args", [["--dt", "0"], ["--times", "a,b"], ["--method", "rk4"]])
def test_bad_option_is_one_line_and_exit_2(args: list[str]) -> None:
    run = _run(*args)
    assert run.returncode == 2
    assert run.stderr.startswith("error: ") and run.stderr.strip().count("\n") == 0


def test_saved_trajectory_is_the_films_from_lead_to_tail(tmp_path: Path) -> None:
    path = tmp_path / "break.npz"
    run = _run("--json", "--trajectory", str(path))
    assert run.returncode == 0, run.stderr
    rest_time = json.loads(run.stdout)["rest_time"]
    trajectory = Trajectory.load(path)
    assert trajectory.times[0] == -0.5  # [render] lead
    assert rest_time + 1.0 - 1 / 30 < trajectory.times[-1] <= rest_time + 1.0  # [render] tail
    # The film's 30 frames/s, SHUTTER_STEPS states a frame for the open shutter's blur.
    assert trajectory.fps == pytest.approx(30.0 * SHUTTER_STEPS)
    assert trajectory.positions.shape == (len(trajectory.times), 16, 3)
    assert [p.name for p in tmp_path.iterdir()] == ["break.npz"]  # no temporary left


def test_the_sample_times_are_bounded_before_any_run() -> None:
    import argparse

    from billiards.record.result_json import MAX_TIMES
    from billiards.simulate import _parse_times

    assert len(_parse_times(",".join(["0.5"] * MAX_TIMES))) == MAX_TIMES
    with pytest.raises(argparse.ArgumentTypeError, match="100,001 times: expected at most 100,000"):
        _parse_times(",".join(["0.5"] * (MAX_TIMES + 1)))
