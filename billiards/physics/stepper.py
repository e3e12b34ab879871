"""The stepper: run setups to rest by one of the three methods and package the results;
runs of one shape go through one batch (billiards.physics.batch), a single run is a
batch of one."""

from __future__ import annotations

from collections.abc import Generator, Hashable, Iterable, Iterator
from typing import Protocol

import numpy as np

from billiards.physics.batch import Batch, shape_of
from billiards.physics.calendar import (
    Calendar,
    resolve_changes,
    resolve_cushions,
    resolve_pairs,
)
from billiards.physics.events import Event, Transition
from billiards.physics.laws import CUSHION_LAWS
from billiards.physics.result import AnchoredMotion, SampledMotion, SimulationResult
from billiards.physics.setup import Setup

METHODS = ("exact", "event", "naive")


class Stepped(Protocol):
    """What the stepper's loops drive: one run's calendar of events in time order."""

    setup: Setup
    event_count: int

    def next_time(self) -> float: ...

    def latest_stop(self) -> float: ...


# One run: its setup, ball ids, method and dt, as `run` takes them.
Run = tuple[Setup, tuple[str, ...], str, float]


def run(setup: Setup, ball_ids: tuple[str, ...], method: str, dt: float) -> SimulationResult:
    """Simulate a setup to rest (or max_time) by `method`, stepping by `dt` where it steps:
    a batch of one (run_batch)."""
    result = next(run_batch([(setup, ball_ids, method, dt)]))
    if isinstance(result, Exception):
        raise result
    return result


def run_batch(runs: Iterable[Run]) -> Iterator[SimulationResult | Exception]:
    """Each run's result, in order, exactly what it gives alone, or the exception it
    raised (a failing run fails alone). Runs that share a shape (batch.shape_of) go
    through one batch, pass by pass; `naive` runs one at a time."""
    items = list(runs)
    results: list[SimulationResult | Exception | None] = [None] * len(items)
    groups: dict[Hashable, list[int]] = {}
    for index, (setup, ball_ids, method, dt) in enumerate(items):
        try:
            _check(setup, method, dt)
            if method == "naive":
                results[index] = _naive(setup, ball_ids, dt)
                continue
            key = shape_of(setup)
        except Exception as error:  # the run's outcome, not the batch's
            results[index] = error
            continue
        groups.setdefault(key, []).append(index)
    for indices in groups.values():
        for index, result in zip(indices, _drive([items[i] for i in indices]), strict=True):
            results[index] = result
    for outcome in results:
        assert outcome is not None
        yield outcome


def _check(setup: Setup, method: str, dt: float) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    if not dt > 0:
        raise ValueError(f"dt must be positive, got {dt!r}")
    if setup.cushion_law not in CUSHION_LAWS:
        raise ValueError(f"unknown cushion law {setup.cushion_law!r}")


def _drive(items: list[Run]) -> list[SimulationResult | Exception]:
    """Run a batch of runs of one shape to the end, pass by pass: each pass picks every
    unfinished run's next event, lets each run resolve its own, and re-anchors all of
    them at once (billiards.physics.batch). If the batch itself fails (not one run's
    rules), each of its runs is run again alone, so that a failure stays with its run."""
    try:
        batch = Batch([setup for setup, *_ in items])
        calendars = [Calendar(setup, batch, run) for run, (setup, *_) in enumerate(items)]
    except Exception as error:
        return _alone(items, error)
    batch.with_stops = any(method != "event" for *_, method, _ in items)
    loops = [
        run_events(calendar, setup.max_time)
        if method == "event"
        else run_steps(calendar, dt, setup.max_time)
        for calendar, (setup, _, method, dt) in zip(calendars, items, strict=True)
    ]
    outcomes: list[SimulationResult | Exception | None] = [None] * len(items)
    # Plain frictionless pair contacts are resolved for all runs at once (in batches
    # of more than one: alone, the calendar's own path is the cheaper).
    together = items[0][0].ball_law == "frictionless"
    mirrors = items[0][0].cushion_law == "mirror"
    active = list(range(len(items)))
    while active:
        batch.select(np.array(active))
        resolving = []
        for run in active:
            try:
                next(loops[run])
            except StopIteration as stop:
                outcomes[run] = _finish(calendars[run], items[run], stop.value)
                continue
            except Exception as error:  # the run's outcome, not the batch's
                outcomes[run] = error
                continue
            resolving.append(run)
        try:
            alone = list(resolving)
            if len(items) > 1:
                wanting = np.array(resolving, dtype=np.intp)
                kind = batch.next_kind[wanting]
                changes = kind == 0
                resolve_changes(calendars, wanting[changes])
                pairs = kind == 2 if together else np.zeros(len(wanting), dtype=bool)
                edges = kind == 1 if mirrors else np.zeros(len(wanting), dtype=bool)
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
    done = [outcome for outcome in outcomes if outcome is not None]
    assert len(done) == len(items)
    return done


def _alone(items: list[Run], error: Exception) -> list[SimulationResult | Exception]:
    """Each run as a batch of its own (or the batch's error, if it is one run)."""
    if len(items) == 1:
        return [error]
    return [_drive([item])[0] for item in items]


def _finish(calendar: Calendar, item: Run, steps: int) -> SimulationResult | Exception:
    """Package a run that has ended."""
    setup, ball_ids, method, dt = item
    try:
        stop = calendar.latest_stop()
        complete = calendar.event_count <= setup.max_events and stop <= setup.max_time
        rest_time = min(stop, setup.max_time)
        if calendar.event_count > setup.max_events:
            # The guard stopped resolving contacts: past the last one the anchors would
            # carry balls through cushions and each other, so the run ends there.
            rest_time = min(rest_time, calendar.log.times[-1])
        log = calendar.log
        motion = calendar.law.recorded(
            np.concatenate(log.segment_balls).astype(np.intp),
            np.concatenate(log.segment_rows),
            len(ball_ids),
        )
        contacts = zip(log.times, log.kinds, log.balls, log.impact_speeds, log.pockets, strict=True)
        names = calendar.law.state_names
        transitions = tuple(
            Transition(time, ball_ids[ball], names[state])
            for time, ball, state in log.transitions
            if time <= rest_time
        )
        return _result(
            setup, ball_ids, method, dt, contacts, rest_time, steps, motion, complete, transitions
        )
    except Exception as error:  # the run's outcome, not the batch's
        return error


def _result(
    setup: Setup,
    ball_ids: tuple[str, ...],
    method: str,
    dt: float,
    contacts: Iterable[tuple[float, str, tuple[int, ...], float, str | None]],
    rest_time: float,
    steps: int,
    motion: AnchoredMotion | SampledMotion,
    complete: bool,
    transitions: tuple[Transition, ...] = (),
) -> SimulationResult:
    """Package a run: contacts named by ball id, the setup's constants carried along."""
    events = tuple(
        Event(time, kind, tuple(ball_ids[b] for b in balls), speed, pocket)
        for time, kind, balls, speed, pocket in contacts
    )
    return SimulationResult(
        method=method,
        model=setup.model,
        dt=None if method == "event" else dt,
        ball_ids=ball_ids,
        radius=setup.radius,
        table_size=setup.table_size,
        masses=setup.masses,
        initial_positions=setup.positions,
        initial_velocities=setup.velocities,
        events=events,
        rest_time=rest_time,
        steps=steps,
        motion=motion,
        complete=complete,
        transitions=transitions,
        stopped_by=None
        if complete
        else ("max_events" if len(events) > setup.max_events else "max_time"),
        pockets=setup.pockets,
    )


# A run's loop: it yields where it wants its calendar's next event resolved (the
# batch's pass does that, for every run at once) and returns its step count.
Loop = Generator[None, None, int]


def run_events(calendar: Stepped, max_time: float) -> Loop:
    """Pure event-driven: jump from contact to contact. Returns 0 steps."""
    limit = calendar.setup.max_events
    while calendar.next_time() <= max_time and calendar.event_count <= limit:
        yield
    return 0


def run_steps(calendar: Stepped, dt: float, max_time: float) -> Loop:
    """Fixed steps of dt: each step resolves, at their exact times and in order, the
    contacts that fall inside it. Balls are evaluated in closed form from their
    anchors, so the step size changes how the work is split, never the result, and
    a step in which nothing happens costs nothing (the loop skips to the next step
    that holds a contact or the last stop)."""
    limit = calendar.setup.max_events
    step = 0
    next_contact = calendar.next_time()
    rest = calendar.latest_stop()
    while True:
        step += 1
        step_end = min(step * dt, max_time)
        while next_contact <= step_end and calendar.event_count <= limit:
            yield
            next_contact = calendar.next_time()
            rest = calendar.latest_stop()
        if rest <= step_end or step_end >= max_time or calendar.event_count > limit:
            return step
        upcoming = min(next_contact, rest, max_time)
        step = max(step, int(upcoming // dt) - 1)


def _naive(setup: Setup, ball_ids: tuple[str, ...], dt: float) -> SimulationResult:
    from billiards.physics.naive import run_naive  # the seed's stepped method, on request

    times, positions, velocities, spins, contacts, complete = run_naive(setup, dt)
    motion = SampledMotion(times=times, positions=positions, velocities=velocities, spins=spins)
    rest_time = float(times[-1])
    return _result(
        setup, ball_ids, "naive", dt, contacts, rest_time, len(times) - 1, motion, complete
    )
