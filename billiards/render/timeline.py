"""The film's clock and the balls' state at any simulation time.

A film frame k is shown at film time `FilmClock.start + k / fps` and shows the break
at simulation time `FilmClock.sim_times[k]`. Without slow motion film time is
simulation time. With it, `SlowMotion` maps simulation time to film time (for the
sound's events) and back (for the frames); cameras and ball states keep taking
simulation time, so a shot stays on the moment it was written for.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.trajectory import Event, Trajectory

FloatArray = npt.NDArray[np.float64]

# The slow-motion window, in simulation seconds around the first ball-ball contact:
# full slow motion from SLOW_BEFORE before it to SLOW_AFTER after it, eased in and
# out over SLOW_EASE on each side (the cue ball's approach and the rack's first
# spread, the part of a break too fast to see at full speed).
SLOW_BEFORE = 0.1  # s
SLOW_AFTER = 0.4  # s
SLOW_EASE = 0.15  # s


def first_contact_time(events: Sequence[Event]) -> float | None:
    """s, simulation time of the first ball-ball contact (None if balls never touch)."""
    return next((e.time for e in events if e.kind == "ball"), None)


@dataclass(frozen=True)
class SlowMotion:
    """Playback at `speed` (in (0, 1]) from simulation time `start` to `end`.

    The film's rate d(film time)/d(simulation time) is 1 + (1/speed - 1) w(t), where
    the weight w rises from 0 to 1 by a smoothstep over the `ease` seconds before
    `start` and falls back over the `ease` seconds after `end`: the picture slows
    down and speeds up again without a jolt. Before the window film time equals
    simulation time; after it the film is `extra` seconds behind.
    """

    speed: float
    start: float  # s, simulation time
    end: float  # s
    ease: float = SLOW_EASE  # s

    def __post_init__(self) -> None:
        if not 0.0 < self.speed <= 1.0:
            raise ValueError(f"slow motion speed {self.speed:g}: expected a number in (0, 1]")
        if not (self.end >= self.start and self.ease > 0.0):
            raise ValueError("a slow-motion window needs start <= end and ease > 0")

    @classmethod
    def around_first_contact(cls, events: Sequence[Event], speed: float) -> SlowMotion | None:
        """The default window around the first ball-ball contact (or the first contact
        of any kind); None when the speed is 1 or nothing touches."""
        if speed >= 1.0:
            return None
        first = first_contact_time(events)
        if first is None:
            first = min((e.time for e in events), default=None)
        if first is None:
            return None
        return cls(speed, first - SLOW_BEFORE, first + SLOW_AFTER)

    @property
    def _gain(self) -> float:
        return 1.0 / self.speed - 1.0

    @property
    def extra(self) -> float:
        """s of film the window adds: (1/speed - 1) times its length plus one ease."""
        return self._gain * (self.end - self.start + self.ease)

    def _weight_integral(self, times: FloatArray) -> FloatArray:
        """The integral of w from -infinity to each time (closed form)."""
        e, a, b = self.ease, self.start, self.end
        rising = np.clip((times - (a - e)) / e, 0.0, 1.0)
        full = np.clip(times - a, 0.0, b - a)
        falling = np.clip((times - b) / e, 0.0, 1.0)

        def smoothstep_integral(x: FloatArray) -> FloatArray:
            return x**3 - x**4 / 2  # of 3x^2 - 2x^3, from 0 to x

        return e * smoothstep_integral(rising) + full + e * (falling - smoothstep_integral(falling))

    def film_time(self, sim_times: npt.ArrayLike) -> FloatArray:
        """Film time of each simulation time: continuous and strictly increasing."""
        times = np.asarray(sim_times, dtype=np.float64)
        return times + self._gain * self._weight_integral(times)

    def sim_time(self, film_times: npt.ArrayLike) -> FloatArray:
        """The inverse of film_time, by bisection to the last bit.

        film_time(t) lies between t and t + extra, so t lies in [f - extra, f].
        """
        film = np.asarray(film_times, dtype=np.float64)
        low, high = film - self.extra, film.copy()
        for _ in range(80):
            middle = 0.5 * (low + high)
            late = self.film_time(middle) > film
            high = np.where(late, middle, high)
            low = np.where(late, low, middle)
        return 0.5 * (low + high)


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
