"""The stepper: run a setup to rest by one of the three methods and package the result."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Protocol

import numpy as np

from billiards.physics.calendar import Calendar
from billiards.physics.events import Event, Transition
from billiards.physics.result import AnchoredMotion, SampledMotion, SimulationResult
from billiards.physics.setup import Setup

METHODS = ("exact", "event", "naive")


class Stepped(Protocol):
    """What the stepper's loops drive: a calendar of events in time order."""

    setup: Setup
    event_count: int

    def next_time(self) -> float: ...

    def resolve_next(self) -> float: ...

    def latest_stop(self) -> float: ...


def run(setup: Setup, ball_ids: tuple[str, ...], method: str, dt: float) -> SimulationResult:
    """Simulate a setup to rest (or max_time) by `method`, stepping by `dt` where it steps."""
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    if not dt > 0:
        raise ValueError(f"dt must be positive, got {dt!r}")
    if method == "naive":
        return _naive(setup, ball_ids, dt)
    calendar = Calendar(setup)
    if method == "event":
        steps = run_events(calendar, setup.max_time)
    else:
        steps = run_steps(calendar, dt, setup.max_time)
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


# One run of a batch: its setup, ball ids, method and dt, as `run` takes them.
Run = tuple[Setup, tuple[str, ...], str, float]


def run_batch(runs: Iterable[Run]) -> Iterator[SimulationResult | Exception]:
    """Each run's result, in order, exactly what `run` gives it alone, or the exception
    it raised (a failing run fails alone). Today each run goes through `run` in turn:
    issue 19's calendar over a run axis (one pass resolving the next event of every
    unfinished run) is not built; this is where it goes, behind the same contract."""
    for setup, ball_ids, method, dt in runs:
        try:
            yield run(setup, ball_ids, method, dt)
        except Exception as error:  # the run's outcome, not the batch's
            yield error


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


def run_events(calendar: Stepped, max_time: float) -> int:
    """Pure event-driven: jump from contact to contact. Returns 0 steps."""
    limit = calendar.setup.max_events
    while calendar.next_time() <= max_time and calendar.event_count <= limit:
        calendar.resolve_next()
    return 0


def run_steps(calendar: Stepped, dt: float, max_time: float) -> int:
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
            calendar.resolve_next()
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
