"""The numpy engine's stepper: run setups to rest, event by event (`event`) or on a grid
of steps too (`exact`), and package the results; runs of one shape go through one batch
(engine.batch), a single run a batch of one. (billiards.physics.methods chooses the
engine for each run.)"""

from __future__ import annotations

import gc
from collections.abc import Hashable, Iterator
from contextlib import contextmanager

import numpy as np

from billiards.physics.engine.batch import Batch, NextKind, shape_of
from billiards.physics.engine.batch_log import ContactLog
from billiards.physics.engine.calendar import (
    Calendar,
    resolve_changes,
    resolve_cushions,
    resolve_pairs,
)
from billiards.physics.engine.packaging import Run, package
from billiards.physics.engine.result import (
    SimulationResult,
    keep_final_positions,
)
from billiards.physics.numerics.arrays import BoolArray, FloatArray, IntArray


def run_engine(items: list[Run]) -> list[SimulationResult | Exception]:
    """Each exact run's result (event or exact) by the numpy engine, in order, or the
    exception it raised (a failing run fails alone): runs that share a shape
    (batch.shape_of) through one batch, pass by pass."""
    results: list[SimulationResult | Exception | None] = [None] * len(items)
    groups: dict[Hashable, list[int]] = {}
    for index, (setup, *_) in enumerate(items):
        try:
            key = shape_of(setup)
        except Exception as error:  # the run's outcome, not the batch's
            results[index] = error
            continue
        groups.setdefault(key, []).append(index)
    for indices in groups.values():
        with _no_cycle_collection():
            driven = _drive([items[i] for i in indices])
        for index, result in zip(indices, driven, strict=True):
            results[index] = result
    return [result for result in results if result is not None]


@contextmanager
def _no_cycle_collection() -> Iterator[None]:
    """The cycle collector off: a batch makes no cycles, yet collecting took 13-30% of it."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _drive(items: list[Run]) -> list[SimulationResult | Exception]:
    """Run a batch of one shape, pass by pass; if the batch fails, each run alone."""
    try:
        batch = Batch([setup for setup, *_ in items])
        calendars = [Calendar(setup, batch, run) for run, (setup, *_) in enumerate(items)]
    except Exception as error:  # each run as a batch of its own
        return [error] if len(items) == 1 else [_drive([item])[0] for item in items]
    batch.with_stops = any(method != "event" for *_, method, _ in items)
    loops = Loops(items)
    outcomes: list[SimulationResult | Exception | None] = [None] * len(items)
    # Plain frictionless pair and cushion contacts for all runs at once (alone, the
    # calendar's own path is the cheaper).
    together = items[0][0].ball_law == "frictionless"
    active = list(range(len(items)))
    ended: dict[int, int] = {}  # the runs that came to their end, and their step counts
    while active:
        runs = np.array(active, dtype=np.intp)
        resolving = active  # until the loops say which runs want their next event
        try:
            batch.select(runs)
            resolving, ending = loops.advance(batch, runs)
            ended.update(ending)
            alone = list(resolving)
            if len(items) > 1:
                wanting = np.array(resolving, dtype=np.intp)
                kind = batch.next_kind[wanting]
                changes = kind == NextKind.CHANGE
                resolve_changes(calendars, wanting[changes])
                pairs = kind == NextKind.PAIR if together else np.zeros(len(wanting), dtype=bool)
                edges = kind == NextKind.EDGE
                alone = [
                    *wanting[~pairs & ~edges & ~changes].tolist(),
                    *resolve_pairs(calendars, wanting[pairs]).tolist(),
                    *resolve_cushions(calendars, wanting[edges]).tolist(),
                ]
            for run in alone:
                try:
                    calendars[run].resolve_selected()
                except Exception as error:  # the run's outcome, not the batch's
                    outcomes[run] = error
                    resolving.remove(run)
            batch.flush()
        except Exception as error:
            if len(items) == 1:
                return [error]
            for run in resolving:  # each again alone: a failure stays with its run
                outcomes[run] = _drive([items[run]])[0]
            resolving = []
        active = resolving
    logs = batch.log.by_run(list(ended))
    for run, step_count in ended.items():
        outcomes[run] = _finish(calendars[run], items[run], step_count, logs[run])
    keep_final_positions([outcome for outcome in outcomes if isinstance(outcome, SimulationResult)])
    done = [outcome for outcome in outcomes if outcome is not None]
    assert len(done) == len(items)
    return done


def _finish(
    calendar: Calendar, item: Run, steps: int, log: ContactLog
) -> SimulationResult | Exception:
    """Package a run that has ended, from its log."""
    setup, ball_ids, *_ = item
    try:
        motion = calendar.law.recorded(setup, log.segment_balls, log.segment_rows, len(ball_ids))
        stop, events, names = calendar.latest_stop(), calendar.event_count, calendar.law.state_names
        return package(item, steps, log, stop, events, motion, names)
    except Exception as error:  # the run's outcome, not the batch's
        return error


class Loops:
    """Every run's loop, for all runs at once. `event` runs jump from contact to contact;
    `exact` runs take fixed steps of dt, each resolving the contacts inside it at their
    exact times, so dt changes how the work is split, never the result."""

    def __init__(self, items: list[Run]) -> None:
        self.stepping = np.array([method != "event" for *_, method, _ in items])
        self.dt = np.array([dt for *_, dt in items], dtype=np.float64)
        self.max_time = np.array([setup.max_time for setup, *_ in items], dtype=np.float64)
        self.limit = np.array([setup.max_events for setup, *_ in items], dtype=np.intp)
        self.step = np.zeros(len(items), dtype=np.intp)  # a stepping run's step, 0: not begun
        self.step_end = np.zeros(len(items))  # and the time its step ends

    def advance(self, batch: Batch, runs: IntArray) -> tuple[list[int], list[tuple[int, int]]]:
        """Of `runs`, just selected (batch.select): those that want their next event
        resolved, and those that have ended, each with its step count (0 for `event`)."""
        if len(runs) == 1:
            return self._advance_one(batch, int(runs[0]))
        next_time = batch.next_time[runs]
        under = batch.event_count[runs] <= self.limit[runs]
        wants = (next_time <= self.max_time[runs]) & under
        steps = np.zeros(len(runs), dtype=np.intp)
        stepping = self.stepping[runs].nonzero()[0]
        if stepping.size:
            wants[stepping], steps[stepping] = self._steps(
                runs[stepping], next_time[stepping], batch.stops[runs[stepping]], under[stepping]
            )
        over = ~wants
        ended = zip(runs[over].tolist(), steps[over].tolist(), strict=True)
        return runs[wants].tolist(), list(ended)

    def _advance_one(self, batch: Batch, run: int) -> tuple[list[int], list[tuple[int, int]]]:
        """advance for one run, on Python numbers (a run alone pays per numpy call)."""
        next_time = float(batch.next_time[run])
        under = int(batch.event_count[run]) <= int(self.limit[run])
        max_time = float(self.max_time[run])
        if not self.stepping[run]:
            wants = next_time <= max_time and under
            return ([run], []) if wants else ([], [(run, 0)])
        # _steps, on Python numbers.
        dt, rest = float(self.dt[run]), float(batch.stops[run])
        step, step_end = int(self.step[run]), float(self.step_end[run])
        if step == 0:
            step, step_end = 1, min(dt, max_time)
        while not (wants := next_time <= step_end and under):
            if rest <= step_end or step_end >= max_time or not under:
                break
            upcoming = min(next_time, rest, max_time)
            step = max(step, int(upcoming // dt) - 1) + 1
            step_end = min(step * dt, max_time)
        self.step[run], self.step_end[run] = step, step_end
        return ([run], []) if wants else ([], [(run, step)])

    def _steps(
        self, runs: IntArray, next_time: FloatArray, rest: FloatArray, under: BoolArray
    ) -> tuple[BoolArray, IntArray]:
        """advance for stepping runs: whether each wants its next event, and its step."""
        dt, max_time = self.dt[runs], self.max_time[runs]
        step, step_end = self.step[runs], self.step_end[runs]
        begun = step > 0
        step[~begun] = 1
        step_end[~begun] = np.minimum(dt[~begun], max_time[~begun])
        wants = np.zeros(len(runs), dtype=bool)
        open_ = np.arange(len(runs))  # neither wanting an event nor ended yet
        while open_.size:
            wanting = (next_time[open_] <= step_end[open_]) & under[open_]
            wants[open_[wanting]] = True
            open_ = open_[~wanting]
            end = step_end[open_]
            ends = (rest[open_] <= end) | (end >= max_time[open_]) | ~under[open_]
            open_ = open_[~ends]
            # The next step that holds a contact or the last stop (or max_time).
            upcoming = np.minimum(np.minimum(next_time[open_], rest[open_]), max_time[open_])
            skipped = (upcoming // dt[open_]).astype(np.intp) - 1
            step[open_] = np.maximum(step[open_], skipped) + 1
            step_end[open_] = np.minimum(step[open_] * dt[open_], max_time[open_])
        self.step[runs], self.step_end[runs] = step, step_end
        return wants, step
