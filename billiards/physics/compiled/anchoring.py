"""Re-anchoring, compiled (engine.batch.Batch.flush for one run): the balls an event
changed take their new anchors, logged; their edge entries and the entries of every
pair they are in are asked again; balls at rest and gone balls cost nothing."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum, py_max
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.motion import anchor, remaining, state_at
from billiards.physics.compiled.rolling_times import (
    END,
    REST,
    REST_X,
    REST_Y,
    SPEED,
    T0,
    UX,
    UY,
    edge_contact,
    pair_contact,
)
from billiards.physics.compiled.state import Anchors, Calendar, Log, Table
from billiards.physics.rolling.contact_times import PRUNE_FROM


@kernel
def flush(world: tuple, balls: np.ndarray, time: float, kinematics: np.ndarray) -> None:
    """Anchor `balls` at `time` (kinematics (k, 4): position, velocity), log them, and ask
    their edge entries (calendar.skip: a (ball, edge) the ball ignores, then cleared)
    and their pairs' entries again. world: (anchors, calendar, table, log)."""
    anchors, calendar, table, log = world
    fastest = 0.0
    for row in range(len(balls)):
        ball = balls[row]
        x, y, vx, vy = kinematics[row]
        anchor(anchors, ball, time, x, y, vx, vy, table.decel)
        v0x, v0y = anchors.v0[ball, 0], anchors.v0[ball, 1]
        speed = math.sqrt(v0x * v0x + v0y * v0y)
        fastest = speed if row == 0 else np_maximum(fastest, speed)
        _log_segment(log, ball, time, anchors)
    calendar.speed_scale[0] = py_max(calendar.speed_scale[0], fastest)
    for ball in balls:
        ignored = calendar.skip[1] if ball == calendar.skip[0] else -1
        calendar.edge_time[ball], calendar.edge[ball] = edge_contact(anchors, ball, table, ignored)
    calendar.skip[0] = calendar.skip[1] = -1
    _ask_pairs(world, balls, time)


@kernel
def _log_segment(log: Log, ball: int, time: float, anchors: Anchors) -> None:
    """One anchor's row (t0, p0, v0), or the overflow mark where the buffer is full."""
    row = log.filled[1]
    if row >= len(log.segment_ball):
        log.filled[2] = 1
        return
    log.segment_ball[row] = ball
    log.segment_rows[row, 0] = time
    log.segment_rows[row, 1], log.segment_rows[row, 2] = anchors.p0[ball, 0], anchors.p0[ball, 1]
    log.segment_rows[row, 3], log.segment_rows[row, 4] = anchors.v0[ball, 0], anchors.v0[ball, 1]
    log.filled[1] = row + 1


@kernel
def _ask_pairs(world: tuple, balls: np.ndarray, time: float) -> None:
    """Every pair with one of `balls` in it, once: its next contact (inf for a gone ball's
    and for two at rest), the pruning as the numpy flush prunes (by how many it asks)."""
    anchors, calendar, table, _ = world
    count = len(calendar.edge_time)
    anchored, gone, pair_time = calendar.anchored, calendar.gone, calendar.pair_time
    for ball in range(count):
        anchored[ball] = False
    for ball in balls:
        anchored[ball] = True
    rows = calendar.pair_rows
    reach = motion_now(anchors, calendar, table, time)
    asked = 0
    for first in range(count):
        for second in range(first + 1, count):
            if (anchored[first] or anchored[second]) and _wanted(gone, rows, first, second):
                asked += 1
    # np.bool_: a value, not a constant (numba compiles a kernel again for each constant).
    flags = (asked >= PRUNE_FROM, np.bool_(False))
    constants = (table.radius, table.decel, reach)
    for first in range(count):
        for second in range(first + 1, count):
            if not (anchored[first] or anchored[second]):
                continue
            found = math.inf
            if _wanted(gone, rows, first, second):
                found = pair_contact(rows, constants, (first, second), time, flags, table.bernstein)
            pair_time[first, second] = found


@kernel
def _wanted(gone: np.ndarray, rows: np.ndarray, first: int, second: int) -> bool:
    """Whether a pair is asked at all: neither ball gone, and one still rolling."""
    if gone[first] or gone[second]:
        return False
    return not (rows[first, REST] == 0 and rows[second, REST] == 0)


@kernel
def motion_now(anchors: Anchors, calendar: Calendar, table: Table, time: float) -> float:
    """Every ball's row of calendar.pair_rows (rolling_times.PAIR_COLUMNS) at `time`;
    returns the run's reach (its largest coordinate), as rolling.law.RollingLaw.
    pair_times finds them."""
    count = len(anchors.t0)
    rows = calendar.pair_rows
    reach = 0.0
    for ball in range(count):
        row = rows[ball]
        state_at(anchors, ball, time, table.decel, row)  # X to AY
        row[REST] = remaining(anchors, ball, time)
        row[END] = calendar.edge_time[ball]
        row[SPEED], row[T0] = anchors.speed[ball], anchors.t0[ball]
        row[REST_X], row[REST_Y] = anchors.rest_position[ball, 0], anchors.rest_position[ball, 1]
        row[UX], row[UY] = anchors.direction[ball, 0], anchors.direction[ball, 1]
        for axis in range(2):
            size = abs(row[axis])
            reach = size if ball == 0 and axis == 0 else np_maximum(reach, size)
    return reach


@kernel
def ask_return(world: tuple, first: int, second: int, time: float) -> bool:
    """Set a touching pair's entry to its return (a graze: only a return counts), or to
    never if that is not after `time` (engine.calendar.Calendar._ask_return)."""
    anchors, calendar, table, _ = world
    reach = motion_now(anchors, calendar, table, time)
    rows = calendar.pair_rows
    returns = math.inf
    if not (rows[first, REST] == 0 and rows[second, REST] == 0):
        flags = (np.bool_(False), np.bool_(True))  # values, not constants (_ask_pairs)
        constants = (table.radius, table.decel, reach)
        returns = pair_contact(rows, constants, (first, second), time, flags, table.bernstein)
    calendar.pair_time[first, second] = returns if returns > time else math.inf
    return returns > time
