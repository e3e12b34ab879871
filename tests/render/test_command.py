"""`python -m billiards.render`: films, stills, and one-line failures with no half files."""

from __future__ import annotations

import ctypes.util
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.commands import run_module
from tests.render.fixtures import decode_mp4, needs_gl, rolling_trajectory, streams


def run(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return run_module("billiards.render", *args, env=env)


@pytest.mark.gl
@needs_gl
def test_the_seed_break_becomes_a_film_of_the_right_size_and_length(tmp_path: Path) -> None:
    target = tmp_path / "break.mp4"
    done = run("-o", str(target), "--width", "160", "--height", "90", "--fps", "10", "--quiet")
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    meta, frames = decode_mp4(target)
    assert meta["size"] == (160, 90)
    assert meta["fps"] == pytest.approx(10.0)
    # From half a second before the cue ball moves to a second after the last ball
    # stops, its last 2.5 s of slow rolling quickened to 1.5 s (render.quiet_play).
    from billiards.record.window import film_trajectory
    from billiards.render.film_clock import FilmClock
    from billiards.render.quiet_play import LONGEST_HOLD
    from billiards.scene.reader import load_scene
    from billiards.simulation import simulate_scene

    scene = load_scene(None)
    trajectory = film_trajectory(simulate_scene(scene), scene.render)
    clock = FilmClock.of(trajectory, 10.0)
    [(start, end)] = [(w.start - w.ease, w.end + w.ease) for w in clock.quick]
    length = float(trajectory.times[-1] - trajectory.times[0]) - (end - start) + LONGEST_HOLD
    expected = int(np.floor(length * 10 + 1e-9)) + 1
    assert len(frames) == expected == clock.frame_count
    assert meta["duration"] == pytest.approx(expected / 10.0, abs=0.15)
    # The opening shot is the wide view of the table: green cloth in the middle.
    r, g, b = (int(v) for v in frames[0][50, 80])
    assert g > r + 25 and g > b + 25
    assert list(tmp_path.iterdir()) == [target]


@pytest.mark.long
@pytest.mark.gl
@needs_gl
def test_a_still_at_a_given_time_is_an_image(tmp_path: Path) -> None:
    target = tmp_path / "still.png"
    done = run(
        "--frame",
        "2.5",
        "-o",
        str(target),
        "--width",
        "160",
        "--height",
        "90",
        "--camera",
        "overhead",
    )
    assert done.returncode == 0, done.stderr
    with Image.open(target) as image:
        assert image.size == (160, 90)


@pytest.mark.gl
@needs_gl
def test_a_saved_trajectory_renders_without_the_simulator(tmp_path: Path) -> None:
    saved = tmp_path / "roll.npz"
    rolling_trajectory().save(saved)
    target = tmp_path / "roll.mp4"
    done = run(
        "--trajectory", str(saved), "-o", str(target), "--width", "96", "--height", "64", "--quiet"
    )
    assert done.returncode == 0, done.stderr
    _, frames = decode_mp4(target)
    assert len(frames) == len(rolling_trajectory().times)


def test_a_bad_scene_is_one_line_exit_2_and_no_file(tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text("[rack]\n[render]\nwidth = 0\n")  # valid but for the width
    target = tmp_path / "out.mp4"
    done = run(str(scene), "-o", str(target))
    assert done.returncode == 2
    assert done.stderr.startswith("error: ") and done.stderr.count("\n") == 1
    assert "render.width = 0" in done.stderr
    assert not target.exists()
    missing = run(str(tmp_path / "nope.toml"), "-o", str(target))
    assert missing.returncode == 2 and "no such scene file" in missing.stderr


def test_an_odd_size_on_the_command_line_is_refused(tmp_path: Path) -> None:
    done = run("--width", "161", "-o", str(tmp_path / "f.mp4"))
    assert done.returncode == 2 and done.stderr.startswith("error: --width 161")


@pytest.mark.long
def test_no_opengl_is_one_line_naming_the_packages(tmp_path: Path) -> None:
    target = tmp_path / "out.mp4"
    done = run("-o", str(target), env={"BILLIARDS_GL_BACKEND": "none"})
    assert done.returncode == 1
    assert done.stderr.startswith("error: no headless OpenGL") and done.stderr.count("\n") == 1
    assert "libegl1 libgl1-mesa-dri" in done.stderr
    assert "Traceback" not in done.stderr
    assert list(tmp_path.iterdir()) == []


HAS_OSMESA = ctypes.util.find_library("OSMesa") is not None


@pytest.mark.gl
@needs_gl
@pytest.mark.skipif(not HAS_OSMESA, reason="libosmesa6 is not installed: no fallback to try")
def test_where_egl_fails_osmesa_draws_the_same_still(tmp_path: Path) -> None:
    still = ("--frame", "0.5", "--width", "160", "--height", "90", "--quiet")
    egl = run(*still, "-o", str(tmp_path / "egl.png"))
    # An EGL vendor list that names no driver: libglvnd's EGL then finds no device.
    broken_egl = {"__EGL_VENDOR_LIBRARY_FILENAMES": str(tmp_path / "no-vendor.json")}
    osmesa = run(*still, "-o", str(tmp_path / "osmesa.png"), env=broken_egl)
    assert egl.returncode == 0 and osmesa.returncode == 0, osmesa.stderr
    # ... and EGL really was broken there, so the picture is OSMesa's.
    egl_only = run(
        *still, "-o", str(tmp_path / "x.png"), env={**broken_egl, "BILLIARDS_GL_BACKEND": "egl"}
    )
    assert egl_only.returncode == 1 and "EGL:" in egl_only.stderr
    assert (tmp_path / "egl.png").read_bytes() == (tmp_path / "osmesa.png").read_bytes()


SMALL_FILM = ("--width", "320", "--height", "180")


@pytest.mark.long
@pytest.mark.gl
@needs_gl
@pytest.mark.parametrize(
    ("signum", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143), (signal.SIGHUP, 129)]
)
def test_a_signal_mid_film_exits_cleanly_and_leaves_no_file_and_no_ffmpeg(
    tmp_path: Path, signum: int, status: int
) -> None:
    target = tmp_path / "break.mp4"
    process = subprocess.Popen(
        [sys.executable, "-m", "billiards.render", "-o", str(target), *SMALL_FILM],
        stderr=subprocess.PIPE,
        text=True,
    )
    assert process.stderr is not None
    # tqdm redraws its bar after a carriage return (a line break in text mode): its
    # second drawing comes after the first frames, so then frames are flowing.
    drawings: list[str] = []
    for line in iter(process.stderr.readline, ""):
        if line.strip():
            drawings.append(line)
        if len(drawings) == 2:
            break
    encoders = _children_writing_into(tmp_path)
    assert encoders, "no ffmpeg was writing the film when the signal was sent"
    process.send_signal(signum)
    rest = process.stderr.read()
    process.stderr.close()
    assert process.wait(timeout=60) == status
    assert "no output written" in rest and "Traceback" not in rest
    assert not rest.startswith("\n")  # no blank line in a log
    assert list(tmp_path.iterdir()) == []
    assert not [pid for pid in encoders if Path(f"/proc/{pid}").exists()]


def _children_writing_into(folder: Path) -> list[int]:
    """Processes whose command line names a file in `folder` (the ffmpeg encoder)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            words = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if any(str(folder).encode() in word for word in words) and b"ffmpeg" in words[0]:
            found.append(int(entry.name))
    return found


@pytest.mark.long
@pytest.mark.gl
@needs_gl
def test_a_saved_trajectory_renders_with_its_scenes_render_settings(tmp_path: Path) -> None:
    scene = tmp_path / "small.toml"
    scene.write_text("[render]\nwidth = 160\nheight = 90\nfps = 10\nsound = false\n")
    saved = run_module("billiards.simulate", str(scene), "--trajectory", "t.npz", cwd=tmp_path)
    assert saved.returncode == 0 and "wrote t.npz" in saved.stderr
    done = run_module("billiards.render", "--trajectory", "t.npz", "-o", "f.mp4", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    meta, _ = decode_mp4(tmp_path / "f.mp4")
    assert meta["size"] == (160, 90) and meta["fps"] == pytest.approx(10.0)
    assert "Audio:" not in streams(tmp_path / "f.mp4")  # the scene said sound = false


@pytest.mark.long
@pytest.mark.gl
@needs_gl
@pytest.mark.parametrize("output", [["--frame", "1", "-o", "x.png"], ["-o", "x.mp4"]])
def test_a_frame_larger_than_the_gl_allows_names_the_limit(
    tmp_path: Path, output: list[str]
) -> None:
    done = run_module(
        "billiards.render", *output, "--width", "100000", "--height", "100000", "--quiet",
        cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 2  # bad input, like every size out of range
    assert "100000x100000: this GL draws at most" in done.stderr and "px a side" in done.stderr
    assert done.stderr.count("\n") == 1 and list(tmp_path.iterdir()) == []
