"""Every command answers a bad option with one line and exit status 2."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.commands import run_module, signalled_midway


@pytest.mark.long
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


COMMANDS_AND_OUTPUTS = [
    ("billiards.render", ["-o"], "film.mp4"),
    ("billiards.render", ["--frame", "1", "-o"], "still.png"),
    ("billiards.render", ["--sound-only"], "break.wav"),
    ("billiards.simulate", ["--trajectory"], "break.npz"),
    ("billiards.plot", ["-o"], "top.png"),
]


@pytest.mark.long
@pytest.mark.parametrize(("command", "option", "name"), COMMANDS_AND_OUTPUTS)
def test_an_output_path_is_checked_whole_before_any_work(
    command: str, option: list[str], name: str, tmp_path: Path
) -> None:
    (tmp_path / name).mkdir()  # a folder in its place
    folder = run_module(command, *option, name, cwd=tmp_path)
    assert folder.returncode == 2
    assert folder.stderr == f"error: {name}: is a folder; name a file to write\n"
    missing = run_module(command, *option, f"nowhere/{name}", cwd=tmp_path)
    assert missing.returncode == 2
    assert missing.stderr == f"error: nowhere/{name}: the folder nowhere does not exist\n"
    (tmp_path / name).rmdir()
    (tmp_path / name).write_bytes(b"mine")
    kept = run_module(command, *option, name, cwd=tmp_path)
    assert kept.returncode == 2 and "already exists (pass --force to replace it)" in kept.stderr
    assert (tmp_path / name).read_bytes() == b"mine"
    assert sorted(path.name for path in tmp_path.iterdir()) == [name]  # nothing else written


@pytest.mark.long
def test_force_replaces_an_existing_output(tmp_path: Path) -> None:
    (tmp_path / "top.png").write_bytes(b"mine")
    done = run_module("billiards.plot", "-o", "top.png", "--width", "200", "--force", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "top.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert done.stdout == "" and done.stderr.startswith("wrote top.png")


@pytest.mark.long
def test_plot_writes_a_jpeg_when_asked_for_one(tmp_path: Path) -> None:
    done = run_module("billiards.plot", "-o", "top.jpg", "--width", "200", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "top.jpg").read_bytes()[:3] == b"\xff\xd8\xff"


@pytest.mark.long
@pytest.mark.parametrize("command", ["billiards.render", "billiards.simulate", "billiards.plot"])
def test_every_command_has_version_and_names_the_shipped_scenes(command: str) -> None:
    from billiards import __version__

    version = run_module(command, "--version")
    assert version.returncode == 0 and version.stdout.strip().endswith(__version__)
    listed = run_module(command, "--list-scenes")
    assert listed.returncode == 0
    assert {"break", "hard_break", "bank_shot", "newtons_cradle"} <= set(listed.stdout.split())


def test_an_installed_command_names_itself_in_its_version() -> None:
    from billiards import __version__

    script = Path(sys.executable).parent / "billiards-render"
    done = subprocess.run([script, "--version"], capture_output=True, text=True, check=False)
    assert done.returncode == 0 and done.stdout == f"billiards-render {__version__}\n"


@pytest.mark.long
@pytest.mark.parametrize("times", ["-1,200", "1,,2", "x"])
def test_bad_sample_times_are_one_line(times: str) -> None:
    done = run_module("billiards.simulate", "--times", times)
    assert done.returncode == 2
    assert f"argument --times: {times}: expected comma-separated times" in done.stderr
    assert done.stderr.count("\n") == 1


@pytest.mark.long
def test_a_run_stopped_by_max_time_says_so(tmp_path: Path) -> None:
    scene = tmp_path / "short.toml"
    scene.write_text("[simulation]\nmax_time = 0.5\n")
    done = run_module("billiards.simulate", str(scene), "--json")
    assert done.returncode == 0
    import json

    data = json.loads(done.stdout)
    assert data["complete"] is False and data["stopped_by"] == "max_time"
    assert "warning:" in done.stderr and "stopped by max_time at 0.5 s" in done.stderr
    table = run_module("billiards.simulate", str(scene))
    assert "STOPPED by max_time at 0.5000 s" in table.stdout


SCENE_COMMANDS = {
    "billiards.simulate": [],
    "billiards.plot": [],
    "billiards.render": [],
    "billiards.sweep": ["-o", "sweep", "--workers", "0"],
}


@pytest.mark.long
@pytest.mark.parametrize(
    ("text", "line"),
    [
        ("[render]\nfps = 500\n", "bad.toml: render.fps = 500: expected a number in [1, 240]"),
        (
            '[[camera]]\npreset = "drone"\n',
            "bad.toml: camera[0].preset = 'drone': expected one of \"overhead\", "
            '"behind_cue", "low_side", "orbit", "corner", "rack"',
        ),
    ],
)
def test_every_command_refuses_a_bad_render_table_with_the_same_line(
    text: str, line: str, tmp_path: Path
) -> None:
    (tmp_path / "bad.toml").write_text(text)
    for command, args in SCENE_COMMANDS.items():
        run = run_module(command, "bad.toml", *args, cwd=tmp_path)
        assert (run.returncode, run.stderr) == (2, f"error: {line}\n"), command
    assert sorted(path.name for path in tmp_path.iterdir()) == ["bad.toml"]


def _old_trajectory(folder: Path, render_tables: object) -> Path:
    """A trajectory as simulate saved it before the render settings were typed: the
    scene's [render] and [[camera]] tables as its file had them."""
    import json

    import numpy as np

    (folder / "small.toml").write_text("[render]\nfps = 5\n")
    saved = run_module("billiards.simulate", "small.toml", "--trajectory", "new.npz", cwd=folder)
    assert saved.returncode == 0, saved.stderr
    with np.load(folder / "new.npz") as data:
        arrays = dict(data)
    arrays["scene"] = np.array(json.dumps({"source": "small.toml", "render": render_tables}))
    np.savez_compressed(folder / "old.npz", **arrays)
    return folder / "old.npz"


@pytest.mark.long
def test_render_refuses_an_older_trajectorys_bad_render_table_in_one_line(
    tmp_path: Path,
) -> None:
    _old_trajectory(tmp_path, {"render": {"fps": 500}})
    done = run_module("billiards.render", "--trajectory", "old.npz", "-o", "f.mp4", cwd=tmp_path)
    assert (done.returncode, done.stderr) == (
        2,
        "error: old.npz: small.toml: render.fps = 500: expected a number in [1, 240]\n",
    )


@pytest.mark.long
def test_an_older_trajectory_loads_with_its_render_tables_read(tmp_path: Path) -> None:
    from billiards.record.trajectory import Trajectory
    from billiards.scene.render_table import CameraShot

    tables = {"render": {"width": 320, "height": 180}, "camera": [{"preset": "overhead"}]}
    loaded = Trajectory.load(_old_trajectory(tmp_path, tables))
    assert loaded.scene_source == "small.toml" and loaded.render_settings is not None
    assert (loaded.render_settings.width, loaded.render_settings.height) == (320, 180)
    assert loaded.render_settings.cameras == (CameraShot(preset="overhead"),)


def test_render_says_a_file_is_not_a_trajectory(tmp_path: Path) -> None:
    (tmp_path / "notes.toml").write_text("[physics]\n")
    done = run_module("billiards.render", "--trajectory", "notes.toml", cwd=tmp_path)
    assert done.returncode == 2
    assert "notes.toml: not a trajectory file" in done.stderr
    assert "pickle" not in done.stderr


@pytest.mark.long
@pytest.mark.parametrize("frame", ["999", "-1"])
def test_a_frame_outside_the_film_is_one_line(frame: str, tmp_path: Path) -> None:
    done = run_module("billiards.render", "--frame", frame, "-o", "x.png", cwd=tmp_path)
    assert done.returncode == 2
    assert f"--frame {frame}: expected a time in s within the film, -0.5 to" in done.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.long
@pytest.mark.parametrize(
    ("command", "output"),
    [("billiards.simulate", ["--trajectory", "t.npz"]), ("billiards.plot", ["-o", "top.png"])],
)
@pytest.mark.parametrize(("signum", "status"), [(15, 143), (1, 129), (2, 130)])
def test_a_signal_mid_run_exits_cleanly_and_writes_nothing(
    command: str, output: list[str], signum: int, status: int, tmp_path: Path
) -> None:
    # A slow run (the stepped method at a tiny step) to be stopped halfway.
    (tmp_path / "slow.toml").write_text('[simulation]\nmethod = "naive"\ndt = 1e-5\n')
    returncode, errors = signalled_midway(command, ["slow.toml", *output], tmp_path, signum)
    assert returncode == status
    assert "stopped, no output written" in errors and "Traceback" not in errors
    assert sorted(path.name for path in tmp_path.iterdir()) == ["slow.toml"]
