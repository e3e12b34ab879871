"""Slow motion around the first contacts: a map between simulation and film time.

`SlowMotion` maps simulation time to film time (for the sound's events) and back (for
the frames); cameras and ball states keep taking simulation time, so a shot stays on
the moment it was written for.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Event, first_contact_time

FloatArray = npt.NDArray[np.float64]

# The slow-motion window, in simulation seconds around the first ball-ball contact:
# full slow motion from SLOW_BEFORE before it to SLOW_AFTER after it, eased in and
# out over SLOW_EASE on each side (the cue ball's approach and the rack's first
# spread, the part of a break too fast to see at full speed).
SLOW_BEFORE = 0.1  # s
SLOW_AFTER = 0.4  # s
SLOW_EASE = 0.15  # s


@dataclass(frozen=True)
class SlowMotion:
    """Playback at `speed` from simulation time `start` to `end`: below 1 slowed, above
    1 quickened (billiards.render.quiet_play's stretches of slow rolling).

    The film's rate d(film time)/d(simulation time) is 1 + (1/speed - 1) w(t), where
    the weight w rises from 0 to 1 by a smoothstep over the `ease` seconds before
    `start` and falls back over the `ease` seconds after `end`: the picture slows
    down and speeds up again without a jolt. Before the window film time equals
    simulation time; after it the film is `extra` seconds behind (ahead, if quickened).
    """

    speed: float
    start: float  # s, simulation time
    end: float  # s
    ease: float = SLOW_EASE  # s

    def __post_init__(self) -> None:
        if not (0.0 < self.speed < float("inf")):
            raise ValueError(f"playback speed {self.speed:g}: expected a positive number")
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

    def lag(self, sim_times: npt.ArrayLike) -> FloatArray:
        """Film time less simulation time at each simulation time: from 0 before the
        window to `extra` after it (several windows' lags add up: FilmClock)."""
        times = np.asarray(sim_times, dtype=np.float64)
        return self._gain * self._weight_integral(times)

    def film_time(self, sim_times: npt.ArrayLike) -> FloatArray:
        """Film time of each simulation time: continuous and strictly increasing."""
        times = np.asarray(sim_times, dtype=np.float64)
        return times + self.lag(times)

    def sim_time(self, film_times: npt.ArrayLike) -> FloatArray:
        """The inverse of film_time, by bisection to the last bit.

        film_time(t) lies between t and t + extra, so t lies in [f - extra, f] (the
        other way round for a quickened window).
        """
        film = np.asarray(film_times, dtype=np.float64)
        low, high = film - max(self.extra, 0.0), film - min(self.extra, 0.0)
        for _ in range(80):
            middle = 0.5 * (low + high)
            late = self.film_time(middle) > film
            high = np.where(late, middle, high)
            low = np.where(late, low, middle)
        return 0.5 * (low + high)
