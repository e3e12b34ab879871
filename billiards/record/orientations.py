"""The balls' orientations over a sampled run: rolling without slipping, or turning by
the spin model's angular velocity."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import numpy.typing as npt

from billiards.record import quaternions
from billiards.record.trajectory import RecordedMotion

FloatArray = npt.NDArray[np.float64]


def rolling_orientations(motion: RecordedMotion, times: FloatArray) -> FloatArray:
    """Each ball's orientation (F, N, 4) at `times`, starting from identity at t = 0.

    Between two path breaks a ball rolls straight, so the rotation over a stretch of
    length s in direction phi is the report's three-step rotation
    Rz(phi) Ry(s / r) Rz(-phi), applied on the left of the orientation so far.
    """
    breaks = motion.path_breaks()
    breaks = breaks[(breaks > 0) & (breaks < times[-1])]
    grid = np.union1d(np.maximum(times, 0.0), breaks)
    grid = np.union1d(grid, [0.0])
    positions = motion.positions_at(grid)
    steps = np.diff(positions, axis=0)  # (G-1, N, 2): straight stretches
    turns = (rolling_rotation(step, motion.radius) for step in steps)
    return _turned(turns, grid, positions.shape[1], times)


# The spin model's balls turn by their own angular velocity, integrated on a grid at
# least this fine (and through every path break, where it jumps).
SPIN_STEP = 1.0 / 480.0  # s


def spin_orientations(motion: RecordedMotion, times: FloatArray) -> FloatArray:
    """Each ball's orientation (F, N, 4) at `times` in the spin model, from identity at
    t = 0: the angular velocity w(t) (piecewise linear between breaks) integrated by the
    midpoint rule on a grid through every break, each step a turn by w dt about w. For
    the picture only; orientation never feeds back into the motion."""
    end = float(np.max(times))
    breaks = motion.path_breaks()
    breaks = breaks[(breaks > 0) & (breaks < end)]
    grid = np.union1d(np.maximum(times, 0.0), breaks)
    grid = np.union1d(grid, np.arange(0.0, end, SPIN_STEP))
    middles = 0.5 * (grid[:-1] + grid[1:])
    turns = np.asarray(motion.spins_at(middles)) * np.diff(grid)[:, None, None]  # (G-1, N, 3)
    count = turns.shape[1] if len(turns) else len(motion.ball_ids)
    return _turned((rotation_vector_turn(turn) for turn in turns), grid, count, times)


def _turned(
    turns: Iterator[FloatArray], grid: FloatArray, count: int, times: FloatArray
) -> FloatArray:
    """The orientations (F, N, 4) at `times` of `count` balls that start at identity at
    grid[0] and turn by each of `turns` (quaternions (N, 4), on the left) to the next
    grid point."""
    orientation = np.tile(np.array(quaternions.IDENTITY), (count, 1))
    at_grid = np.empty((len(grid), count, 4))
    at_grid[0] = orientation
    for index, turn in enumerate(turns, start=1):
        orientation = quaternions.multiply(turn, orientation)
        # Renormalise: thousands of products would otherwise drift off the unit sphere.
        orientation /= np.linalg.norm(orientation, axis=1, keepdims=True)
        at_grid[index] = orientation
    return at_grid[np.searchsorted(grid, np.maximum(times, 0.0))]


def rotation_vector_turn(turn: FloatArray) -> FloatArray:
    """Quaternions (N, 4) turning by |turn| radians about turn / |turn| (N, 3)."""
    angle = np.sqrt(np.sum(turn * turn, axis=1))
    with np.errstate(invalid="ignore", divide="ignore"):
        axis = np.where(angle[:, None] > 0, turn / angle[:, None], 0.0)
    quaternion = np.empty((len(turn), 4))
    quaternion[:, :3] = axis * np.sin(0.5 * angle)[:, None]
    quaternion[:, 3] = np.cos(0.5 * angle)
    return quaternion


def rolling_rotation(step: FloatArray, radius: float) -> FloatArray:
    """Quaternions (N, 4) for rolling along `step` (N, 2) without slipping:
    Rz(phi) * Ry(s / r) * Rz(-phi), a turn by s / r about (-sin phi, cos phi, 0)."""
    length = np.hypot(step[:, 0], step[:, 1])
    phi = np.arctan2(step[:, 1], step[:, 0])
    angle = length / radius
    turn_z = quaternions.about_axis(2, phi)
    roll_y = quaternions.about_axis(1, angle)
    unturn_z = quaternions.about_axis(2, -phi)
    return quaternions.multiply(turn_z, quaternions.multiply(roll_y, unturn_z))
