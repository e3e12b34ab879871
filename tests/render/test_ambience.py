"""The sound bed under the contacts: the room's tone everywhere, and a rumble that
follows the rolling balls' speeds (billiards.render.sound.ambience)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from billiards.record.drop import GONE_DEPTH
from billiards.render.film_clock import FilmClock
from billiards.render.sound.ambience import ROOM_LEVEL, RUMBLE_LEVEL, rolling_drive, sound_bed
from billiards.render.sound.soundtrack import film_sound
from billiards.render.sound.voices import SAMPLE_RATE
from billiards.scene.render_table import RenderSettings
from tests.render.fixtures import rolling_trajectory


def rms(samples: np.ndarray) -> float:
    return float(np.sqrt(np.mean(samples.astype(np.float64) ** 2)))


def test_the_room_is_heard_while_nothing_moves_and_the_rolling_over_it() -> None:
    # The cue ball waits 0.5 s, then rolls at 1 m/s, slowing at 0.1 m/s^2.
    trajectory = rolling_trajectory(start=-0.5, end=1.0, speed=1.0)
    clock = FilmClock.of(trajectory, 30.0)
    bed = sound_bed(trajectory, clock, 0)
    waiting = bed[: int(0.45 * SAMPLE_RATE)]
    rolling = bed[int(0.6 * SAMPLE_RATE) : int(1.4 * SAMPLE_RATE)]
    assert rms(waiting) == pytest.approx(ROOM_LEVEL, rel=0.3)
    # One ball at about 0.95 m/s over the room's tone.
    expected = np.hypot(ROOM_LEVEL, RUMBLE_LEVEL * 0.95)
    assert rms(rolling) == pytest.approx(expected, rel=0.2)
    # Well under the contacts: a click at 3 m/s peaks at 0.4.
    assert np.abs(bed).max() < 0.1


def test_the_bed_repeats_bit_for_bit_and_changes_with_the_seed() -> None:
    trajectory = rolling_trajectory()
    clock = FilmClock.of(trajectory, 30.0)
    assert sound_bed(trajectory, clock, 0).tobytes() == sound_bed(trajectory, clock, 0).tobytes()
    assert sound_bed(trajectory, clock, 0).tobytes() != sound_bed(trajectory, clock, 1).tobytes()


def test_a_dropped_ball_rolls_no_more() -> None:
    trajectory = rolling_trajectory(speed=1.0)
    positions = trajectory.positions.copy()
    positions[:, 0, 2] = GONE_DEPTH
    gone = dataclasses.replace(trajectory, positions=positions)
    assert rolling_drive(trajectory).max() > 0.9
    assert rolling_drive(gone).max() < 1e-9  # (the resting rack: rounding of the times)


def test_the_film_track_has_the_bed_under_its_contacts() -> None:
    trajectory = rolling_trajectory()
    clock = FilmClock.of(trajectory, 30.0)
    settings = RenderSettings()
    bare = film_sound(trajectory.events, clock, settings)
    full = film_sound(trajectory.events, clock, settings, motion=trajectory)
    assert np.mean(bare == 0) > 0.9  # the contacts alone: mostly digital silence
    assert np.mean(full == 0) < 0.001
    np.testing.assert_allclose(full, bare + sound_bed(trajectory, clock, 0), atol=1e-6)
