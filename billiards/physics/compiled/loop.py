"""The compiled event loop (engine.stepper's loop for one run, engine.batch's select):
pick the next event by the tie rule, resolve it, re-anchor, until the run ends; and the
same over many runs, one after another (on the caller's threads, a span each), each run's
arithmetic its own, so a run gives the same bits alone, in a batch, and on any thread.

Ties: at one instant a motion-state change goes first (it moves nothing), then an edge
contact, then a pair contact, each the lowest ball (or first, then second ball) first;
no rolling ball changes state by itself (its change entries stay inf).

The run's motion model (Table.model) is a number the loop passes on: the same loop,
calendar and rules for both, the model's kernels chosen where a ball is moved or timed.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.compiled.airborne.bed import jump_launch
from billiards.physics.compiled.airborne.bounces import settles
from billiards.physics.compiled.anchoring import flush
from billiards.physics.compiled.arithmetic import np_maximum, py_min
from billiards.physics.compiled.calendar import change_state, resolve_edge, resolve_pair
from billiards.physics.compiled.jit import entry, inline, kernel
from billiards.physics.compiled.laws import CushionNumbers
from billiards.physics.compiled.motion import state_at
from billiards.physics.compiled.pair_table import earliest_pair
from billiards.physics.compiled.rolling_times import PAIR_COLUMNS
from billiards.physics.compiled.spin_motion import spin_latest_stop, spin_state_at
from billiards.physics.compiled.state import (
    BALL_FRICTION_A,
    BALL_FRICTION_B,
    BALL_FRICTION_C,
    BALL_LAW,
    CUSHION_FRICTION,
    CUSHION_HEIGHT,
    CUSHION_LAW,
    CUSHION_RESTITUTION,
    CUSHION_RESTITUTION_SPEED,
    DECEL,
    DT,
    FLIES,
    GRAVITY,
    JAW_REACH,
    MAX_EVENTS,
    MAX_TIME,
    MODEL,
    MODEL_SPIN,
    POCKETS,
    RADIUS,
    RESTITUTION,
    RETENTION,
    SETTLE_SPEED,
    SLIDE_DECEL,
    SLIDING_FRICTION,
    SPIN_DECEL,
    STATE_WIDTH,
    STEPPING,
    TABLE_FRICTION,
    TABLE_RESTITUTION,
    Anchors,
    Calendar,
    Log,
    Logs,
    Runs,
    Table,
)

KIND_CHANGE, KIND_EDGE, KIND_PAIR = 0, 1, 2


@kernel
def _first_least(values: np.ndarray) -> int:
    """numpy's argmin: the first least value (a NaN counts as least)."""
    best, index = values[0], 0
    for each in range(1, len(values)):
        value = values[each]
        if value < best or (value != value and best == best):
            best, index = value, each
    return index


@inline
def select(anchors: Anchors, calendar: Calendar) -> tuple[int, int, float]:
    """The next event (kind, ball or flat pair index, time) by the tie rule
    (Batch._select_one)."""
    change_ball = _first_least(anchors.change_time)
    edge_ball = _first_least(calendar.edge_time)
    flat, pair_time = earliest_pair(calendar)
    change_time, edge_time = anchors.change_time[change_ball], calendar.edge_time[edge_ball]
    if change_time <= edge_time and change_time <= pair_time:
        return KIND_CHANGE, change_ball, change_time
    if edge_time <= pair_time:
        return KIND_EDGE, edge_ball, edge_time
    return KIND_PAIR, flat, pair_time


@inline
def latest_stop(anchors: Anchors, model: int) -> float:
    """When the run's last ball comes to rest (the model's law's latest_stop)."""
    if model == MODEL_SPIN:
        return spin_latest_stop(anchors)
    stop = 0.0
    for each in anchors.stop_time:
        stop = np_maximum(stop, each)
    return stop


@kernel
def dynamics_at(world: tuple, ball: int, time: float, out: np.ndarray) -> None:
    """out (9,) = the ball's position, velocity, acceleration and spin at `time` by the
    run's model (the law's state_at)."""
    anchors, _, table, _ = world
    if table.model == MODEL_SPIN:
        spin_state_at(anchors, ball, time, table, out)
    else:
        state_at(anchors, ball, time, table.decel, out)


@inline
def advance(
    stepping: bool,
    step: np.ndarray,
    next_time: float,
    rest: float,
    under: bool,
    limits: tuple[float, float],
) -> bool:
    """Whether the run wants its next event (stepper.Loops._advance_one); a stepping run
    (`exact`) counts its steps of dt in step (2,): the step (a whole number), and when
    it ends."""
    max_time, dt = limits
    if not stepping:
        return next_time <= max_time and under
    if step[0] == 0:
        step[0], step[1] = 1, py_min(dt, max_time)
    while True:
        wants = next_time <= step[1] and under
        if wants or rest <= step[1] or step[1] >= max_time or not under:
            return wants
        upcoming = py_min(py_min(next_time, rest), max_time)
        step[0] = max(int(step[0]), int(upcoming // dt) - 1) + 1
        step[1] = py_min(step[0] * dt, max_time)


@inline
def _on_the_cloth(count: int, radius: float) -> np.ndarray:
    """Anchors.lift of `count` balls on the cloth: height R, no vertical velocity."""
    lift = np.zeros((count, 2))
    for ball in range(count):
        lift[ball, 0] = radius
    return lift


@kernel
def _launch(table: Table, drive_down: float, row: np.ndarray) -> None:
    """A jump stroke's ball (row (9,): position, velocity, spin, height, vertical
    velocity), driven into the bed at drive_down: it leaves the bed as bed.jump_launch
    gives (TP A-30/31, the vertical part kept, then the bed's bounce), or slides off it
    where that launch would rise less than the settling height (bounces.settles)."""
    _, restitution, friction, lowest_launch = table.flight
    spin = (row[4], row[5], row[6])
    velocity, turned = jump_launch(
        (row[2], row[3]), spin, drive_down, table.radius, restitution, friction
    )
    row[2], row[3] = velocity[0], velocity[1]
    row[4], row[5], row[6] = turned
    row[8] = 0.0 if settles(velocity[2], lowest_launch) else velocity[2]


@inline
def start(
    table: Table,
    positions: np.ndarray,
    motion: tuple[np.ndarray, np.ndarray, np.ndarray],
    log: Log,
) -> tuple:
    """A run's world at time 0, every ball anchored (Batch.__init__'s first flush) from
    its position and motion (velocities, spins, drives into the bed: a jump stroke's,
    _launch): (anchors, calendar, table, log)."""
    count = len(positions)
    velocities, spins, drives = motion
    anchors = Anchors(
        t0=np.zeros(count),
        p0=positions.copy(),
        v0=np.zeros((count, 2)),
        change_time=np.full(count, np.inf),
        speed=np.zeros(count),
        direction=np.zeros((count, 2)),
        rest_after=np.zeros(count),
        stop_time=np.zeros(count),
        rest_position=positions.copy(),
        w0=np.zeros((count, 3)),
        acceleration=np.zeros((count, 2)),
        angular=np.zeros((count, 2)),
        state=np.zeros(count, dtype=np.int64),
        duration=np.full(count, np.inf),
        lift=_on_the_cloth(count, table.radius),
    )
    calendar = Calendar(
        edge_time=np.full(count, np.inf),
        edge=np.zeros(count, dtype=np.int64),
        pair_time=np.full((count, count), np.inf),
        pair_least=np.full(count, np.inf),
        pair_partner=np.zeros(count, dtype=np.int64),
        gone=np.zeros(count, dtype=np.bool_),
        contact_time=np.full(count, -np.inf),
        pressed_at=np.full((count, count), np.nan),
        speed_scale=np.zeros(1),
        counts=np.zeros(2, dtype=np.int64),
        held_time=np.full(count, -np.inf),
        held_into=np.zeros((count, 2)),
        held_pair_time=np.full((count, count), np.nan),
        held_pair_holds=np.zeros((count, count), dtype=np.int64),
        skip=np.full(2, -1, dtype=np.int64),
        queue=np.zeros(2, dtype=np.int64),
        queued_balls=np.zeros(2, dtype=np.int64),
        queued=np.zeros((2, 9)),
        pair_rows=np.zeros((count, PAIR_COLUMNS)),
        anchored=np.zeros(count, dtype=np.bool_),
        now=np.zeros(STATE_WIDTH),
        edge_times=np.zeros(4 + len(table.jaws) + len(table.capture_level)),
        partials=np.zeros(5),
    )
    world = (anchors, calendar, table, log)
    kinematics = np.empty((count, 9))
    for ball in range(count):
        kinematics[ball, 0], kinematics[ball, 1] = positions[ball, 0], positions[ball, 1]
        kinematics[ball, 2], kinematics[ball, 3] = velocities[ball, 0], velocities[ball, 1]
        kinematics[ball, 4], kinematics[ball, 5] = spins[ball, 0], spins[ball, 1]
        kinematics[ball, 6] = spins[ball, 2]
        kinematics[ball, 7], kinematics[ball, 8] = table.radius, 0.0
        if table.flies and drives[ball] > 0:
            _launch(table, drives[ball], kinematics[ball])
    calendar.queue[0] = count
    flush(world, np.arange(count), 0.0, kinematics)
    return world


@inline
def run_one(
    table: Table,
    positions: np.ndarray,
    motion: tuple[np.ndarray, np.ndarray, np.ndarray],
    limits: tuple,
    log: Log,
) -> tuple[int, int, float]:
    """One run to its end: (events resolved, steps taken, when its last ball stops).
    motion: (velocities, spins, drives); limits: (max_time, max_events, stepping, dt). Stops
    early if the log overflows."""
    world = start(table, positions, motion, log)
    anchors, calendar, _, _ = world
    step = np.zeros(2)
    resolve_events(world, limits, step, np.zeros((2, STATE_WIDTH)))
    return calendar.counts[0], int(step[0]), latest_stop(anchors, table.model)


@kernel
def resolve_events(world: tuple, limits: tuple, step: np.ndarray, at: np.ndarray) -> None:
    """Resolve a started run's events (run_one) until it ends or its log overflows; step
    (2,): advance's, at (2, STATE_WIDTH): the colliding balls' dynamics. A kernel of its
    own, not in the entry: there, every array read from the run's structures would be
    reference-counted (two atomic operations each, a tenth of a run's time)."""
    max_time, max_events, stepping, dt = limits
    anchors, calendar, table, log = world
    while log.filled[2] == 0:
        kind, index, time = select(anchors, calendar)
        rest = latest_stop(anchors, table.model) if stepping else 0.0
        under = calendar.counts[0] <= max_events
        if not advance(stepping, step, time, rest, under, (max_time, dt)):
            break
        count = len(calendar.edge_time)
        if kind == KIND_CHANGE:
            change_state(world, index, time)
        elif kind == KIND_EDGE:
            dynamics_at(world, index, time, at[0])
            resolve_edge(world, index, time, at[0])
        else:
            first, second = index // count, index % count
            dynamics_at(world, first, time, at[0])
            dynamics_at(world, second, time, at[1])
            resolve_pair(world, first, second, time, at)
        if calendar.queue[0] > 0:  # the event's anchoring (none for a graze asked again)
            flush(world, calendar.queued_balls, time, calendar.queued)


@inline
def run_at(runs: Runs, logs: Logs, run: int) -> None:
    """Run `run` of `runs`, into its row of `logs`."""
    own = slice(runs.starts[run], runs.starts[run + 1])
    constants = runs.constants[run]
    table = Table(
        model=int(constants[MODEL]),
        ball_law=int(constants[BALL_LAW]),
        cushion_law=int(constants[CUSHION_LAW]),
        radius=constants[RADIUS],
        bounds=runs.bounds[run],
        decel=constants[DECEL],
        slide_decel=constants[SLIDE_DECEL],
        spin_decel=constants[SPIN_DECEL],
        max_time=constants[MAX_TIME],
        restitution=constants[RESTITUTION],
        retention=constants[RETENTION],
        cushion=CushionNumbers(
            radius=constants[RADIUS],
            retention=constants[RETENTION],
            cushion_restitution=constants[CUSHION_RESTITUTION],
            cushion_friction=constants[CUSHION_FRICTION],
            cushion_height=constants[CUSHION_HEIGHT],
            sliding_friction=constants[SLIDING_FRICTION],
            cushion_restitution_speed=constants[CUSHION_RESTITUTION_SPEED],
        ),
        ball_friction=(
            constants[BALL_FRICTION_A],
            constants[BALL_FRICTION_B],
            constants[BALL_FRICTION_C],
        ),
        masses=runs.masses[own],
        pockets=constants[POCKETS] != 0,
        jaws=runs.jaws[run],
        jaw_pocket=runs.jaw_pocket,
        jaw_reach=constants[JAW_REACH],
        capture_normal=runs.capture_normal[run],
        capture_level=runs.capture_level[run],
        segments=runs.segments[run],
        segment_count=runs.segment_count,
        bernstein=(runs.bernstein_whole, runs.bernstein_eighths),
        flies=constants[FLIES] != 0,
        flight=(
            constants[GRAVITY],
            constants[TABLE_RESTITUTION],
            constants[TABLE_FRICTION],
            constants[SETTLE_SPEED],
        ),
    )
    log = Log(
        contact_time=logs.contact_time[run],
        contact_kind=logs.contact_kind[run],
        contact_balls=logs.contact_balls[run],
        contact_speed=logs.contact_speed[run],
        contact_pocket=logs.contact_pocket[run],
        segment_ball=logs.segment_ball[run],
        segment_rows=logs.segment_rows[run],
        transition_time=logs.transition_time[run],
        transition_ball=logs.transition_ball[run],
        transition_state=logs.transition_state[run],
        filled=logs.filled[run],
    )
    log.filled[:] = 0
    limits = (constants[MAX_TIME], constants[MAX_EVENTS], constants[STEPPING] != 0, constants[DT])
    motion = (runs.velocities[own], runs.spins[own], runs.drives[own])
    events, steps, stop = run_one(table, runs.positions[own], motion, limits, log)
    logs.outcome[run, 0], logs.outcome[run, 1], logs.stop[run] = events, steps, stop


@entry
def run_many(runs: Runs, logs: Logs, first: int, stop: int) -> None:
    """Runs first to stop - 1 of `runs`, one after another, each into its row of `logs`.
    It holds no GIL: threads run spans side by side, each run's arithmetic its own."""
    for run in range(first, stop):
        run_at(runs, logs, run)
