"""A batch of runs: the calendar's arrays for many runs at once, each run's next event
picked in one pass, and every re-anchoring of a pass computed in one set of calls.

A break is chaotic, so users run many (billiards.simulation.simulate_batch). Run alone,
a run pays numpy's fixed cost per call on arrays of a few balls; most of that cost is
asking the re-anchored balls' new edge and pair times. Here the runs' balls sit in one
set of arrays, ball b of run r at row r N + b (billiards.physics.motion_law), and each
pass:

1. picks every unfinished run's next event by the calendar's tie rule (`select`: an
   argmin per run over its own rows);
2. lets each run's calendar resolve it (billiards.physics.calendar: the contact laws
   and the rounding rules, one run at a time), which queues the balls it re-anchors;
3. anchors all queued balls, then asks their edge times and their pairs' times in one
   call each (`flush`).

Nothing reduces across runs: every reduction (the argmins, the run's largest
coordinate, its fastest speed) is over one run's rows, and every other operation is
elementwise, so run i gives the same bits in any batch as alone. A single run is a
batch of one: there is no other path.

Runs batch together only if they share the motion law's constants (`shape_of`): the
ball count, the model, the laws and every physical constant; they differ in their
balls' positions, velocities, spins and masses. billiards.physics.stepper.run_batch
splits a mixed batch into such groups.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass, field, fields
from itertools import accumulate

import numpy as np

from billiards.physics.arithmetic import norm
from billiards.physics.motion import FloatArray, IntArray, Kinematics
from billiards.physics.motion_law import MotionLaw, motion_law
from billiards.physics.setup import Setup

# A setup's own balls: what may differ between runs of one batch.
_PER_RUN = {"positions", "velocities", "masses", "spins"}


def shape_of(setup: Setup) -> Hashable:
    """What runs of one batch share: every constant of the setup and its ball count."""
    constants: list[Hashable] = [len(setup.positions)]
    for item in fields(setup):
        if item.name in _PER_RUN:
            continue
        value = getattr(setup, item.name)
        if item.name == "pockets" and value is not None:  # laid out from these alone
            value = (
                value.table_size,
                value.radius,
                value.corner_width,
                value.side_width,
                value.jaw_radius,
            )
        constants.append(value)
    return tuple(constants)


@dataclass
class ContactLog:
    """What happened in one run: contacts that changed velocities, motion-state
    changes, and every anchor (path segment) as the motion law's rows."""

    times: list[float] = field(default_factory=list)
    kinds: list[str] = field(default_factory=list)
    balls: list[tuple[int, ...]] = field(default_factory=list)
    impact_speeds: list[float] = field(default_factory=list)
    pockets: list[str | None] = field(default_factory=list)  # the pocket, where one
    transitions: list[tuple[float, int, int]] = field(default_factory=list)  # t, ball, state
    segment_balls: list[IntArray] = field(default_factory=list)
    segment_rows: list[FloatArray] = field(default_factory=list)

    def contact(
        self, time: float, kind: str, balls: tuple[int, ...], speed: float, pocket: str | None
    ) -> None:
        self.times.append(time)
        self.kinds.append(kind)
        self.balls.append(balls)
        self.impact_speeds.append(speed)
        self.pockets.append(pocket)


@dataclass
class _Anchoring:
    """One run's re-anchoring, queued until the pass's flush."""

    run: int
    balls: IntArray  # the run's own indices
    time: float
    kinematics: Kinematics
    skip: tuple[int, int] | None  # (ball, edge) the ball ignores, of the run's own
    transitions: tuple[int, ...]  # balls whose new motion state is logged after


class Batch:
    """The shared arrays of R runs of N balls that share a shape (shape_of)."""

    def __init__(self, setups: Sequence[Setup]) -> None:
        self.setups = setups
        self.runs = len(setups)
        self.law: MotionLaw = motion_law(setups)
        count = self.count = self.law.count
        rows = self.runs * count
        self.edge_time = np.full(rows, np.inf)
        self.edge = np.zeros(rows, dtype=np.intp)
        # pair_time[r, i, j] for i < j of run r; the rest stays inf.
        self.pair_time = np.full((self.runs, count, count), np.inf)
        self.gone = np.zeros(rows, dtype=bool)  # pocketed: out of every pair
        # The fastest any ball of a run has gone: the scale of its velocities' rounding.
        self.speed_scale = np.zeros(self.runs)
        self.logs = [ContactLog() for _ in setups]
        # Each run's next event, as `select` last found it: 0 a state change, 1 an
        # edge, 2 a pair; the ball or flat pair index; the time. fresh: still current.
        self.next_kind = np.zeros(self.runs, dtype=np.intp)
        self.next_index = np.zeros(self.runs, dtype=np.intp)
        self.next_time = np.full(self.runs, np.inf)
        self.fresh = np.zeros(self.runs, dtype=bool)
        # When each run's last ball stops (law.latest_stops), and its next event's balls'
        # positions, velocities, spins and accelerations at its time (rows of 2).
        self.stops = np.zeros(self.runs)
        self.dynamics = tuple(np.zeros((self.runs, 2, size)) for size in (2, 2, 3, 2))
        self._queued: list[_Anchoring] = []
        self._queued_runs: set[int] = set()
        self._pairs: dict[tuple[int, ...], tuple[IntArray, IntArray]] = {}
        for run, setup in enumerate(setups):
            spins = (
                np.zeros((count, 3))
                if setup.spins is None
                else np.asarray(setup.spins, dtype=np.float64)
            )
            kinematics = (
                np.array(setup.positions, dtype=np.float64),
                np.asarray(setup.velocities, dtype=np.float64),
                spins,
            )
            self.queue(run, np.arange(count), 0.0, kinematics)
        self.flush()

    # -- the next event of every run ----------------------------------------------------

    def select(self, runs: IntArray) -> None:
        """Each of `runs`' next event by the tie rule: state changes before edges before
        pairs at one instant, each the lowest index (argmin's first minimum)."""
        count = self.count
        change = self.law.change_time.reshape(self.runs, count)[runs]
        edge = self.edge_time.reshape(self.runs, count)[runs]
        pair = self.pair_time.reshape(self.runs, count * count)[runs]
        every = np.arange(len(runs))
        change_ball = change.argmin(axis=1)
        edge_ball = edge.argmin(axis=1)
        flat = pair.argmin(axis=1)
        change_time = change[every, change_ball]
        edge_time = edge[every, edge_ball]
        pair_time = pair[every, flat]
        first = (change_time <= edge_time) & (change_time <= pair_time)
        second = ~first & (edge_time <= pair_time)
        self.next_kind[runs] = np.where(first, 0, np.where(second, 1, 2))
        self.next_index[runs] = np.where(first, change_ball, np.where(second, edge_ball, flat))
        time = np.where(first, change_time, np.where(second, edge_time, pair_time))
        self.next_time[runs] = time
        self.stops[runs] = self.law.latest_stops(runs)
        # The event's balls (an edge's or a change's twice) at its time, for all at once:
        # each run's resolution starts from these (a run with no event: its start).
        lower, higher = flat // count, flat % count
        base = runs * count
        one = np.where(first, change_ball, edge_ball)
        balls = base[:, None] + np.stack(
            (np.where(first | second, one, lower), np.where(first | second, one, higher)), axis=1
        )
        at = np.repeat(np.where(np.isfinite(time), time, 0.0), 2)
        dynamics = self.law.state_at(balls.reshape(-1), at)
        for kept, found in zip(self.dynamics, dynamics, strict=True):
            kept[runs] = found.reshape(len(runs), 2, -1)
        self.fresh[runs] = True

    # -- re-anchoring ---------------------------------------------------------------------

    def queue(
        self,
        run: int,
        balls: IntArray,
        time: float,
        kinematics: Kinematics,
        skip: tuple[int, int] | None = None,
        transitions: tuple[int, ...] = (),
    ) -> None:
        """Re-anchor a run's `balls` at `time` at the next flush (one per run a pass:
        a second one flushes the first)."""
        if run in self._queued_runs:
            self.flush()
        self._queued.append(_Anchoring(run, balls, time, kinematics, skip, transitions))
        self._queued_runs.add(run)
        self.fresh[run] = False

    def flush(self) -> None:
        """Anchor every queued ball, log its rows, and recompute its edge entry and the
        entries of every pair of its run that it is in."""
        queued = self._queued
        if not queued:
            return
        self._queued = []
        self._queued_runs = set()
        count = self.count
        law = self.law
        sizes = [len(item.balls) for item in queued]
        starts = np.array([0, *accumulate(sizes[:-1])], dtype=np.intp)
        bases = np.array([item.run * count for item in queued])
        balls = np.concatenate([item.balls for item in queued]) + np.repeat(bases, sizes)
        times = np.repeat([item.time for item in queued], sizes)
        kinematics = tuple(
            np.concatenate([item.kinematics[part] for item in queued]) for part in range(3)
        )
        rows = law.anchor(balls, times, (kinematics[0], kinematics[1], kinematics[2]))
        speeds = np.maximum.reduceat(norm(rows[:, 3:5]), starts)
        runs = np.array([item.run for item in queued])
        self.speed_scale[runs] = np.maximum(self.speed_scale[runs], speeds)
        for item, start, size in zip(queued, starts.tolist(), sizes, strict=True):
            log = self.logs[item.run]
            log.segment_balls.append(item.balls)
            log.segment_rows.append(rows[start : start + size])
        skipping = [
            start + int((item.balls == item.skip[0]).nonzero()[0][0])
            for item, start in zip(queued, starts.tolist(), strict=True)
            if item.skip is not None
        ]
        skip = None
        if skipping:
            mask = np.zeros(len(balls), dtype=bool)
            mask[skipping] = True
            edges = np.zeros(len(balls), dtype=np.intp)
            edges[skipping] = [item.skip[1] for item in queued if item.skip is not None]
            skip = (mask, edges)
        found, edges = law.edge_times(balls, skip, starts)
        self.edge_time[balls] = found
        self.edge[balls] = edges
        firsts = []
        seconds = []
        for item, base in zip(queued, bases.tolist(), strict=True):
            lower, higher = self._pairs_with(item.balls)
            firsts.append(lower + base)
            seconds.append(higher + base)
        first = np.concatenate(firsts)
        second = np.concatenate(seconds)
        # The pairs come run by run; law.pair_times wants each run once, ascending.
        order = sorted(range(len(queued)), key=lambda place: queued[place].run)
        ranked = runs[order]
        now = np.array([queued[place].time for place in order])
        found = law.pair_times((first, second), now, self.edge_time, False, ranked)
        if self.setups[0].pockets is not None:
            found[self.gone[first] | self.gone[second]] = np.inf
        self.pair_time.reshape(-1)[first * count + second % count] = found
        for item in queued:
            for ball in item.transitions:
                state = law.state_of(item.run * count + ball)
                self.logs[item.run].transitions.append((item.time, ball, state))

    def _pairs_with(self, balls: IntArray) -> tuple[IntArray, IntArray]:
        """Every pair (lower, higher index) of a run with at least one of `balls` in it,
        once (kept: the same few sets come back all the time)."""
        key = tuple(balls.tolist())
        pairs = self._pairs.get(key)
        if pairs is None:
            pairs = self._pairs[key] = _pairs_with(balls, self.count)
        return pairs


def _pairs_with(balls: IntArray, count: int) -> tuple[IntArray, IntArray]:
    """Every pair (lower, higher index) with at least one of `balls` in it, once."""
    if len(balls) == count:
        return np.triu_indices(count, k=1)
    firsts = []
    seconds = []
    others = np.ones(count, dtype=bool)
    for ball in balls.tolist():
        others[ball] = False
        partner = others.nonzero()[0]  # skips balls of the set already paired
        firsts.append(np.minimum(partner, ball))
        seconds.append(np.maximum(partner, ball))
    return np.concatenate(firsts), np.concatenate(seconds)
