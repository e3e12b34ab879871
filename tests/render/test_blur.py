"""Facts about motion blur: a ball is drawn over the open shutter along its exact path,
so a fast ball's streak is its speed times the shutter long, and a resting ball stays
sharp."""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt
import pytest

from billiards.render.cameras import CameraPose
from billiards.render.film_clock import FilmClock
from billiards.render.renderer import Renderer
from billiards.trajectory import GONE_DEPTH, Trajectory
from tests.render.fixtures import (
    CUE_START,
    RADIUS,
    gl_context,  # noqa: F401 (the ctx fixture)
    rolling_trajectory,
)

pytestmark = pytest.mark.gl
SIZE = (480, 270)
SPEED = 10.0  # m/s: a hard break's cue ball
TIME = 0.03  # s: the cue ball 0.3 m on from its start


LIFT = 0.5  # m: the cue ball flies this high, so its faint shadow does not mark the cloth


def fast() -> Trajectory:
    trajectory = rolling_trajectory(fps=240.0, end=0.1, speed=SPEED, deceleration=1e-9)
    trajectory.positions[:, 0, 2] = LIFT
    return trajectory


def without_cue(trajectory: Trajectory) -> Trajectory:
    positions = trajectory.positions.copy()
    positions[:, 0] = (CUE_START[0], CUE_START[1], GONE_DEPTH)
    return dataclasses.replace(trajectory, positions=positions)


def pose() -> CameraPose:
    x = CUE_START[0] + SPEED * TIME
    return CameraPose((x, CUE_START[1] - 1e-3, 0.9), (x, CUE_START[1], 0.0), 40.0)


def streak_length(ctx: object, exposure: float) -> float:
    """m: the width at half height, along the path, of the cue ball's mark on the cloth
    (for a disc of diameter D swept over L >= D, that is L; for a sharp one, D)."""
    view = pose()
    pictures = []
    for trajectory in (fast(), without_cue(fast())):
        renderer = Renderer(ctx, trajectory, SIZE, antialias=0)  # type: ignore[arg-type]
        try:
            pictures.append(renderer.frame(TIME, view, exposure).astype(np.float64))
        finally:
            renderer.release()
    row = round(float(view.project(np.array([[*view.target[:2], LIFT]]), *SIZE)[0][1]))
    difference: npt.NDArray[np.float64] = np.abs(pictures[0] - pictures[1])[row, :, 0]
    marked = np.flatnonzero(difference > 0.5 * difference.max())
    ends = view.project(
        np.array(
            [[view.target[0], CUE_START[1], LIFT], [view.target[0] + 0.1, CUE_START[1], LIFT]]
        ),
        *SIZE,
    )
    metres_per_pixel = 0.1 / float(ends[1][0] - ends[0][0])
    return float(marked[-1] - marked[0] + 1) * metres_per_pixel


def test_a_fast_balls_streak_is_its_speed_times_the_shutter(ctx: object) -> None:
    for shutter in (0.5, 1.0):
        exposure = shutter / 30.0
        assert streak_length(ctx, exposure) == pytest.approx(SPEED * exposure, rel=0.06)


def test_with_the_shutter_shut_a_fast_ball_is_sharp(ctx: object) -> None:
    assert streak_length(ctx, 0.0) == pytest.approx(2 * RADIUS, rel=0.1)


def test_a_resting_ball_is_the_same_with_the_shutter_open(ctx: object) -> None:
    still = rolling_trajectory(fps=240.0, end=0.1, speed=1e-12)
    renderer = Renderer(ctx, still, SIZE, antialias=0)  # type: ignore[arg-type]
    try:
        sharp = renderer.frame(TIME, pose(), 0.0)
        open_shutter = renderer.frame(TIME, pose(), 0.5 / 30.0)
    finally:
        renderer.release()
    assert np.array_equal(sharp, open_shutter)


def test_the_shutter_is_open_a_share_of_each_frames_simulated_time() -> None:
    clock = FilmClock.of(rolling_trajectory(), 30.0)
    assert np.allclose(clock.exposures(0.5), 0.5 / 30.0)
    slowed = FilmClock.of(rolling_trajectory(), 30.0, slow_motion=0.25)
    assert slowed.exposures(0.5).min() == pytest.approx(0.25 * 0.5 / 30.0, rel=0.01)
