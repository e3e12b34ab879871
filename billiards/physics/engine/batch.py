"""A batch of runs (docs/batch.md): the calendar's arrays for many runs at once, ball b
of run r at row r N + b, so that numpy's fixed cost a call is paid once a pass for all.
Each pass picks every unfinished run's next event by the tie rule (`select`), resolves
the plain ones of all runs over rows (calendar.resolve_pairs, resolve_cushions,
resolve_changes: `queue_rows`) and the others by each run's calendar (`queue`), then
anchors all queued balls and asks their edge and pair times in one call each (`flush`).

Nothing reduces across runs (every argmin, largest coordinate or fastest speed is one
run's), so run i gives the same bits in any batch as alone; a single run is a batch of
one. Constants are one number where all runs share it, else a value a row; a run with
fewer balls is padded with balls at rest at the origin, gone from the start. The model,
the laws and whether the table has pockets are code, not numbers: they split a batch
(`shape_of`); `naive` runs outside batches.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, fields
from enum import IntEnum
from functools import lru_cache
from itertools import accumulate

import numpy as np

from billiards.physics.engine.batch_log import BatchLog
from billiards.physics.engine.motion_law import MotionLaw, motion_law, row_bounds, row_constant
from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.arithmetic import at_rows, norm
from billiards.physics.numerics.arrays import Constant, FloatArray, IntArray, Kinematics


class NextKind(IntEnum):
    """What a run's next event is (Batch.next_kind), in the tie rule's order at one
    instant: a motion-state change, then an edge contact, then a pair contact."""

    CHANGE = 0
    EDGE = 1
    PAIR = 2


def shape_of(setup: Setup) -> Hashable:
    """What runs of one batch share: the motion model, the contact laws, and whether
    the table has pockets (the module's docstring says why)."""
    return (setup.model, setup.ball_law, setup.cushion_law, setup.pockets is None)


@dataclass(frozen=True)
class RunConstants:
    """The constants calendar.resolve_pairs and resolve_cushions read: each the one
    number where every run shares it (no gather), else one value a run (R,)."""

    bounds: FloatArray  # (4,) where every run shares them, else (R, 4)
    radius: Constant
    retention: Constant
    cushion_restitution: Constant
    cushion_friction: Constant
    cushion_height: Constant
    sliding_friction: Constant
    cushion_restitution_speed: Constant
    restitution: Constant

    @classmethod
    def start(cls, setups: Sequence[Setup]) -> RunConstants:
        return cls(row_bounds(setups, 1), *(row_constant(setups, 1, name) for name in _NUMBERS))

    def of(self, runs: IntArray) -> RunConstants:
        """The constants of `runs`, a row each (the one number where all share it)."""
        bounds = self.bounds if self.bounds.ndim == 1 else self.bounds[runs]
        return RunConstants(bounds, *(at_rows(getattr(self, name), runs) for name in _NUMBERS))


_NUMBERS = [field.name for field in fields(RunConstants)][1:]  # all but the bounds


@dataclass
class _Anchoring:
    """One run's re-anchoring, queued until the pass's flush."""

    run: int
    balls: IntArray  # the run's own indices
    time: float
    kinematics: Kinematics
    skip: tuple[int, int] | None  # (ball, edge) the ball ignores, of the run's own
    transitions: tuple[int, ...]  # balls whose new motion state is logged after


@dataclass
class _Rows:
    """Many runs' re-anchorings, queued at once by a resolution over rows."""

    runs: IntArray  # (k,), each once
    balls: IntArray  # (k, m): each run's own indices
    times: FloatArray  # (k,)
    kinematics: Kinematics  # positions, velocities, spins: (k, m, 2 | 2 | 3)
    transitions: bool  # every ball's new motion state is logged after


class Batch:
    """The shared arrays of R runs of N balls that share a shape (shape_of)."""

    def __init__(self, setups: Sequence[Setup]) -> None:
        self.setups = setups
        self.runs = len(setups)
        self.law: MotionLaw = motion_law(setups)
        count = self.count = self.law.count
        rows = self.runs * count
        self.constants = RunConstants.start(setups)
        self.edge_time = np.full(rows, np.inf)
        self.edge = np.zeros(rows, dtype=np.intp)
        # pair_time[r, i, j] for i < j of run r; the rest stays inf.
        self.pair_time = np.full((self.runs, count, count), np.inf)
        # Pocketed, or a run's padding (its rows past its own balls): out of every pair.
        self.gone = np.zeros(rows, dtype=bool)
        # Each ball's latest ball-ball contact (calendar: the TC rule), and its mass.
        self.contact_time = np.full(rows, -np.inf)
        # The fastest any ball of a run has gone: the scale of its velocities' rounding.
        self.speed_scale = np.zeros(self.runs)
        self.log = BatchLog(self.runs)
        self.event_count = np.zeros(self.runs, dtype=np.intp)  # contacts resolved
        # Each run's next event, as `select` last found it: 0 a state change, 1 an
        # edge, 2 a pair; the ball or flat pair index; the time. fresh: still current.
        self.next_kind = np.zeros(self.runs, dtype=np.intp)
        self.next_index = np.zeros(self.runs, dtype=np.intp)
        self.next_time = np.full(self.runs, np.inf)
        self.fresh = np.zeros(self.runs, dtype=bool)
        # When each run's last ball stops (law.latest_stops), and its next event's balls'
        # positions, velocities, spins and accelerations at its time (rows of 2).
        self.stops = np.zeros(self.runs)
        self.with_stops = False  # whether select finds them (a stepping method asks)
        self.dynamics = tuple(np.zeros((self.runs, 2, size)) for size in (2, 2, 3, 2))
        self._queued: list[_Anchoring] = []
        self._queued_rows: list[_Rows] = []
        self._queued_runs: set[int] = set()
        masses = np.ones((self.runs, count))
        for run, setup in enumerate(setups):
            own = len(setup.positions)
            masses[run, :own] = setup.masses
            self.gone[run * count + own : (run + 1) * count] = True
            spins = np.zeros((own, 3)) if setup.spins is None else setup.spins
            start = (setup.positions, setup.velocities, spins)
            positions, velocities, spins = (np.array(part, dtype=np.float64) for part in start)
            self.queue(run, np.arange(own), 0.0, (positions, velocities, spins))
        self.masses = masses.reshape(-1)
        # Whether a pair's entry may have a gone ball: then it is never.
        self.goes = bool(self.gone.any()) or setups[0].pockets is not None
        self.flush()

    # -- the next event of every run ----------------------------------------------------

    def select(self, runs: IntArray) -> None:
        """Each of `runs`' next event by the tie rule: state changes before edges before
        pairs at one instant, each the lowest index (argmin's first minimum)."""
        if len(runs) == 1:
            self._select_one(int(runs[0]))
            return
        count = self.count
        entries = (self.law.change_time, self.edge_time, self.pair_time)
        tables = [values.reshape(self.runs, -1) for values in entries]
        if len(runs) < self.runs:  # else the tables themselves, not copies
            tables = [table[runs] for table in tables]
        every = np.arange(len(runs))
        # Each kind's first entry (the lowest index), then the earliest kind; argmin's
        # first minimum is the tie rule's order: a state change, an edge, a pair.
        index = np.empty((len(runs), 3), dtype=np.intp)
        times = np.empty((len(runs), 3))
        for column, table in enumerate(tables):
            first = table.argmin(axis=1)
            index[:, column] = first
            times[:, column] = table[every, first]  # the least entry: at that index
        kind = times.argmin(axis=1)
        time = times[every, kind]
        self.next_kind[runs] = kind
        self.next_index[runs] = index[every, kind]
        self.next_time[runs] = time
        if self.with_stops:
            self.stops[runs] = self.law.latest_stops(runs)
        self.fresh[runs] = True
        # The balls of each edge or pair event (an edge's twice) at its time, for all at
        # once: each run's resolution starts from these.
        contact = ((kind != NextKind.CHANGE) & np.isfinite(time)).nonzero()[0]
        if contact.size == 0:
            return
        flat, edge_ball = index[contact, 2], index[contact, 1]
        edges = kind[contact] == NextKind.EDGE
        base = runs[contact] * count
        balls = np.empty((len(contact), 2), dtype=np.intp)
        balls[:, 0] = base + np.where(edges, edge_ball, flat // count)
        balls[:, 1] = base + np.where(edges, edge_ball, flat % count)
        dynamics = self.law.state_at(balls.reshape(-1), np.repeat(time[contact], 2))
        chosen = runs[contact]
        for kept, found in zip(self.dynamics, dynamics, strict=True):
            kept[chosen] = found.reshape(len(contact), 2, -1)

    def _select_one(self, run: int) -> None:
        """select for one run, on Python numbers (a run alone pays per numpy call)."""
        count = self.count
        own = slice(run * count, (run + 1) * count)
        change, edge = self.law.change_time[own], self.edge_time[own]
        pair = self.pair_time[run].reshape(-1)
        change_ball, edge_ball, flat = int(change.argmin()), int(edge.argmin()), int(pair.argmin())
        change_time, edge_time = float(change[change_ball]), float(edge[edge_ball])
        pair_time = float(pair[flat])
        if change_time <= edge_time and change_time <= pair_time:
            kind, index, time = NextKind.CHANGE, change_ball, change_time
        elif edge_time <= pair_time:
            kind, index, time = NextKind.EDGE, edge_ball, edge_time
        else:
            kind, index, time = NextKind.PAIR, flat, pair_time
        self.next_kind[run], self.next_index[run], self.next_time[run] = kind, index, time
        if self.with_stops:
            self.stops[run] = self.law.latest_stop(run)
        self.fresh[run] = True
        if kind == NextKind.CHANGE or time == math.inf:
            return
        base = run * count
        balls = (
            [base + index] * 2
            if kind == NextKind.EDGE
            else [base + flat // count, base + flat % count]
        )
        dynamics = self.law.state_at(np.array(balls), time)
        for kept, found in zip(self.dynamics, dynamics, strict=True):
            kept[run] = found

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
        """Re-anchor a run's `balls` at `time` (skip: a (ball, edge) ignored) at the next
        flush, one per run a pass (a second flushes the first); log `transitions`' states."""
        if run in self._queued_runs:
            self.flush()
        self._queued.append(_Anchoring(run, balls, time, kinematics, skip, transitions))
        self._queued_runs.add(run)
        self.fresh[run] = False

    def queue_rows(
        self,
        runs: IntArray,
        balls: IntArray,
        times: FloatArray,
        kinematics: Kinematics,
        transitions: bool = False,
    ) -> None:
        """queue for many `runs` (each once, none queued yet this pass), a row of balls
        each; `transitions`: log every ball's new motion state after."""
        if len(runs) == 0:
            return
        self._queued_rows.append(_Rows(runs, balls, times, kinematics, transitions))
        self._queued_runs.update(runs.tolist())
        self.fresh[runs] = False

    def flush(self) -> None:
        """Anchor every queued ball, log its rows, and recompute its edge entry and the
        entries of every pair of its run that it is in."""
        queued, queued_rows = self._queued, self._queued_rows
        if not queued and not queued_rows:
            return
        self._queued, self._queued_rows = [], []
        self._queued_runs = set()
        count, law = self.count, self.law
        alone = len(queued) == 1 and not queued_rows  # a run alone: nothing to join
        times: float | FloatArray
        if alone:
            item = queued[0]
            entry_runs, sizes, starts = (
                np.array([item.run]),
                [len(item.balls)],
                np.zeros(1, np.intp),
            )
            local, times, kinematics = item.balls, item.time, item.kinematics
        else:
            entry_runs, sizes, starts, local, times, kinematics = _joined(queued, queued_rows)
        balls = local + item.run * count if alone else local + np.repeat(entry_runs * count, sizes)
        rows = law.anchor(balls, times, kinematics)
        speeds = norm(rows[:, 3:5])
        if alone:
            run = item.run
            self.speed_scale[run] = max(self.speed_scale[run], speeds.max())
        else:
            fastest = np.maximum.reduceat(speeds, starts)
            self.speed_scale[entry_runs] = np.maximum(self.speed_scale[entry_runs], fastest)
        run_of_ball = np.full(len(local), item.run) if alone else np.repeat(entry_runs, sizes)
        self.log.segments(run_of_ball, local, rows)
        # The balls that ignore an edge (from a run's own resolution: its first entries).
        skipping = [
            start + int((item.balls == item.skip[0]).nonzero()[0][0])
            for item, start in zip(queued, starts.tolist(), strict=False)
            if item.skip is not None
        ]
        skip = None
        if skipping:
            mask = np.zeros(len(balls), dtype=bool)
            mask[skipping] = True
            edges = np.zeros(len(balls), dtype=np.intp)
            edges[skipping] = [item.skip[1] for item in queued if item.skip is not None]
            skip = (mask, edges)
        self.edge_time[balls], self.edge[balls] = law.edge_times(balls, skip, starts)
        # Every pair of a run that a re-anchored ball is in, once: the ball against each
        # ball of its run not re-anchored, and against the re-anchored ones above it
        # (each pair's time is its own, whatever else is asked with it).
        if alone:  # the few sets it asks for, kept
            lower, higher = _pairs_with(count, tuple(item.balls.tolist()))
            first, second = lower + item.run * count, higher + item.run * count
            ranked, now = entry_runs, np.array([item.time])
        else:
            partner = (balls - balls % count)[:, None] + np.arange(count)
            anchored = np.zeros(len(self.gone), dtype=bool)
            anchored[balls] = True
            once = ~anchored[partner] | (balls[:, None] < partner)
            ball = np.repeat(balls, count)[once.reshape(-1)]
            partner = partner[once]
            first, second = np.minimum(ball, partner), np.maximum(ball, partner)
            # law.pair_times wants each run once, ascending.
            order = np.lexsort((entry_runs,))
            ranked, now = entry_runs[order], np.asarray(times)[starts[order]]
        if self.goes:
            # A pair with a gone ball (pocketed, or a run's padding) is never: asked for
            # none (each pair's time is its own: the others' are the same without it).
            live = ~(self.gone[first] | self.gone[second])
            found = np.full(len(first), np.inf)
            if live.any():
                found[live] = law.pair_times(
                    (first[live], second[live]), now, self.edge_time, False, ranked
                )
        else:
            found = law.pair_times((first, second), now, self.edge_time, False, ranked)
        self.pair_time.reshape(-1)[first * count + second % count] = found
        self._log_transitions(queued, queued_rows)

    def _log_transitions(self, queued: list[_Anchoring], queued_rows: list[_Rows]) -> None:
        """Log the new motion states of the balls whose resolution asked for it."""
        count = self.count
        singles = [(item.run, item.time, ball) for item in queued for ball in item.transitions]
        chunks = [
            (
                np.repeat(chunk.runs, chunk.balls.shape[1]),
                np.repeat(chunk.times, chunk.balls.shape[1]),
                chunk.balls.reshape(-1),
            )
            for chunk in queued_rows
            if chunk.transitions
        ]
        if singles:
            runs, times, balls = zip(*singles, strict=True)
            chunks.append((np.array(runs), np.array(times), np.array(balls, dtype=np.intp)))
        for runs_of, times_of, local in chunks:
            self.log.transitions(
                runs_of, times_of, local, self.law.states_of(runs_of * count + local)
            )


def _joined(
    queued: list[_Anchoring], queued_rows: list[_Rows]
) -> tuple[IntArray, list[int], IntArray, IntArray, FloatArray, Kinematics]:
    """The queued entries joined, the runs' own resolutions first."""
    runs = [np.array([item.run for item in queued], dtype=np.intp)]
    sizes = [len(item.balls) for item in queued]
    local = [item.balls for item in queued]
    times = [np.repeat([item.time for item in queued], sizes)]
    parts: list[list[FloatArray]] = [
        [item.kinematics[part] for item in queued] for part in range(3)
    ]
    for chunk in queued_rows:
        width = chunk.balls.shape[1]
        runs.append(chunk.runs)
        sizes.extend([width] * len(chunk.runs))
        local.append(chunk.balls.reshape(-1))
        times.append(np.repeat(chunk.times, width))
        for part in range(3):
            values = chunk.kinematics[part]
            parts[part].append(values.reshape(-1, values.shape[-1]))
    starts = np.array([0, *accumulate(sizes[:-1])], dtype=np.intp)
    positions, velocities, spins = (np.concatenate(part) for part in parts)
    return (
        np.concatenate(runs),
        sizes,
        starts,
        np.concatenate(local).astype(np.intp),
        np.concatenate(times),
        (positions, velocities, spins),
    )


@lru_cache(maxsize=4096)
def _pairs_with(count: int, balls: tuple[int, ...]) -> tuple[IntArray, IntArray]:
    """Every pair (lower, higher) of `count` balls with one of `balls` in it, once."""
    if len(balls) == count:
        return np.triu_indices(count, k=1)
    others = np.ones(count, dtype=bool)
    firsts = []
    seconds = []
    for ball in balls:
        others[ball] = False
        partner = others.nonzero()[0]  # skips balls of the set already paired
        firsts.append(np.minimum(partner, ball))
        seconds.append(np.maximum(partner, ball))
    return np.concatenate(firsts), np.concatenate(seconds)
