"""The film's clock: which simulation time each film frame shows.

A film frame k is shown at film time `FilmClock.start + k / fps` and shows the break
at simulation time `FilmClock.sim_times[k]`. Without slow motion film time is
simulation time; with it, billiards.render.slow_motion maps one to the other.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory
from billiards.render.slow_motion import SlowMotion

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class FilmClock:
    fps: float
    sim_times: FloatArray  # (frames,) s, simulation time shown by each film frame
    slow_motion: SlowMotion | None = None

    @property
    def frame_count(self) -> int:
        return len(self.sim_times)

    @property
    def duration(self) -> float:
        """s of film."""
        return self.frame_count / self.fps

    @property
    def start(self) -> float:
        """Film time of the first frame (its simulation time when nothing is slowed)."""
        return float(self.film_time(self.sim_times[:1])[0]) if self.frame_count else 0.0

    def exposures(self, shutter: float) -> FloatArray:
        """(frames,) s of simulation time each frame's shutter is open: `shutter` of
        the frame's time (slowed frames see less of the break)."""
        if self.frame_count < 2:
            return np.full(self.frame_count, shutter / self.fps)
        return shutter * np.gradient(self.sim_times)

    def film_time(self, sim_times: npt.ArrayLike) -> FloatArray:
        """Film time of simulation times (for the sound track's events)."""
        times = np.asarray(sim_times, dtype=np.float64)
        return times.copy() if self.slow_motion is None else self.slow_motion.film_time(times)

    @classmethod
    def real_time(cls, trajectory: Trajectory, fps: float | None = None) -> FilmClock:
        """One film second per simulated second, over the whole trajectory.

        At the trajectory's own frame rate the frames are exactly its samples.
        """
        times = np.asarray(trajectory.times, dtype=np.float64)
        if fps is None or (len(times) > 1 and abs(fps - trajectory.fps) < 1e-9 * fps):
            return cls(fps or trajectory.fps or 30.0, times.copy())
        return cls.over(float(times[0]), float(times[-1]), fps)

    @classmethod
    def of(cls, trajectory: Trajectory, fps: float, slow_motion: float = 1.0) -> FilmClock:
        """The film's clock: real time, slowed to `slow_motion` around the first contacts
        (SlowMotion.around_first_contact) when that is below 1."""
        slow = SlowMotion.around_first_contact(trajectory.events, slow_motion)
        if slow is None:
            return cls.real_time(trajectory, fps)
        return cls.over(float(trajectory.times[0]), float(trajectory.times[-1]), fps, slow)

    @classmethod
    def over(
        cls, start: float, end: float, fps: float, slow_motion: SlowMotion | None = None
    ) -> FilmClock:
        """Frames every 1/fps s of film from simulation time `start` to `end`."""
        if slow_motion is None:
            count = int(np.floor((end - start) * fps + 1e-9)) + 1
            return cls(fps, start + np.arange(count) / fps)
        first, last = slow_motion.film_time(np.array([start, end]))
        count = int(np.floor((last - first) * fps + 1e-9)) + 1
        sim_times = slow_motion.sim_time(first + np.arange(count) / fps)
        sim_times[0] = start  # exact, not a bisection's last bit
        return cls(fps, sim_times, slow_motion)
