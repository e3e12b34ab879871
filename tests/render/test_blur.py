"""Facts about motion blur: a ball is drawn over the open shutter along its exact path,
so a fast ball's streak is its speed times the shutter long, and a resting ball stays
sharp."""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.drop import GONE_DEPTH
from billiards.record.trajectory import Trajectory
from billiards.render.film_clock import FilmClock
from billiards.render.gl.renderer import Renderer
from billiards.stage.cameras import CameraPose
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


def interior_dips(profile: npt.NDArray[np.float64], tolerance: float) -> list[int]:
    """Indices where the profile falls more than `tolerance` below both a point before
    it and a point after it: an interior minimum, as copies or rings of a ball show."""
    ahead = np.maximum.accumulate(profile)
    behind = np.maximum.accumulate(profile[::-1])[::-1]
    dips = np.minimum(ahead, behind) - profile
    return [int(i) for i in np.flatnonzero(dips > tolerance)]


def streak_profile(ctx: object, speed: float, lift: float, exposure: float) -> np.ndarray:
    """How much the ball (and, on the cloth, its shadow) changes the picture, summed over
    the colour channels, along the row through its path, seen from above."""
    view = pose()
    pictures = []
    for gone in (False, True):
        trajectory = rolling_trajectory(fps=240.0, end=0.1, speed=speed, deceleration=1e-9)
        trajectory.positions[:, 0, 2] = lift
        if gone:
            trajectory = without_cue(trajectory)
        renderer = Renderer(ctx, trajectory, SIZE, antialias=0)  # type: ignore[arg-type]
        try:
            x = CUE_START[0] + speed * TIME
            look = CameraPose((x, CUE_START[1] - 1e-3, 0.9), (x, CUE_START[1], 0.0), 40.0)
            pictures.append(renderer.frame(TIME, look, exposure).astype(np.float64))
        finally:
            renderer.release()
    row = round(float(view.project(np.array([[*view.target[:2], lift]]), *SIZE)[0][1]))
    return np.abs(pictures[0] - pictures[1])[row].sum(axis=1)


@pytest.mark.parametrize("speed", [2.0, 10.0])  # 10 m/s: the hard break's cue ball
@pytest.mark.parametrize("lift", [RADIUS, LIFT], ids=["with its shadow", "alone"])
def test_a_fast_balls_streak_is_one_smear_without_copies(
    ctx: object, speed: float, lift: float
) -> None:
    profile = streak_profile(ctx, speed, lift, 0.5 / 30.0)
    marked = np.flatnonzero(profile > 0.1 * profile.max())
    inside = profile[marked[0] : marked[-1] + 1]
    # Copies or rings would be dips between brighter parts (a quarter or more of the
    # peak, as the discrete instants drew them). What is left is the ball's own print
    # and highlight smeared along the streak, and, seen through it, its shadow's time
    # average, darkest mid-path: swells of a few per cent.
    assert interior_dips(inside, 0.08 * float(inside.max())) == []
    assert len(inside) > 20  # a streak, not a sharp ball


def test_the_dip_finder_finds_two_copies() -> None:
    two = np.array([0, 5, 40, 60, 40, 20, 40, 60, 40, 5, 0], dtype=np.float64)
    assert interior_dips(two, 4.0) == [4, 5, 6]
    assert interior_dips(np.array([0, 10, 30, 30, 30, 10, 0], dtype=np.float64), 4.0) == []
