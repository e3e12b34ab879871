"""Every command answers a bad option with one line and exit status 2."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.commands import run_module


@pytest.mark.parametrize(
    ("command", "args", "message"),
    [
        ("billiards.simulate", ["--method", "rk4"], "argument --method: invalid choice: 'rk4'"),
        ("billiards.render", ["--antialias", "3"], "argument --antialias: invalid choice: 3"),
        ("billiards.render", ["--fps", "fast"], "argument --fps: invalid float value: 'fast'"),
        ("billiards.plot", ["--width", "x"], "argument --width: invalid int value: 'x'"),
    ],
)
def test_bad_option_is_one_line_and_exit_2(
    command: str, args: list[str], message: str, tmp_path: Path
) -> None:
    run = run_module(command, *args, cwd=tmp_path)
    assert run.returncode == 2
    assert run.stderr.startswith("error: ") and message in run.stderr
    assert run.stderr.strip().count("\n") == 0
    assert list(tmp_path.iterdir()) == []  # nothing written


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-o", "film.avi"], "film.avi: the film is an MP4 file (name it .mp4)"),
        (["--frame", "1", "-o", "still.mp4"], "still.mp4: a still needs an image file name"),
    ],
)
def test_a_wrong_output_name_is_refused_before_any_work(
    args: list[str], message: str, tmp_path: Path
) -> None:
    run = run_module("billiards.render", *args, cwd=tmp_path)
    assert run.returncode == 2 and message in run.stderr
    assert list(tmp_path.iterdir()) == []
