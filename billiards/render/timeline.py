"""The film's clock and the balls' state at any simulation time.

A film frame k is shown at film time k / fps and shows the break at simulation time
`FilmClock.sim_times[k]`. Today the map is the identity shifted to the trajectory's
first frame; slow motion later only has to build a different, non-linear
`sim_times` array (cameras, ball states and sound all take simulation time).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.trajectory import Trajectory

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class FilmClock:
    fps: float
    sim_times: FloatArray  # (frames,) s, simulation time shown by each film frame

    @property
    def frame_count(self) -> int:
        return len(self.sim_times)

    @property
    def duration(self) -> float:
        """s of film."""
        return self.frame_count / self.fps

    @classmethod
    def real_time(cls, trajectory: Trajectory, fps: float | None = None) -> FilmClock:
        """One film second per simulated second, over the whole trajectory.

        At the trajectory's own frame rate the frames are exactly its samples.
        """
        times = np.asarray(trajectory.times, dtype=np.float64)
        if fps is None or (len(times) > 1 and abs(fps - trajectory.fps) < 1e-9 * fps):
            return cls(fps or trajectory.fps or 30.0, times.copy())
        count = int(np.floor((times[-1] - times[0]) * fps + 1e-9)) + 1
        return cls(fps, times[0] + np.arange(count) / fps)


def ball_state(trajectory: Trajectory, time: float) -> tuple[FloatArray, FloatArray]:
    """Ball centres (N x 3) and orientations (N x 4, x y z w) at a simulation time.

    Exact at the recorded frames; between them, centres are interpolated linearly and
    orientations by normalised linear interpolation (both far below a pixel at film
    frame rates). Clamped to the recorded span.
    """
    times = trajectory.times
    if time <= times[0]:
        return trajectory.positions[0], trajectory.orientations[0]
    if time >= times[-1]:
        return trajectory.positions[-1], trajectory.orientations[-1]
    index = int(np.searchsorted(times, time, side="right")) - 1
    t0, t1 = float(times[index]), float(times[index + 1])
    if time == t0:
        return trajectory.positions[index], trajectory.orientations[index]
    weight = (time - t0) / (t1 - t0)
    p0, p1 = trajectory.positions[index], trajectory.positions[index + 1]
    q0, q1 = trajectory.orientations[index], trajectory.orientations[index + 1]
    # q and -q are the same rotation: take the nearer one before blending.
    sign = np.where(np.einsum("ij,ij->i", q0, q1) < 0, -1.0, 1.0)[:, None]
    q = q0 * (1 - weight) + sign * q1 * weight
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return p0 * (1 - weight) + p1 * weight, q


def rotation_matrices(quaternions: FloatArray) -> FloatArray:
    """Body-to-world rotation matrices (N x 3 x 3) of unit quaternions (x, y, z, w)."""
    x, y, z, w = (quaternions[:, k] for k in range(4))
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        axis=1,
    )
