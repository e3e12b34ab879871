"""A simulation sampled into a Trajectory: positions at the asked times, the pocketed
balls' drops and the balls' orientations."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from billiards.record import quaternions
from billiards.record.drop import drop_pocketed, fly_off_table
from billiards.record.orientations import rolling_orientations, spin_orientations
from billiards.record.pocket_shapes import PocketShapes
from billiards.record.trajectory import RecordedMotion, Trajectory

FloatArray = npt.NDArray[np.float64]


def record_trajectory(
    motion: RecordedMotion,
    fps: float = 30.0,
    start: float = 0.0,
    end: float | None = None,
) -> Trajectory:
    """Sample a simulation at `fps` from `start` to `end` (default: rest time).

    Before t = 0 the balls wait at their starting places, so a film can open a moment
    before the cue ball moves. Orientations follow the rolling rotation over the path
    each ball actually travelled, including the bends at its contacts between frames.
    """
    stop = motion.rest_time if end is None else end
    count = max(int(np.floor((stop - start) * fps + 1e-9)) + 1, 1)
    return sample_trajectory(motion, start + np.arange(count) / fps)


def sample_trajectory(
    motion: RecordedMotion,
    times: FloatArray,
    table_size: tuple[float, float] | None = None,
    *,
    turn: bool = True,
) -> Trajectory:
    """Sample a simulation at any increasing times (record_trajectory's even ones, or
    say every contact for a picture of the paths). With turn=False the orientations
    stay at the identity: a picture from above does not need them, and for a stepped
    run they cost a loop over every step."""
    flat = motion.positions_at(times)
    if not turn:
        orientations = np.tile(np.array(quaternions.IDENTITY), (*flat.shape[:2], 1))
    elif motion.model == "spin":
        orientations = spin_orientations(motion, times)
    else:
        orientations = rolling_orientations(motion, times)
    heights = getattr(motion, "heights_at", None)  # a flying ball's z (issue 45)
    lifted = None if heights is None else heights(times)[..., None]
    height = np.full((*flat.shape[:2], 1), motion.radius) if lifted is None else lifted
    positions = np.concatenate([flat, height], axis=2)
    pockets = None if motion.pockets is None else PocketShapes.of(motion.pockets)
    if pockets is not None:
        drop_pocketed(positions, times, motion, pockets, motion.radius)
    if lifted is not None:
        fly_off_table(positions, times, motion)
    return Trajectory(
        ball_ids=motion.ball_ids,
        radius=motion.radius,
        table_size=table_size or motion.table_size,
        times=times,
        positions=positions,
        orientations=orientations,
        events=motion.events,
        rest_time=motion.rest_time,
        pockets=pockets,
    )
