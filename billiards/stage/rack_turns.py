"""The way each object ball lies when the rack is set: its number turned at random.

A racked ball does not sit with its number straight up. The physics starts every ball
at the identity orientation (billiards.record.trajectory), and orientation never feeds back
into the motion, so the film turns each object ball once, in its own body frame,
before the recorded rolling: drawn orientation = recorded * set. The turns come from a
generator seeded by the scene (its ball ids and starting places), so a film repeats
bit for bit, and two scenes racked alike lie alike. The cue ball keeps its own.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import numpy.typing as npt

from billiards.record import quaternions
from billiards.record.trajectory import Trajectory
from billiards.record.window import CUE_BALL

FloatArray = npt.NDArray[np.float64]


def scene_seed(ball_ids: Sequence[str], start: FloatArray) -> int:
    """A seed from what sets the scene: the ball ids and where each ball starts (N, 3)."""
    digest = hashlib.sha256(",".join(ball_ids).encode())
    digest.update(np.ascontiguousarray(start, dtype="<f8").tobytes())
    return int.from_bytes(digest.digest()[:8], "little")


def uniform_turns(count: int, rng: np.random.Generator) -> FloatArray:
    """`count` unit quaternions (x, y, z, w) uniform over all rotations (Shoemake 1992,
    "Uniform random rotations", Graphics Gems III)."""
    u1, u2, u3 = rng.random((3, count))
    a, b = np.sqrt(1.0 - u1), np.sqrt(u1)
    return np.stack(
        [
            a * np.sin(2 * np.pi * u2),
            a * np.cos(2 * np.pi * u2),
            b * np.sin(2 * np.pi * u3),
            b * np.cos(2 * np.pi * u3),
        ],
        axis=1,
    )


def rack_turns(trajectory: Trajectory) -> FloatArray:
    """Each ball's turn (N, 4) as the rack is set: uniform for an object ball, the
    identity for the cue ball."""
    return turns_of(trajectory.ball_ids, trajectory.positions[0])


def turns_of(ball_ids: Sequence[str], start: FloatArray) -> FloatArray:
    """rack_turns for balls named `ball_ids` starting at `start` (N, 3): the export's
    balls lie as the film's do."""
    turns = uniform_turns(len(ball_ids), np.random.default_rng(scene_seed(ball_ids, start)))
    for index, ball_id in enumerate(ball_ids):
        if ball_id == CUE_BALL:
            turns[index] = quaternions.IDENTITY
    return turns


def racked(trajectory: Trajectory) -> Trajectory:
    """The trajectory as drawn: every recorded orientation times its ball's rack turn
    (the turn first, in the ball's own frame, then the recorded rolling)."""
    turns = rack_turns(trajectory)
    orientations = quaternions.multiply(trajectory.orientations, turns[None, :, :])
    return replace(trajectory, orientations=orientations)
