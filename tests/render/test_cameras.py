"""Facts about the cameras' moves: an ease turns and travels as an operator would
(continuous velocity, no whip), for every pair of presets and every shipped scene's
own shots; a cut stays a cut. No GL."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from billiards.scene.reader import load_scene, shipped_scene_names
from billiards.scene.render_table import PRESETS, CameraShot
from billiards.stage.cameras import CameraPose, CameraTimeline, Stage, eased
from tests.render.fixtures import rolling_trajectory

FPS = 30.0
STAGE = Stage.of(rolling_trajectory())


def turn_between(first: CameraPose, second: CameraPose) -> float:
    """Degrees the view turns (roll included) from one pose to the other."""
    relative = first.orientation().T @ second.orientation()
    return math.degrees(math.acos(float(np.clip((np.trace(relative) - 1) / 2, -1.0, 1.0))))


def roll(pose: CameraPose) -> float:
    """Degrees the picture's horizon leans: the angle between the camera's right vector
    and the horizontal plane (0 for a camera on a level head, whichever way it looks;
    looking straight down every right vector is horizontal)."""
    right, _, _ = pose.basis()
    return math.degrees(math.asin(min(1.0, abs(float(right[2])))))


# Degrees of lean allowed: rounding. The quaternion slerp the eases used to take leaned
# the seed break's picture 11 degrees half way out of overhead, pocket_shot's 5.
LEVEL = 1e-6


def check_ease(timeline: CameraTimeline, start: float, length: float, name: str) -> None:
    times = start + np.arange(0, round(length * FPS) + 1) / FPS
    poses = [timeline.pose(float(t)) for t in times]
    leans = [roll(pose) for pose in poses]
    assert max(leans) <= LEVEL, (name, max(leans))
    turns = np.array([turn_between(a, b) for a, b in itertools.pairwise(poses)])
    median = float(np.median(turns))
    if median > 1e-6:
        assert turns.max() <= 2 * median, (name, turns.max(), median)
    # The eye's velocity is continuous: frame to frame, its step changes by a small
    # share of the largest step (no jolt at the start, the end or on the way).
    eyes = np.array([pose.eye for pose in poses])
    steps = np.diff(eyes, axis=0)
    largest = float(np.max(np.linalg.norm(steps, axis=1)))
    if largest > 1e-9:
        jolts = np.linalg.norm(np.diff(steps, axis=0), axis=1)
        assert jolts.max() <= 0.2 * largest, (name, jolts.max(), largest)
    # The turn picks up from the shot before and hands on to the one after at their
    # own pace (at rest, or an orbit's), as the eye does.
    before = turn_between(timeline.pose(float(times[0] - 1 / FPS)), poses[0])
    after = turn_between(poses[-1], timeline.pose(float(times[-1] + 1 / FPS)))
    allowed = 0.2 * turns.max() + 1e-9
    assert abs(turns[0] - before) <= allowed and abs(turns[-1] - after) <= allowed, name


@pytest.mark.parametrize("first", PRESETS)
def test_an_ease_between_presets_turns_smoothly_without_a_whip(first: str) -> None:
    for second in PRESETS:
        if second == first:
            continue
        shots = (
            CameraShot(preset=first),
            CameraShot(start=0.2, preset=second, transition="ease", ease=2.0),
        )
        check_ease(CameraTimeline(shots, STAGE, 16 / 9), 0.2, 2.0, f"{first} -> {second}")


def test_the_shipped_scenes_eases_turn_smoothly_and_their_cuts_stay_cuts() -> None:
    checked = 0
    for name in shipped_scene_names():
        shots = load_scene(name).render.cameras
        if not shots:
            continue  # the default film: its one ease is a pair of presets, above
        timeline = CameraTimeline(shots, STAGE, 16 / 9)
        for index, shot in enumerate(shots[1:], start=1):
            assert shot.start is not None
            if shot.transition == "ease":
                check_ease(timeline, shot.start, shot.ease, f"{name} shot {index}")
                checked += 1
            else:
                before = timeline.pose(shot.start - 1e-6)
                after = timeline.pose(shot.start)
                assert after == timeline._shot_pose(timeline.shots[index], shot.start)
                assert before != after or shots[index - 1] == shot, name
    assert checked >= 1  # pocket_shot's ease into overhead


@pytest.mark.long
def test_every_ease_of_the_shipped_films_keeps_the_horizon_level() -> None:
    """Each shipped scene's film as rendered (its own shots, or the default film's,
    on its own table and break), sampled at 120 frames/s through every ease."""
    from billiards.record.window import film_trajectory
    from billiards.render.film import camera_timeline
    from billiards.simulation import simulate_scene

    eased_scenes = set()
    for name in shipped_scene_names():
        scene = load_scene(name)
        # A still's trajectory: the whole span of the film, sampled at its frame rate.
        trajectory = film_trajectory(simulate_scene(scene), scene.render, 0.0)
        timeline = camera_timeline(trajectory, scene.render)
        for index, shot in enumerate(timeline.shots[1:], start=1):
            if shot.transition != "ease":
                continue
            times = shot.start + np.linspace(0.0, shot.ease, round(shot.ease * 120) + 1)
            leans = [roll(timeline.pose(float(t))) for t in times]
            assert max(leans) <= LEVEL, (name, index, max(leans))
            eased_scenes.add(name)
    # The seed break's ease out of overhead, the shots' eases into it, and most others.
    assert {"break", "pocket_shot", "throw_shot"} <= eased_scenes
    assert len(eased_scenes) >= len(shipped_scene_names()) - 2, eased_scenes


def test_an_ease_ends_exactly_on_its_shots() -> None:
    first = CameraPose((0.0, -1.0, 0.6), (1.0, 0.5, 0.0), 45.0)
    second = CameraPose((1.0, 0.5, 3.0), (1.0, 0.51, 0.0), 40.0)
    for blend, pose in ((0.0, first), (1.0, second)):
        got = eased(first, second, blend)
        assert np.allclose(got.eye, pose.eye) and np.allclose(got.target, pose.target)
        assert turn_between(got, pose) < 1e-4


def test_a_shot_straight_down_shows_the_tables_length_across_and_eases_out_level() -> None:
    # Its +z up vector lies along the view, so says nothing: the picture faces as the
    # overhead preset's does (+x to the right, +y up), not a picture of NaNs.
    down = CameraPose((1.065, 0.5325, 2.0), (1.065, 0.5325, 0.0), 40.0)
    right, up, _ = down.basis()
    assert np.allclose(right, (1.0, 0.0, 0.0)) and np.allclose(up, (0.0, 1.0, 0.0))
    assert np.isfinite(down.view_projection(16 / 9)).all()
    shots = (
        CameraShot(eye=down.eye, target=down.target),
        CameraShot(start=0.2, preset="corner", transition="ease", ease=2.0),
    )
    check_ease(CameraTimeline(shots, STAGE, 16 / 9), 0.2, 2.0, "straight down -> corner")
