"""The film's sound track and slow motion: sync, length, determinism, CLI switches."""

from __future__ import annotations

import dataclasses
import subprocess
import wave
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.trajectory import Event, Trajectory
from billiards.render.film_clock import FilmClock
from billiards.render.slow_motion import SLOW_AFTER, SLOW_BEFORE, SLOW_EASE, SlowMotion
from billiards.render.sound.soundtrack import film_sound
from billiards.render.sound.voices import SAMPLE_RATE
from billiards.scene.render_table import RenderSettings
from tests.commands import run_module
from tests.render.fixtures import decode_audio, decode_mp4, needs_gl, rolling_trajectory, streams

FPS = 30.0
FRAME = 1 / FPS  # s
TINY = ("--width", "64", "--height", "36", "--fps", "30", "--antialias", "0", "--quiet")
# Separated contacts (simulation s): clicks of several loudnesses with thumps between.
CLICKS = (0.25, 0.95, 1.45)
EVENTS = (
    Event(0.25, "ball", ("cue", "1"), 2.0),
    Event(0.6, "cushion", ("1",), 1.5),
    Event(0.95, "ball", ("1", "2"), 0.6),
    Event(1.2, "cushion", ("2",), 2.5),
    Event(1.45, "ball", ("cue", "3"), 1.2),
)


def contacts() -> Trajectory:
    """1.5 s of the rolling fixture (-0.5 .. 1.9 s) with the separated contacts above."""
    return dataclasses.replace(rolling_trajectory(end=1.9), events=EVENTS)


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return run_module("billiards.render", *args)


def loudest_time(track: npt.NDArray[np.float32], around: float, start: float) -> float:
    """Film time of the loudest sample within 0.1 s of `around` (track starts at `start`)."""
    first = max(round((around - 0.1 - start) * SAMPLE_RATE), 0)
    last = round((around + 0.1 - start) * SAMPLE_RATE)
    return start + (first + int(np.argmax(np.abs(track[first:last])))) / SAMPLE_RATE


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("trajectory") / "contacts.npz"
    contacts().save(path)
    return path


# --- the clock: slow motion both ways ---------------------------------------------------


def test_slow_motion_maps_both_ways_monotone_and_continuous() -> None:
    slow = SlowMotion(0.25, start=0.2, end=0.7)
    times = np.linspace(-1.0, 3.0, 40_001)
    film = slow.film_time(times)
    assert np.all(np.diff(film) > 0)
    np.testing.assert_allclose(slow.sim_time(film), times, atol=1e-12)
    # Real time before the window, 1/4 speed inside it, real time again after it.
    step = np.diff(film) / np.diff(times)
    assert step[times[:-1] < 0.2 - SLOW_EASE] == pytest.approx(1.0)
    assert step[(times[:-1] > 0.2) & (times[:-1] < 0.7 - 1e-4)] == pytest.approx(4.0)
    assert np.max(np.abs(np.diff(step))) < 0.01  # eased: no jump (a cut would be 3)
    assert film[-1] - times[-1] == pytest.approx(slow.extra)
    assert slow.extra == pytest.approx(3.0 * (0.5 + SLOW_EASE))


def test_slowed_film_is_longer_by_the_window_and_keeps_its_ends() -> None:
    trajectory = contacts()
    plain = FilmClock.of(trajectory, FPS)
    slowed = FilmClock.of(trajectory, FPS, slow_motion=0.25)
    assert plain.slow_motion is None and slowed.slow_motion is not None
    window = SlowMotion(0.25, 0.25 - SLOW_BEFORE, 0.25 + SLOW_AFTER)
    assert slowed.slow_motion == window
    assert slowed.duration - plain.duration == pytest.approx(window.extra, abs=FRAME)
    # Still from the lead before the cue moves to the tail after the rest.
    assert slowed.sim_times[0] == trajectory.times[0]
    assert slowed.sim_times[-1] == pytest.approx(trajectory.times[-1], abs=FRAME)
    assert np.all(np.diff(slowed.sim_times) > 0)
    np.testing.assert_allclose(
        slowed.film_time(slowed.sim_times),
        slowed.start + np.arange(slowed.frame_count) / FPS,
        rtol=0,
        atol=1e-12,
    )


def test_a_speed_of_one_or_a_break_with_no_contact_is_not_slowed() -> None:
    assert SlowMotion.around_first_contact(EVENTS, 1.0) is None
    assert SlowMotion.around_first_contact((), 0.5) is None
    cushion_only = SlowMotion.around_first_contact(EVENTS[1:2], 0.5)
    assert cushion_only is not None and cushion_only.start == pytest.approx(0.6 - SLOW_BEFORE)


# --- the track on the film clock (no GL) ------------------------------------------------


def test_the_track_is_as_long_as_the_film_and_clicks_sit_on_the_contacts() -> None:
    clock = FilmClock.of(contacts(), FPS)
    track = film_sound(EVENTS, clock, RenderSettings())
    assert len(track) == round(clock.duration * SAMPLE_RATE)
    for time in CLICKS:
        assert abs(loudest_time(track, time, clock.start) - time) < 0.002


def test_the_same_scene_gives_the_same_samples_and_the_seed_changes_them() -> None:
    clock = FilmClock.of(contacts(), FPS)
    first = film_sound(EVENTS, clock, RenderSettings())
    assert np.array_equal(first, film_sound(EVENTS, clock, RenderSettings()))
    assert not np.array_equal(first, film_sound(EVENTS, clock, RenderSettings(sound_seed=1)))


@pytest.mark.parametrize("sound", ["match", "natural"])
def test_in_slow_motion_a_click_lands_at_its_slowed_film_time(sound: str) -> None:
    settings = RenderSettings(slow_motion=0.25, slow_motion_sound=sound)
    clock = FilmClock.of(contacts(), FPS, settings.slow_motion)
    track = film_sound(EVENTS, clock, settings)
    assert len(track) == round(clock.duration * SAMPLE_RATE)
    for time in CLICKS:
        slowed = float(clock.film_time(np.array([time]))[0])
        assert abs(loudest_time(track, slowed, clock.start) - slowed) < 0.005


def test_matched_slow_motion_sound_is_longer_and_lower_than_natural() -> None:
    def click(sound: str) -> npt.NDArray[np.float32]:
        settings = RenderSettings(slow_motion=0.25, slow_motion_sound=sound)
        clock = FilmClock.of(contacts(), FPS, settings.slow_motion)
        track = film_sound(EVENTS[:1], clock, settings)
        at = round((float(clock.film_time(np.array([0.25]))[0]) - clock.start) * SAMPLE_RATE)
        return track[at - 100 : at + 4800]

    def centroid(samples: npt.NDArray[np.float32]) -> float:
        power = np.abs(np.fft.rfft(samples.astype(np.float64))) ** 2
        return float((power * np.fft.rfftfreq(len(samples), 1 / SAMPLE_RATE)).sum() / power.sum())

    assert centroid(click("match")) < 0.5 * centroid(click("natural"))


# --- the command line -------------------------------------------------------------------


def test_a_scene_with_a_trajectory_gives_the_film_its_render_settings_and_says_so(
    tmp_path: Path, saved: Path
) -> None:
    scene = tmp_path / "slow.toml"
    scene.write_text("[render]\nslow_motion = 0.25\n[[ball]]\nid = 'x'\nposition = [1, 0.5]\n")
    plain, slowed = tmp_path / "plain.wav", tmp_path / "slowed.wav"
    assert run("--trajectory", str(saved), "--sound-only", str(plain), "--quiet").returncode == 0
    done = run(str(scene), "--trajectory", str(saved), "--sound-only", str(slowed), "--quiet")
    assert done.returncode == 0, done.stderr
    assert done.stderr == (
        f"note: {scene}: only its [render] and [[camera]] tables are used; the table and "
        f"the balls' motion are {saved}'s\n"
    )
    with wave.open(str(plain), "rb") as a, wave.open(str(slowed), "rb") as b:
        extra = (b.getnframes() - a.getnframes()) / SAMPLE_RATE
    # The scene's slow motion, on the trajectory's contacts (its one ball is not used).
    assert extra == pytest.approx(3.0 * (SLOW_BEFORE + SLOW_AFTER + SLOW_EASE), abs=FRAME)


def test_sound_only_writes_a_wav_of_the_films_length(tmp_path: Path, saved: Path) -> None:
    target = tmp_path / "break.wav"
    done = run("--trajectory", str(saved), "--sound-only", str(target), "--quiet")
    assert done.returncode == 0, done.stderr
    with wave.open(str(target), "rb") as wav:
        assert wav.getframerate() == SAMPLE_RATE and wav.getnchannels() == 1
        frames = wav.getnframes()
    assert frames == round(FilmClock.of(contacts(), FPS).duration * SAMPLE_RATE)
    slowed = tmp_path / "slow.wav"
    done = run("--trajectory", str(saved), "--sound-only", str(slowed), "--slow-motion", "0.25")
    assert done.returncode == 0 and done.stderr.startswith(f"wrote {slowed}")
    with wave.open(str(slowed), "rb") as wav:
        extra = (wav.getnframes() - frames) / SAMPLE_RATE
    assert extra == pytest.approx(3.0 * (SLOW_BEFORE + SLOW_AFTER + SLOW_EASE), abs=FRAME)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["break.wav", "slow.wav"]


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("slow_motion = 0", "render.slow_motion = 0: expected a playback speed in (0, 1]"),
        ("slow_motion = 2", "render.slow_motion = 2: expected a playback speed in (0, 1]"),
        ('slow_motion = "x"', "render.slow_motion = 'x': expected a playback speed"),
        (
            'slow_motion_sound = "fast"',
            "render.slow_motion_sound = 'fast': expected one of \"match\"",
        ),
        ('sound = "yes"', "render.sound = 'yes': expected true or false"),
        ("sound_seed = -1", "render.sound_seed = -1: expected a whole number >= 0"),
    ],
)
def test_a_bad_sound_or_slow_motion_key_is_one_line_exit_2(
    tmp_path: Path, line: str, message: str
) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text(f"[rack]\n[render]\n{line}\n")  # a valid scene but for {line}
    done = run(str(scene), "--sound-only", str(tmp_path / "out.wav"))
    assert done.returncode == 2
    assert done.stderr.startswith("error: ") and done.stderr.count("\n") == 1
    assert message in done.stderr
    assert list(tmp_path.iterdir()) == [scene]


@pytest.mark.parametrize("value", ["0", "1.5", "nan", "-0.25"])
def test_a_bad_slow_motion_option_is_one_line_exit_2(tmp_path: Path, value: str) -> None:
    done = run(f"--slow-motion={value}", "--sound-only", str(tmp_path / "out.wav"))
    assert done.returncode == 2
    assert done.stderr.startswith(f"error: --slow-motion {value}")
    assert done.stderr.count("\n") == 1 and list(tmp_path.iterdir()) == []


def test_sound_only_needs_a_wav_name(tmp_path: Path) -> None:
    done = run("--sound-only", str(tmp_path / "out.mp3"))
    assert done.returncode == 2 and "writes a .wav file" in done.stderr
    assert list(tmp_path.iterdir()) == []


# --- the film (GL) ----------------------------------------------------------------------


@pytest.mark.long
@pytest.mark.gl
@needs_gl
def test_the_film_has_an_aac_track_as_long_as_the_video_in_sync_and_repeatable(
    tmp_path: Path, saved: Path
) -> None:
    films = [tmp_path / "one.mp4", tmp_path / "two.mp4"]
    for film in films:
        done = run("--trajectory", str(saved), "-o", str(film), *TINY)
        assert done.returncode == 0, done.stderr
    assert "Audio: aac" in streams(films[0]) and "mono" in streams(films[0])
    meta, frames = decode_mp4(films[0])
    video = len(frames) / meta["fps"]
    audio = decode_audio(films[0])
    assert abs(len(audio) / SAMPLE_RATE - video) < FRAME
    start = float(contacts().times[0])  # film time of frame 0 (no slow motion)
    errors = [loudest_time(audio, time, start) - time for time in CLICKS]
    assert max(abs(e) for e in errors) < FRAME
    assert max(abs(e) for e in errors) < 0.003  # in fact within a few milliseconds
    # The same scene twice: the same synthesized track, and the same encoded one.
    assert np.array_equal(audio, decode_audio(films[1]))


@pytest.mark.gl
@needs_gl
def test_no_sound_gives_a_film_without_an_audio_stream(tmp_path: Path, saved: Path) -> None:
    film = tmp_path / "silent.mp4"
    done = run("--trajectory", str(saved), "-o", str(film), "--no-sound", *TINY)
    assert done.returncode == 0, done.stderr
    info = streams(film)
    assert "Video: h264" in info and "Audio" not in info
    assert list(tmp_path.iterdir()) == [film]


@pytest.mark.long
@pytest.mark.gl
@needs_gl
def test_a_slow_motion_film_is_longer_and_its_clicks_land_at_the_slowed_times(
    tmp_path: Path, saved: Path
) -> None:
    film = tmp_path / "slow.mp4"
    done = run("--trajectory", str(saved), "-o", str(film), "--slow-motion", "0.25", *TINY)
    assert done.returncode == 0, done.stderr
    clock = FilmClock.of(contacts(), FPS, 0.25)
    assert clock.slow_motion is not None
    _, frames = decode_mp4(film)
    assert len(frames) == clock.frame_count
    plain = FilmClock.of(contacts(), FPS)
    assert len(frames) / FPS - plain.duration == pytest.approx(clock.slow_motion.extra, abs=FRAME)
    audio = decode_audio(film)
    assert abs(len(audio) / SAMPLE_RATE - len(frames) / FPS) < FRAME
    for time in CLICKS:
        slowed = float(clock.film_time(np.array([time]))[0])
        assert abs(loudest_time(audio, slowed, clock.start) - slowed) < FRAME
