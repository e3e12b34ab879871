"""What a simulation returns: the events, and the motion evaluable at any time."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from billiards.physics.events import Event
from billiards.physics.motion import FloatArray, IntArray, path_length, rest_duration


@dataclass(frozen=True)
class AnchoredMotion:
    """Exact motion: each ball's anchors (one per contact), evaluated in closed form."""

    ball: IntArray  # (S,) which ball each segment belongs to
    t0: FloatArray  # (S,) s
    p0: FloatArray  # (S, 2) m
    v0: FloatArray  # (S, 2) m/s
    decel: float
    count: int  # number of balls

    def positions_at(self, times: FloatArray) -> FloatArray:
        return self._state_at(times)[0]

    def velocities_at(self, times: FloatArray) -> FloatArray:
        """Velocities (T, N, 2); at a contact's own time, the velocities just after it."""
        return self._state_at(times)[1]

    def _state_at(self, times: FloatArray) -> tuple[FloatArray, FloatArray]:
        times = np.asarray(times, dtype=np.float64)
        positions = np.empty((len(times), self.count, 2))
        velocities = np.empty((len(times), self.count, 2))
        speed = np.hypot(self.v0[:, 0], self.v0[:, 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            direction = np.where(speed[:, None] > 0, self.v0 / speed[:, None], 0.0)
        rest_after = rest_duration(speed, self.decel)
        for ball in range(self.count):
            rows = np.flatnonzero(self.ball == ball)  # in time order, as logged
            index = rows[np.maximum(np.searchsorted(self.t0[rows], times, side="right") - 1, 0)]
            tau = np.clip(times - self.t0[index], 0.0, rest_after[index])
            distance = path_length(speed[index], self.decel, tau)
            positions[:, ball] = self.p0[index] + direction[index] * distance[:, None]
            speed_now = np.where(tau < rest_after[index], speed[index] - self.decel * tau, 0.0)
            velocities[:, ball] = direction[index] * speed_now[:, None]
        return positions, velocities

    def path_breaks(self) -> FloatArray:
        return np.unique(self.t0)


@dataclass(frozen=True)
class SampledMotion:
    """Stepped motion (the naive method): positions at every step, straight between."""

    times: FloatArray  # (K,) s
    positions: FloatArray  # (K, N, 2) m
    velocities: FloatArray  # (K, N, 2) m/s, after each step

    def velocities_at(self, times: FloatArray) -> FloatArray:
        """The velocities after the last step at or before each time."""
        index = np.clip(
            np.searchsorted(self.times, times, side="right") - 1, 0, len(self.times) - 1
        )
        return np.asarray(self.velocities[index])

    def positions_at(self, times: FloatArray) -> FloatArray:
        times = np.asarray(times, dtype=np.float64)
        upper = np.clip(np.searchsorted(self.times, times, side="right"), 1, len(self.times) - 1)
        lower = upper - 1
        span = self.times[upper] - self.times[lower]
        weight = np.clip((times - self.times[lower]) / span, 0.0, 1.0)[:, None, None]
        return np.asarray(self.positions[lower] * (1 - weight) + self.positions[upper] * weight)

    def path_breaks(self) -> FloatArray:
        return self.times


@dataclass(frozen=True)
class SimulationResult:
    method: str
    dt: float | None  # the fixed step (None for "event")
    ball_ids: tuple[str, ...]
    radius: float
    table_size: tuple[float, float]
    masses: FloatArray
    initial_positions: FloatArray  # (N, 2)
    initial_velocities: FloatArray  # (N, 2)
    events: tuple[Event, ...]
    rest_time: float  # s: when the last ball stopped, or max_time
    steps: int  # fixed steps taken (0 for "event")
    motion: AnchoredMotion | SampledMotion
    complete: bool  # False when max_time or max_events ended the run first

    def positions_at(self, times: FloatArray) -> FloatArray:
        """Ball centres (T, N, 2), clamped to the cushion lines (a rounding-level guard)."""
        positions = self.motion.positions_at(np.atleast_1d(np.asarray(times, dtype=np.float64)))
        r = self.radius
        length, width = self.table_size
        positions[..., 0] = np.clip(positions[..., 0], r, length - r)
        positions[..., 1] = np.clip(positions[..., 1], r, width - r)
        return positions

    def velocities_at(self, times: FloatArray) -> FloatArray:
        return self.motion.velocities_at(np.atleast_1d(np.asarray(times, dtype=np.float64)))

    def path_breaks(self) -> FloatArray:
        return self.motion.path_breaks()

    @property
    def final_positions(self) -> FloatArray:
        return self.positions_at(np.array([self.rest_time]))[0]
