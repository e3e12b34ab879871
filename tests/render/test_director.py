"""The director's rules, over every shipped scene: what is in frame when, and how long
a view is held (billiards.render.director)."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from billiards.record.trajectory import Trajectory, ball_state, first_contact_time
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.director import FOLLOW, curved_path, directed_shots
from billiards.render.film import camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.scene.reader import load_scene, shipped_scene_names
from billiards.scene.render_table import CameraShot, RenderSettings
from billiards.simulation import simulate_scene
from billiards.stage.cameras import CameraPose, CameraTimeline, Stage, preset_pose

SIZE = (1280, 720)
SCENES = shipped_scene_names()


@cache
def filmed(name: str) -> tuple[Trajectory, CameraTimeline]:
    scene = load_scene(name)
    settings = RenderSettings(fps=30.0, shutter=0.0)  # the scene's own cameras left out
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    return trajectory, camera_timeline(trajectory, settings)


def in_frame(pose: CameraPose, points: np.ndarray, margin: float = 0.0) -> bool:
    width, height = SIZE
    x, y = pose.project(np.atleast_2d(points), width, height).T
    ahead = (np.atleast_2d(points) - np.array(pose.eye)) @ pose.basis()[2] > 0
    return bool(
        np.all(ahead)
        and np.all((x >= margin) & (x <= width - margin))
        and np.all((y >= margin) & (y <= height - margin))
    )


@pytest.mark.parametrize("name", SCENES)
def test_the_strike_is_seen_from_behind_the_cue_ball(name: str) -> None:
    trajectory, timeline = filmed(name)
    expected = preset_pose("behind_cue", Stage.of(trajectory), SIZE[0] / SIZE[1])
    assert timeline.pose(0.0) == expected


@pytest.mark.parametrize("name", SCENES)
def test_the_first_contact_is_in_frame(name: str) -> None:
    trajectory, timeline = filmed(name)
    first = first_contact_time(trajectory.events)
    if first is None:
        pytest.skip("no ball meets another")
    contact = next(event for event in trajectory.events if event.kind == "ball")
    balls = [trajectory.ball_ids.index(ball) for ball in contact.balls]
    assert in_frame(timeline.pose(first), ball_state(trajectory, first)[0][balls])


@pytest.mark.parametrize("name", SCENES)
def test_each_drop_is_seen_at_its_pocket(name: str) -> None:
    trajectory, timeline = filmed(name)
    for event in trajectory.events:
        if event.kind == "pocket":
            ball = trajectory.ball_ids.index(event.balls[0])
            where = ball_state(trajectory, event.time)[0][ball]
            assert in_frame(timeline.pose(event.time), where), (event.time, event.pocket)


@pytest.mark.parametrize("name", SCENES)
def test_no_view_is_held_still_for_long_while_balls_move(name: str) -> None:
    trajectory, timeline = filmed(name)
    clock = FilmClock.of(trajectory, 30.0)
    times = clock.sim_times
    poses = [timeline.pose(float(t)) for t in times]
    positions = np.stack([ball_state(trajectory, float(t))[0] for t in times])
    moving = np.any(np.linalg.norm(np.diff(positions, axis=0), axis=2) > 1e-4, axis=1)
    held = 0.0
    for index in range(1, len(times)):
        same = poses[index] == poses[index - 1]
        held = held + (times[index] - times[index - 1]) if same and moving[index - 1] else 0.0
        assert held <= FOLLOW + 0.5, (float(times[index]), held)


@pytest.mark.parametrize("name", SCENES)
def test_the_film_ends_in_the_wide_view_at_rest(name: str) -> None:
    trajectory, timeline = filmed(name)
    end = float(trajectory.times[-1])
    wide = preset_pose("corner", Stage.of(trajectory), SIZE[0] / SIZE[1])
    if any(shot.preset == "corner" for shot in directed_shots(trajectory)):
        assert timeline.pose(end) == wide
    else:  # too short a film for the ease out: it ends on the last view
        assert end < trajectory.rest_time + 2.5


def test_a_masse_is_framed_whole_from_the_strike_to_its_contact() -> None:
    trajectory, timeline = filmed("masse_shot")
    first = first_contact_time(trajectory.events)
    assert first is not None
    path = curved_path(trajectory, first)
    assert path is not None  # it curves
    for time in np.linspace(0.3, first, 5):
        assert in_frame(timeline.pose(float(time)), path)


def test_a_straight_shot_is_not_taken_for_a_curve() -> None:
    trajectory, _ = filmed("pool_break")
    first = first_contact_time(trajectory.events)
    assert first is not None and curved_path(trajectory, first) is None


def test_the_scenes_cameras_override_the_director() -> None:
    trajectory, _ = filmed("pool_break")
    settings = RenderSettings(cameras=(CameraShot(preset="overhead"),))
    timeline = camera_timeline(trajectory, settings)
    overhead = preset_pose("overhead", Stage.of(trajectory), SIZE[0] / SIZE[1])
    assert all(timeline.pose(t) == overhead for t in (0.0, 1.0, trajectory.rest_time))
    assert math.isfinite(trajectory.rest_time)
