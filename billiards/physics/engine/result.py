"""What a simulation returns: the events, and the motion evaluable at any time."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Self

import numpy as np

from billiards.physics.engine.events import Event, Transition
from billiards.physics.numerics.arrays import BoolArray, FloatArray, IntArray
from billiards.physics.pockets import PocketTable


@dataclass(frozen=True)
class AnchoredMotion:
    """Exact motion: each ball's anchors (one per contact), evaluated in closed form by
    its motion model's subclass (rolling.result.RollingMotion, spin.result.SpinMotion)."""

    ball: IntArray  # (S,) which ball each segment belongs to, in the order logged
    t0: FloatArray  # (S,) s, non-decreasing for each ball
    p0: FloatArray  # (S, 2) m
    v0: FloatArray  # (S, 2) m/s
    decel: float
    count: int  # number of balls

    @classmethod
    def logged(
        cls, balls: IntArray, rows: FloatArray, decel: float, count: int, **own: Any
    ) -> Self:
        """From the log's rows (S, C): t0, p0, v0 in columns 0-4; a model's `own` fields."""
        t0, p0, v0 = rows[:, 0].copy(), rows[:, 1:3].copy(), rows[:, 3:5].copy()
        return cls(ball=balls, t0=t0, p0=p0, v0=v0, decel=decel, count=count, **own)

    def positions_at(self, times: FloatArray) -> FloatArray:
        times = np.asarray(times, dtype=np.float64)
        return self.segment_state(self.segments_at(times), times[:, None])[0]

    def velocities_at(self, times: FloatArray) -> FloatArray:
        """Velocities (T, N, 2); at a contact's own time, the velocities just after it."""
        times = np.asarray(times, dtype=np.float64)
        return self.segment_state(self.segments_at(times), times[:, None])[1]

    def segments_at(self, times: FloatArray, *, side: str = "right") -> IntArray:
        """Each ball's segment (T, N) in force at each time: the last anchored at or before
        it ("right"; "left": strictly before, just before a contact then), else its first."""
        times = np.asarray(times, dtype=np.float64)
        if times.shape == (1,) and side == "right" and math.isfinite(times[0]):
            # One finite time (a run's final positions), unsorted: a ball's t0 never falls.
            rows, first, found = last_at_or_before(self.ball, self.t0 <= times[0], self.count)
            return np.asarray(rows[np.maximum(found, first)][None, :], dtype=np.intp)
        # Exact ranks make (ball, time) one integer key: one searchsorted for all.
        _, ranks = np.unique(np.concatenate([self.t0, times]), return_inverse=True)
        stride = len(self.t0) + len(times) + 1
        order = np.lexsort((np.arange(len(self.t0)), self.ball))
        keys = self.ball[order] * stride + ranks[: len(self.t0)][order]
        wanted = np.arange(self.count)[None, :] * stride + ranks[len(self.t0) :][:, None]
        found = np.searchsorted(keys, wanted, side="right" if side == "right" else "left") - 1
        first = np.searchsorted(self.ball[order], np.arange(self.count), side="left")
        return np.asarray(order[np.maximum(found, first[None, :])], dtype=np.intp)

    def segment_state(
        self, rows: IntArray, times: FloatArray | float
    ) -> tuple[FloatArray, FloatArray]:
        """Positions and velocities of the given segments at `times` (broadcasting): the
        motion model's closed form (rolling.result, spin.result)."""
        raise NotImplementedError

    @classmethod
    def keep_final_positions(cls, results: Sequence[SimulationResult]) -> None:
        """Keep these results' final positions, found at once where a model can (each
        finds its own when asked otherwise)."""

    def path_breaks(self) -> FloatArray:
        return np.unique(self.t0)

    def spins_at(self, times: FloatArray) -> FloatArray | None:
        """None: a rolling ball has no spin of its own (it turns at z x v / r)."""
        return None


@dataclass(frozen=True)
class SampledMotion:
    """Stepped motion (the naive method): positions at every step, straight between."""

    times: FloatArray  # (K,) s
    positions: FloatArray  # (K, N, 2) m
    velocities: FloatArray  # (K, N, 2) m/s, after each step
    spins: FloatArray | None = None  # (K, N, 3) rad/s after each step (the spin model)

    def velocities_at(self, times: FloatArray) -> FloatArray:
        """The velocities after the last step at or before each time."""
        return np.asarray(self.velocities[self._step_at(times)])

    def spins_at(self, times: FloatArray) -> FloatArray | None:
        """The spins after the last step at or before each time (None: rolling)."""
        return None if self.spins is None else np.asarray(self.spins[self._step_at(times)])

    def _step_at(self, times: FloatArray) -> IntArray:
        return np.clip(np.searchsorted(self.times, times, side="right") - 1, 0, len(self.times) - 1)

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
class Pocketing:
    """A ball that dropped: which, into which pocket, when."""

    ball: str  # id
    pocket: str  # billiards.physics.pockets.POCKET_NAMES
    time: float  # s, when its centre crossed the pocket's capture line


@dataclass(frozen=True)
class SimulationResult:
    method: str
    model: str  # the motion model that ran: billiards.physics.engine.motion_law.MOTION_LAWS
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
    transitions: tuple[Transition, ...] = ()  # motion-state changes (the spin model)
    stopped_by: str | None = None  # "max_time" or "max_events" when not complete
    pockets: PocketTable | None = None  # None: a table without pockets

    @property
    def pocketed(self) -> tuple[Pocketing, ...]:
        """The balls that dropped, in the order they dropped."""
        return tuple(
            Pocketing(event.balls[0], event.pocket, event.time)
            for event in self.events
            if event.kind == "pocket" and event.pocket is not None
        )

    def positions_at(self, times: FloatArray) -> FloatArray:
        """Ball centres (T, N, 2), clamped to the cushion lines (a rounding-level guard)
        on a table without pockets; a pocketed ball stays where it was captured."""
        positions = self.motion.positions_at(np.atleast_1d(np.asarray(times, dtype=np.float64)))
        if self.pockets is not None:
            # Balls in a pocket's mouth are past the cushion lines: nothing to clamp.
            return positions
        r = self.radius
        length, width = self.table_size
        positions[..., 0] = np.clip(positions[..., 0], r, length - r)
        positions[..., 1] = np.clip(positions[..., 1], r, width - r)
        return positions

    def velocities_at(self, times: FloatArray) -> FloatArray:
        return self.motion.velocities_at(np.atleast_1d(np.asarray(times, dtype=np.float64)))

    def spins_at(self, times: FloatArray) -> FloatArray:
        """Angular velocities (T, N, 3): the spin model's own, else rolling's z x v / r."""
        times = np.atleast_1d(np.asarray(times, dtype=np.float64))
        own = self.motion.spins_at(times)
        if own is not None:
            return own
        velocities = self.velocities_at(times)
        spins = np.zeros((*velocities.shape[:-1], 3))
        spins[..., 0] = -velocities[..., 1] / self.radius
        spins[..., 1] = velocities[..., 0] / self.radius
        return spins

    def heights_at(self, times: FloatArray) -> FloatArray:
        """Ball centres' heights (T, N): the radius on the cloth, a flying ball's parabola
        where a run lets one leave it (spin.result.SpinMotion.heights_at)."""
        times = np.atleast_1d(np.asarray(times, dtype=np.float64))
        own = getattr(self.motion, "heights_at", None)
        if own is not None:
            return np.asarray(own(times), dtype=np.float64)
        return np.full((len(times), len(self.ball_ids)), self.radius)

    def climbs_at(self, times: FloatArray) -> FloatArray:
        """Ball centres' vertical velocities (T, N): 0 on the cloth (heights_at's rate)."""
        times = np.atleast_1d(np.asarray(times, dtype=np.float64))
        own = getattr(self.motion, "climbs_at", None)
        if own is not None:
            return np.asarray(own(times), dtype=np.float64)
        return np.zeros((len(times), len(self.ball_ids)))

    def path_breaks(self) -> FloatArray:
        return self.motion.path_breaks()

    @property
    def curved_paths(self) -> bool:
        """Whether paths curve between the path breaks (the spin model's, not naive)."""
        return self.model == "spin" and not isinstance(self.motion, SampledMotion)

    @property
    def final_positions(self) -> FloatArray:
        """Ball centres (N, 2) at rest_time (keep_final_positions' for a batch's)."""
        kept = self.__dict__.get("_final_positions")
        if kept is not None:
            return np.array(kept)
        return self.positions_at(np.array([self.rest_time]))[0]


def last_at_or_before(
    group: IntArray, before: BoolArray, count: int
) -> tuple[IntArray, IntArray, IntArray]:
    """Segments by group (stably), each group's first, and its last `before` (first - 1)."""
    order = np.lexsort((group,))  # stable
    first = np.searchsorted(group[order], np.arange(count), side="left")
    # By group, those at or before the time first: a key that never falls.
    keys = 2 * group[order] + ~before[order]
    found = np.searchsorted(keys, 2 * np.arange(count), side="right") - 1
    return order, first, found


def keep_final_positions(results: Sequence[SimulationResult]) -> None:
    """Keep many exact results' final positions, each motion model's at once
    (AnchoredMotion.keep_final_positions), bit for bit final_positions' own."""
    by_model: dict[type[AnchoredMotion], list[SimulationResult]] = {}
    for result in results:
        if isinstance(result.motion, AnchoredMotion) and math.isfinite(result.rest_time):
            by_model.setdefault(type(result.motion), []).append(result)
    for model, chosen in by_model.items():
        model.keep_final_positions(chosen)
