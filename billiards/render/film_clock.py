"""The film's clock: which simulation time each film frame shows.

A film frame k is shown at film time `FilmClock.start + k / fps` and shows the break
at simulation time `FilmClock.sim_times[k]`. Without slow motion or quickened quiet
play, film time is simulation time; with them, billiards.render.slow_motion's windows
map one to the other (their lags add up).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory
from billiards.render.quiet_play import quick_windows
from billiards.render.slow_motion import SlowMotion

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class FilmClock:
    fps: float
    sim_times: FloatArray  # (frames,) s, simulation time shown by each film frame
    slow_motion: SlowMotion | None = None
    # Stretches of balls barely moving, played quicker (billiards.render.quiet_play).
    quick: tuple[SlowMotion, ...] = ()

    @property
    def windows(self) -> tuple[SlowMotion, ...]:
        """Every window of the clock: the slow motion's, then the quickened ones."""
        return (*(() if self.slow_motion is None else (self.slow_motion,)), *self.quick)

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
        return film_time(self.windows, sim_times)

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
    def of(
        cls, trajectory: Trajectory, fps: float, slow_motion: float = 1.0, quicken: bool = True
    ) -> FilmClock:
        """The film's clock: real time, slowed to `slow_motion` around the first contacts
        (SlowMotion.around_first_contact) when that is below 1, and (`quicken`) quiet
        play quickened to LONGEST_HOLD s a stretch (billiards.render.quiet_play)."""
        slow = SlowMotion.around_first_contact(trajectory.events, slow_motion)
        quick = quick_windows(trajectory) if quicken else ()
        if slow is None and not quick:
            return cls.real_time(trajectory, fps)
        start, end = float(trajectory.times[0]), float(trajectory.times[-1])
        return cls.over(start, end, fps, slow, quick)

    @classmethod
    def over(
        cls,
        start: float,
        end: float,
        fps: float,
        slow_motion: SlowMotion | None = None,
        quick: tuple[SlowMotion, ...] = (),
    ) -> FilmClock:
        """Frames every 1/fps s of film from simulation time `start` to `end`."""
        windows = (*(() if slow_motion is None else (slow_motion,)), *quick)
        if not windows:
            count = int(np.floor((end - start) * fps + 1e-9)) + 1
            return cls(fps, start + np.arange(count) / fps)
        first, last = film_time(windows, np.array([start, end]))
        count = int(np.floor((last - first) * fps + 1e-9)) + 1
        sim_times = sim_time(windows, first + np.arange(count) / fps)
        sim_times[0] = start  # exact, not a bisection's last bit
        return cls(fps, sim_times, slow_motion, quick)


def film_time(windows: tuple[SlowMotion, ...], sim_times: npt.ArrayLike) -> FloatArray:
    """Film time of simulation times under every window at once (their lags add up);
    strictly increasing, as each window's rate is positive where the others' are 1."""
    times = np.asarray(sim_times, dtype=np.float64)
    film = times.copy()
    for window in windows:
        film += window.lag(times)
    return film


def sim_time(windows: tuple[SlowMotion, ...], film_times: npt.ArrayLike) -> FloatArray:
    """The inverse of film_time, by bisection to the last bit: film time less
    simulation time lies between the windows' negative extras and their positive ones."""
    if len(windows) == 1:
        return windows[0].sim_time(film_times)
    film = np.asarray(film_times, dtype=np.float64)
    low = film - sum(max(w.extra, 0.0) for w in windows)
    high = film - sum(min(w.extra, 0.0) for w in windows)
    for _ in range(80):
        middle = 0.5 * (low + high)
        late = film_time(windows, middle) > film
        high = np.where(late, middle, high)
        low = np.where(late, low, middle)
    return 0.5 * (low + high)
