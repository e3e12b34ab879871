"""What the calendar asks of a motion model, and the registry of models by name.

A motion law holds every ball's anchor (its state just after its last event) and
answers, in closed form, where the balls are and when they next meet an edge, each
other, or the end of their motion state; the calendar owns the rest (the order, the
contact laws, the rounding rules, the log). A new model is a class of this shape and
an entry in MOTION_LAWS.
"""

from __future__ import annotations

import importlib
from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

import numpy as np

from billiards.physics.numerics.arrays import (
    BoolArray,
    Constant,
    Dynamics,
    FloatArray,
    IntArray,
    Kinematics,
)

if TYPE_CHECKING:
    from billiards.physics.engine.result import AnchoredMotion
    from billiards.physics.engine.setup import Setup

# Model name -> "module:class", imported on first use (a rolling run loads no spin).
MOTION_LAWS = {
    "rolling": "billiards.physics.rolling.law:RollingLaw",
    "spin": "billiards.physics.spin.law:SpinLaw",
}


# Edges some balls ignore (one each grazed or is held on): a mask over the balls asked
# and an edge index for each, or None.
Skips = tuple[BoolArray, IntArray] | None
Pairs = tuple[IntArray, IntArray]


class MotionLaw(Protocol):
    """Every ball's motion between events, for the R runs of a batch: ball b of run r is
    row r N + b (engine.batch: padding, constants one or one a row)."""

    count: int  # N

    # When each ball's motion state ends by itself (inf: never), the third kind of event.
    change_time: FloatArray
    state_names: tuple[str, ...]  # by the state indices of transitions

    def state_at(self, balls: IntArray, time: float | FloatArray) -> Dynamics:
        """Positions, velocities, spins and accelerations of `balls` at `time`."""

    def anchor(
        self, balls: IntArray, time: float | FloatArray, kinematics: Kinematics
    ) -> FloatArray:
        """Re-anchor `balls`; their rows for the log (t0, p0, v0, then the model's own)."""

    def state_changes(self, balls: IntArray, times: float | FloatArray) -> Kinematics:
        """The kinematics that start `balls`' next motion states at their change_time."""

    def slipping(self, balls: IntArray) -> BoolArray:
        """Which balls slide (a slip that can press them into what they touch)."""

    def states_of(self, balls: IntArray) -> IntArray:
        """The index (into state_names) of each of `balls`' motion state."""

    def edge_times(
        self, balls: IntArray, skip: Skips, starts: IntArray
    ) -> tuple[FloatArray, IntArray]:
        """Each ball's next edge contact: absolute time and edge (walls 0-3, jaws, capture
        lines; ties to the lower). starts: each run's first among `balls` (per-run reach)."""

    def pair_times(
        self, pairs: Pairs, now: FloatArray, ends: FloatArray, parting: bool, runs: IntArray
    ) -> FloatArray:
        """Each pair's (of one run) next contact after its run's `now`, inf if none before
        `ends` (every row's next edge or state change). parting: only a return counts."""

    def latest_stop(self, run: int) -> float:
        """When the run's last ball comes to rest (or its latest state ends)."""

    def latest_stops(self, runs: IntArray) -> FloatArray: ...

    def recorded(
        self, setup: Setup, balls: IntArray, rows: FloatArray, count: int
    ) -> AnchoredMotion:
        """The run's (of `setup`) motion from every logged anchor: balls (S,), rows (S, C)."""


def motion_law(setups: Sequence[Setup]) -> MotionLaw:
    """The motion law (setup.model) of a batch of setups that share it, unanchored."""
    setup = setups[0]
    if setup.model not in MOTION_LAWS:
        raise ValueError(f"unknown model {setup.model!r}; expected one of {', '.join(MOTION_LAWS)}")
    module, name = MOTION_LAWS[setup.model].split(":")
    law: MotionLaw = getattr(importlib.import_module(module), name)(setups)
    return law


def run_rows(
    runs: IntArray, now: FloatArray, first: IntArray, second: IntArray, count: int
) -> tuple[IntArray | slice, float | FloatArray, IntArray, IntArray, IntArray | None]:
    """For pairs of `runs` (ascending, each once) at their times `now`: those runs' balls
    (a slice where consecutive), their time (one a ball, or the one run's), each pair's
    balls' rows among them, and each pair's run's index into `runs` (None: one run)."""
    low, high = int(runs[0]), int(runs[-1]) + 1
    if len(runs) == 1:
        start = low * count
        return slice(start, start + count), float(now[0]), first - start, second - start, None
    if high - low == len(runs):
        balls: IntArray | slice = slice(low * count, high * count)
        slot = first // count - low
    else:
        balls = (runs[:, None] * count + np.arange(count)).ravel()
        slot = np.searchsorted(runs, first // count)
    base = slot * count
    return balls, np.repeat(now, count), base + first % count, base + second % count, slot


def per_pair(values: FloatArray, slot: IntArray | None) -> float | FloatArray:
    """A per-run quantity for each pair (run_rows' slot), or the one run's."""
    return float(values[0]) if slot is None else values[slot]


def ball_count(setups: Sequence[Setup]) -> int:
    """N, the balls a run of a batch: the most any of its runs has."""
    return max(len(setup.positions) for setup in setups)


def padded_positions(setups: Sequence[Setup], count: int) -> FloatArray:
    """Every run's starting positions, `count` rows a run (R N, 2), padded at the origin."""
    positions = np.zeros((len(setups), count, 2))
    for run, setup in enumerate(setups):
        positions[run, : len(setup.positions)] = setup.positions
    return positions.reshape(-1, 2)


def row_constant(setups: Sequence[Setup], count: int, name: str) -> Constant:
    """A Setup's constant `name` in a batch: the one number where all runs share it,
    else each row's run's (R count,)."""
    values = [float(getattr(setup, name)) for setup in setups]
    if all(each == values[0] for each in values):
        return values[0]
    return np.repeat(np.array(values), count)


def row_bounds(setups: Sequence[Setup], count: int) -> FloatArray:
    """The cushion lines (Setup.bounds): (4,) where all runs share them, else (R N, 4)."""
    bounds = np.array([setup.bounds for setup in setups])
    if (bounds == bounds[0]).all():
        return bounds[0]
    return np.repeat(bounds, count, axis=0)
