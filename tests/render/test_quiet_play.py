"""Facts about the film's pace: no film holds longer than 1.5 s on balls that barely move
(slower than 0.25 m/s), and every film ends a tail after the last ball's centre stops,
not after a ball left spinning in place stops spinning (masse_shot ended on 5.8 s of
that; the seed break held its last slowly rolling balls 2.5 s). No GL."""

from __future__ import annotations

import functools
import re
from pathlib import Path

import numpy as np
import pytest

from billiards.record.trajectory import Trajectory, first_contact_time
from billiards.record.window import film_trajectory, motion_end
from billiards.render.film_clock import FilmClock
from billiards.render.quiet_play import quickened
from billiards.scene.reader import load_scene, shipped_scene_names
from billiards.simulation import SimulationResult, simulate_scene

LONGEST_HOLD = 1.5  # s of film
CRAWL = 0.25  # m/s
# Never hurried: the first contact's next 0.6 s, the last 0.8 s before a drop and the
# 0.6 s after it (the director's cut to the pocket and its hold).
OPENING, BEFORE_DROP, AFTER_DROP = 0.6, 0.8, 0.6
FPS = 30.0
SCENES = [None, *shipped_scene_names()]


@functools.cache
def filmed(name: str | None) -> tuple[SimulationResult, Trajectory, FilmClock]:
    scene = load_scene(name)
    result = simulate_scene(scene)
    trajectory = film_trajectory(result, scene.render)
    return result, trajectory, FilmClock.of(trajectory, FPS, scene.render.slow_motion)


def centre_stops(result: SimulationResult) -> float:
    """When the last ball's centre stops, to a millisecond, from the run itself."""
    times = np.arange(0.0, result.rest_time + 1e-3, 1e-3)
    positions = result.positions_at(times)
    moving = np.any(np.abs(np.diff(positions, axis=0)) > 1e-9, axis=(1, 2))
    return float(times[np.flatnonzero(moving)[-1] + 1]) if moving.any() else 0.0


@pytest.mark.parametrize("name", SCENES)
def test_no_film_holds_long_on_balls_that_barely_move(name: str | None) -> None:
    result, _, clock = filmed(name)
    times = clock.sim_times
    positions = result.positions_at(np.clip(times, 0.0, None))  # (frames, N, 2)
    speeds = np.linalg.norm(np.diff(positions, axis=0), axis=2) / np.diff(times)[:, None]
    # Balls gone into a pocket do not count (they are still in the run's positions).
    gone = np.zeros_like(speeds, dtype=bool)
    for event in result.events:
        if event.kind == "pocket":
            gone[:, result.ball_ids.index(event.balls[0])] = times[1:] > event.time
    quiet = np.where(gone, 0.0, speeds).max(axis=1) < CRAWL
    first = first_contact_time(result.events)
    fences = [(-np.inf, (first if first is not None else times[0]) + OPENING)]
    fences.append((centre_stops(result), np.inf))
    fences += [
        (event.time - BEFORE_DROP, event.time + AFTER_DROP)
        for event in result.events
        if event.kind == "pocket"
    ]
    for low, high in fences:
        quiet &= (times[1:] <= low) | (times[:-1] >= high)
    longest, run = 0, 0
    for frame_is_quiet in quiet:
        run = run + 1 if frame_is_quiet else 0
        longest = max(longest, run)
    assert longest / FPS <= LONGEST_HOLD + 1.5 / FPS, (name, longest / FPS)


@pytest.mark.parametrize("name", SCENES)
def test_the_film_ends_a_tail_after_the_last_ball_stops_moving(name: str | None) -> None:
    result, trajectory, _ = filmed(name)
    tail = load_scene(name).render.tail
    stops = centre_stops(result)
    assert motion_end(result) == pytest.approx(stops, abs=2e-3)
    assert float(trajectory.times[-1]) == pytest.approx(stops + tail, abs=0.01)


def test_the_masse_film_does_not_wait_for_its_ball_spinning_in_place() -> None:
    result, _, clock = filmed("masse_shot")
    assert result.rest_time - motion_end(result) > 4.0  # 4.4 s of spinning in place
    assert clock.duration < 6.0  # was 10.3 s


def test_a_quickened_stretch_plays_in_the_longest_hold_and_its_clock_inverts() -> None:
    stretch = (3.0, 7.0)
    window = quickened(stretch)
    clock = FilmClock.over(-0.5, 9.0, FPS, quick=(window,))
    start, end = clock.film_time(np.array(stretch))
    assert end - start == pytest.approx(LONGEST_HOLD, abs=1e-9)
    assert np.all(np.diff(clock.sim_times) > 0)
    assert np.allclose(
        clock.film_time(clock.sim_times),
        clock.start + np.arange(len(clock.sim_times)) / FPS,
        atol=1e-9,
    )
    # Outside the stretch the film runs at one second a second.
    assert clock.film_time(np.array([2.0]))[0] == pytest.approx(2.0)
    assert clock.film_time(np.array([8.0]))[0] == pytest.approx(8.0 - (4.0 - LONGEST_HOLD))


def test_a_still_of_the_library_is_asked_within_the_same_film_as_the_commands(
    tmp_path: Path,
) -> None:
    """render_still refuses a time past the film's end as `render --frame` does: after
    masse_shot's ball stops moving and the tail, not after it stops spinning."""
    import billiards

    result = billiards.run("masse_shot")
    with pytest.raises(billiards.SceneError, match=re.escape("within the film, -0.5 to 5.39")):
        billiards.render_still(result, 7.0, tmp_path / "never.png")
