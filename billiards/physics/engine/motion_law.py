"""What the calendar asks of a motion model, and the registry of models by name.

A motion law holds every ball's anchor (its state just after its last event) and
answers, in closed form, where the balls are at any time and when they next meet an
edge of the table (a cushion, a jaw, a capture line), each other, or the end of their
own motion state. The calendar (billiards.physics.engine.calendar) owns everything else: the
order of events, the contact laws, the rounding rules, the log. A new model is one
module with a class of this shape and one entry in MOTION_LAWS.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
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

# Model name -> "module:class"; imported on first use, so a rolling run loads none of
# the spin model.
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
    row r N + b (N balls a run: the most any run has; a run with fewer has its last
    rows padded with balls at rest at the origin, gone from the start). Every constant
    the law reads is one number where all runs share it, else one a row
    (`row_constant`)."""

    count: int  # N

    # When each ball's motion state ends by itself (N,), inf where nothing ends it:
    # the calendar's third kind of event, besides edge and pair contacts.
    change_time: FloatArray
    state_names: tuple[str, ...]  # by the state indices of transitions

    def state_at(self, balls: IntArray, time: float | FloatArray) -> Dynamics:
        """Positions (k, 2), velocities (k, 2), spins (k, 3) and accelerations (k, 2)
        of `balls` at `time` (one, or one a ball)."""
        ...

    def anchor(
        self, balls: IntArray, time: float | FloatArray, kinematics: Kinematics
    ) -> FloatArray:
        """Re-anchor `balls` at `time` (one, or one a ball) with these positions,
        velocities and spins; returns their anchored rows (k, C) for the log (t0, p0, v0
        and the model's own columns; v0 in columns 3-4)."""
        ...

    def state_changes(self, balls: IntArray, times: float | FloatArray) -> Kinematics:
        """The start of each of `balls`' next motion state at its change_time, `times`
        (one, or one a ball): positions, velocities and spins to anchor it with."""
        ...

    def slipping(self, balls: IntArray) -> BoolArray:
        """Which balls slide: their acceleration comes from a slip that can press them
        into what they touch (laws.held)."""
        ...

    def states_of(self, balls: IntArray) -> IntArray:
        """The index (into state_names) of each of `balls`' motion state."""
        ...

    def edge_times(
        self, balls: IntArray, skip: Skips, starts: IntArray
    ) -> tuple[FloatArray, IntArray]:
        """Each ball's next edge contact: absolute time and edge index (0-3 the cushion
        walls, then the jaws, then the capture lines; ties to the lower index). skip:
        balls that ignore an edge. starts: where each run's balls begin among `balls`
        (they come run by run): what is reduced over the balls asked is reduced per run."""
        ...

    def pair_times(
        self, pairs: Pairs, now: FloatArray, ends: FloatArray, parting: bool, runs: IntArray
    ) -> FloatArray:
        """Each pair's (pairs: first and second rows, (M,) each, both of one run) next
        contact after its run's time, or inf if none before either ball is re-anchored
        (its next edge contact, `ends` (all rows), or state change). runs: the pairs'
        runs, ascending, each once; now: their times. parting: the pairs touch now with
        a contact judged none; only their return after parting counts."""
        ...

    def latest_stop(self, run: int) -> float:
        """When the run's last ball comes to rest (or its latest state ends)."""
        ...

    def latest_stops(self, runs: IntArray) -> FloatArray:
        """latest_stop of each of `runs`."""
        ...

    def recorded(
        self, setup: Setup, balls: IntArray, rows: FloatArray, count: int
    ) -> AnchoredMotion:
        """The run's (of `setup`) motion from every logged anchor: balls (S,), rows (S, C)."""
        ...


def motion_law(setups: Sequence[Setup]) -> MotionLaw:
    """The motion law (setup.model, a name in MOTION_LAWS) of a batch of setups that
    share it (billiards.physics.engine.batch.shape_of), balls unanchored."""
    setup = setups[0]
    if setup.model not in MOTION_LAWS:
        raise ValueError(f"unknown model {setup.model!r}; expected one of {', '.join(MOTION_LAWS)}")
    module, name = MOTION_LAWS[setup.model].split(":")
    law: MotionLaw = getattr(importlib.import_module(module), name)(setups)
    return law


def run_rows(
    runs: IntArray, now: FloatArray, first: IntArray, second: IntArray, count: int
) -> tuple[IntArray | slice, float | FloatArray, IntArray, IntArray, IntArray | None]:
    """For pairs of the runs `runs` (ascending, each once) at their times `now`: every
    ball of those runs (rows; a slice where the runs are consecutive), their time (one
    a ball, or the one run's), the rows among them of each pair's first and second ball,
    and each pair's run as an index into `runs` (None for one run: every pair's)."""
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
    """Every run's starting positions, `count` rows a run (R N, 2): a run with fewer
    balls padded with balls at the origin (at rest, and gone: batch.Batch)."""
    positions = np.zeros((len(setups), count, 2))
    for run, setup in enumerate(setups):
        positions[run, : len(setup.positions)] = setup.positions
    return positions.reshape(-1, 2)


def row_constant(setups: Sequence[Setup], count: int, value: Callable[[Setup], float]) -> Constant:
    """A constant of every run of a batch: the one number where all share it (as a run
    alone has it), else its run's value for every row (R N,)."""
    values = [float(value(setup)) for setup in setups]
    if all(each == values[0] for each in values):
        return values[0]
    return np.repeat(np.array(values), count)


def row_bounds(setups: Sequence[Setup], count: int) -> FloatArray:
    """The cushion lines (Setup.bounds): (4,) where all runs share them, else every
    row's run's (R N, 4)."""
    bounds = np.array([setup.bounds for setup in setups])
    if (bounds == bounds[0]).all():
        return bounds[0]
    return np.repeat(bounds, count, axis=0)
