"""Packaging a run that has ended: its log, when its last ball stops and its motion, as
the SimulationResult every method returns (the numpy engine's runs, the compiled
loop's and `naive`'s alike)."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import replace

from billiards.physics.engine.batch_log import Contact, ContactLog
from billiards.physics.engine.events import Transition, events_named
from billiards.physics.engine.result import AnchoredMotion, SampledMotion, SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.arrays import FloatArray

# One run: its setup, ball ids, method and dt, as methods.entry.run takes them.
Run = tuple[Setup, tuple[str, ...], str, float]


def started(item: Run, velocities: FloatArray, spins: FloatArray | None) -> Run:
    """The run with its balls started at these velocities (N, 2) and spins (N, 3; None:
    the setup's own) in place of its setup's."""
    setup, ball_ids, method, dt = item
    own = setup.spins if spins is None else spins
    return (replace(setup, velocities=velocities, spins=own), ball_ids, method, dt)


def package(
    item: Run,
    steps: int,
    log: ContactLog,
    stop: float,
    event_count: int,
    motion: AnchoredMotion | SampledMotion,
    state_names: tuple[str, ...],
) -> SimulationResult:
    """A run's result from its log, when its last ball stops, how many events it
    resolved, its motion and its model's state names (for the numpy engine's runs and
    the compiled loop's alike)."""
    setup, ball_ids, *_ = item
    complete = event_count <= setup.max_events and stop <= setup.max_time
    last_contact = log.contacts[-1][0] if event_count > setup.max_events else math.inf
    rest_time = ending(setup, stop, event_count, last_contact)
    transitions = tuple(
        Transition(time, ball_ids[ball], state_names[state])
        for time, ball, state in log.transitions
        if time <= rest_time
    )
    return result_of(item, log.contacts, rest_time, steps, motion, complete, transitions)


def ending(setup: Setup, stop: float, event_count: int, last_contact: float) -> float:
    """A run's rest_time: when its last ball stops (`stop`), at most max_time; and at
    most its last contact's time if it resolved more than max_events."""
    rest_time = min(stop, setup.max_time)
    if event_count > setup.max_events:
        # The guard stopped resolving contacts: past the last one the anchors would
        # carry balls through cushions and each other, so the run ends there.
        rest_time = min(rest_time, last_contact)
    return rest_time


def result_of(
    item: Run,
    contacts: Iterable[Contact],
    rest_time: float,
    steps: int,
    motion: AnchoredMotion | SampledMotion,
    complete: bool,
    transitions: tuple[Transition, ...] = (),
) -> SimulationResult:
    """Package a run: contacts named by ball id, the setup's constants carried along."""
    setup, ball_ids, method, dt = item
    events = events_named(contacts, ball_ids)
    stopped_by = "max_events" if len(events) > setup.max_events else "max_time"
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
        stopped_by=None if complete else stopped_by,
        pockets=setup.pockets,
    )
