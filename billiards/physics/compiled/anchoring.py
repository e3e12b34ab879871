"""Re-anchoring, compiled (engine.batch.Batch.flush for one run): the balls an event
changed take their new anchors, logged; their edge entries and the entries of every
pair they are in are asked again; balls at rest and gone balls cost nothing. The run's
motion model (Table.model) chooses the kernels that anchor and time: the rolling
model's (motion, rolling_times) or the spin model's (spin_motion, spin_times)."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled import spin_times
from billiards.physics.compiled.arithmetic import np_maximum, np_minimum, py_max
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.motion import anchor, remaining, rolling_anchors, rolling_state
from billiards.physics.compiled.pair_table import set_pair_time
from billiards.physics.compiled.rolling_times import (
    AX,
    AY,
    BOX,
    END,
    REST,
    REST_X,
    REST_Y,
    SPEED,
    T0,
    UX,
    UY,
    VX,
    VY,
    X,
    Y,
    edge_contact,
    pair_contact,
    pair_window,
)
from billiards.physics.compiled.spin_motion import (
    flight_height,
    spin_anchor,
    spin_anchors,
    spin_state,
)
from billiards.physics.compiled.state import MODEL_SPIN, Anchors, Calendar, Flag, Log, Table
from billiards.physics.rolling.contact_times import PRUNE_FROM
from billiards.physics.spin.motion import FLYING, ROLLING, SLIDING


@kernel
def flush(world: tuple, balls: np.ndarray, time: float, kinematics: np.ndarray) -> None:
    """Anchor the first `count` of `balls` at `time` (kinematics (k, 7): position,
    velocity, spin), log them, and ask their edge entries (calendar.skip: a (ball, edge)
    the ball ignores, then cleared) and their pairs' entries again; then log the new
    motion state of each ball whose bit (1 << row) `logged` holds. world: (anchors,
    calendar, table, log); (count, logged): calendar.queue's."""
    anchors, calendar, table, log = world
    count, logged = calendar.queue[0], calendar.queue[1]
    calendar.queue[0] = calendar.queue[1] = 0
    balls = balls[:count]
    spin = table.model == MODEL_SPIN
    fastest = size = 0.0
    for row in range(count):
        ball = balls[row]
        if spin:
            spin_anchor(anchors, ball, time, kinematics[row], table)
        else:
            x, y, vx, vy = (
                kinematics[row, 0],
                kinematics[row, 1],
                kinematics[row, 2],
                kinematics[row, 3],
            )
            anchor(anchors, ball, time, x, y, vx, vy, table.decel)
        v0x, v0y = anchors.v0[ball, 0], anchors.v0[ball, 1]
        speed = math.sqrt(v0x * v0x + v0y * v0y)
        fastest = speed if row == 0 else np_maximum(fastest, speed)
        # The anchors' largest coordinate: the spin model's jaws' rounding level.
        largest = np_maximum(abs(anchors.p0[ball, 0]), abs(anchors.p0[ball, 1]))
        size = largest if row == 0 else np_maximum(size, largest)
        _log_segment(log, ball, time, anchors, spin)
    calendar.speed_scale[0] = py_max(calendar.speed_scale[0], fastest)
    for ball in balls:
        ignored = calendar.skip[1] if ball == calendar.skip[0] else -1
        if spin:
            found = spin_times.edge_contact(
                anchors, ball, table, ignored, size, calendar.edge_times
            )
        else:
            found = edge_contact(anchors, ball, table, ignored, calendar.edge_times)
        calendar.edge_time[ball], calendar.edge[ball] = found
    calendar.skip[0] = calendar.skip[1] = -1
    _ask_pairs(world, balls, time)
    for row in range(count):
        if logged >> row & 1:
            _log_transition(log, time, balls[row], anchors.state[balls[row]])


@inline
def _log_segment(log: Log, ball: int, time: float, anchors: Anchors, spin: bool) -> None:
    """One anchor's row (t0, p0, v0, and the spin model's w0 and state), or the overflow
    mark where the buffer is full."""
    row = log.filled[1]
    if row >= len(log.segment_ball):
        log.filled[2] = 1
        return
    log.segment_ball[row] = ball
    rows = log.segment_rows
    rows[row, 0] = time
    rows[row, 1], rows[row, 2] = anchors.p0[ball, 0], anchors.p0[ball, 1]
    rows[row, 3], rows[row, 4] = anchors.v0[ball, 0], anchors.v0[ball, 1]
    if spin:
        rows[row, 5], rows[row, 6] = anchors.w0[ball, 0], anchors.w0[ball, 1]
        rows[row, 7], rows[row, 8] = anchors.w0[ball, 2], anchors.state[ball]
        rows[row, 9], rows[row, 10] = anchors.lift[ball, 0], anchors.lift[ball, 1]
    log.filled[1] = row + 1


@inline
def _log_transition(log: Log, time: float, ball: int, state: int) -> None:
    """One motion-state change (time, ball, its new state), or the overflow mark."""
    row = log.filled[3]
    if row >= len(log.transition_time):
        log.filled[2] = 1
        return
    log.transition_time[row], log.transition_ball[row] = time, ball
    log.transition_state[row] = state
    log.filled[3] = row + 1


@kernel
def _ask_pairs(world: tuple, balls: np.ndarray, time: float) -> None:
    """Every pair with one of `balls` (distinct) in it, once: its next contact (inf for a
    gone ball's and for two at rest), the pruning as the numpy flush prunes (by how many
    it asks). The pairs are visited row by row, an anchored ball's whole row, another's
    entries with the anchored balls: what an event costs grows with N, not N x N."""
    anchors, calendar, table, _ = world
    count = len(calendar.edge_time)
    anchored = calendar.anchored
    for ball in range(count):
        anchored[ball] = False
    for ball in balls:
        anchored[ball] = True
    rows, gone = calendar.pair_rows, calendar.gone
    reach = motion_now(anchors, calendar, table, time)
    spin = table.model == MODEL_SPIN
    # np.bool_: a value, not a constant (numba compiles a kernel again for each constant).
    flags = (_asks_many(world, balls), np.bool_(False))
    constants, bernstein = _constants(table, reach), table.bernstein
    apart = _apart(table.radius, reach)
    for first in range(count):
        for index in range(_entries(anchored, balls, first)):
            second = _second(anchored, balls, first, index)
            if second <= first:
                continue
            found = math.inf
            if _wanted(gone, rows, (first, second), spin) and not (
                not spin and _rolling_apart(rows, (first, second), time, apart)
            ):
                found = _pair_contact(
                    rows, constants, (first, second), time, flags, bernstein, spin
                )
            set_pair_time(calendar, first, second, found)


@inline
def _asks_many(world: tuple, balls: np.ndarray) -> bool:
    """Whether _ask_pairs asks at least PRUNE_FROM pairs (then the pair times rule out
    the pairs too far apart to meet first, as the numpy flush does): counted until there
    are that many."""
    _, calendar, table, _ = world
    anchored, rows, gone = calendar.anchored, calendar.pair_rows, calendar.gone
    spin = table.model == MODEL_SPIN
    asked = 0
    for first in range(len(anchored)):
        for index in range(_entries(anchored, balls, first)):
            second = _second(anchored, balls, first, index)
            if second > first and _wanted(gone, rows, (first, second), spin):
                asked += 1
                if asked >= PRUNE_FROM:
                    return True
    return False


@inline
def _apart(radius: float, reach: float) -> float:
    """How far apart two rolling balls' path boxes must be for the pair to be told apart
    without its pair time (_boxes_apart): the contact distance 2r, and a nanometre and a
    billionth of the sizes, far above the rounding of the boxes' corners and of the
    root search's touching band, as rolling_times.stays_apart keeps."""
    return 2.0 * radius * (1.0 + 1e-9) + 1e-9 * (1.0 + reach)


@inline
def _rolling_apart(rows: np.ndarray, pair: tuple[int, int], time: float, apart: float) -> bool:
    """Whether two rolling balls cannot come within `apart` (_apart) before either's next
    edge contact: their path boxes apart (_boxes_apart), or the gap between them wider
    than both can roll in the window their pair time looks at (rolling_times.
    pair_contact's; each at most its anchor's speed). Then the pair's entry is inf, as its
    pair time would find, at the cost of a few comparisons instead of a call (most of a
    crowded table's pairs)."""
    first, second = pair
    if _boxes_apart(rows, first, second, apart):
        return True
    window = pair_window(rows, pair, time)
    rolls_first = rows[first, SPEED] * np_minimum(rows[first, REST], window)
    rolls_second = rows[second, SPEED] * np_minimum(rows[second, REST], window)
    reach = apart + (rolls_first + rolls_second) * (1.0 + 1e-6) + 1e-9
    gap_x, gap_y = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    return gap_x * gap_x + gap_y * gap_y > reach * reach


@inline
def _boxes_apart(rows: np.ndarray, first: int, second: int, apart: float) -> bool:
    """Whether the boxes of two rolling balls' paths (rolling_times.BOX: until each one's
    next edge contact or rest) are more than `apart` apart along x or y. An unbounded box
    (NaN or inf) is never apart."""
    for axis in range(2):
        low, high = BOX + 2 * axis, BOX + 2 * axis + 1
        if rows[first, low] - rows[second, high] > apart:
            return True
        if rows[second, low] - rows[first, high] > apart:
            return True
    return False


@inline
def _entries(anchored: np.ndarray, balls: np.ndarray, first: int) -> int:
    """How many of row `first`'s entries _ask_pairs visits: an anchored ball's every
    second ball after it, another's the anchored balls (those after it count)."""
    if anchored[first]:
        return len(anchored) - first - 1
    return len(balls)


@inline
def _second(anchored: np.ndarray, balls: np.ndarray, first: int, index: int) -> int:
    """The second ball of row `first`'s visited entry `index` (_entries); an anchored
    ball not after `first` is skipped by the caller (its pair is in its own row)."""
    if anchored[first]:
        return first + 1 + index
    return balls[index]


@inline
def _constants(table: Table, reach: float) -> tuple[float, float, float]:
    """What the run's model's pair times read of it: (radius, decel, reach) rolling,
    (radius, max_time, reach) spin."""
    if table.model == MODEL_SPIN:
        return (table.radius, table.max_time, reach)
    return (table.radius, table.decel, reach)


@kernel
def _pair_contact(
    rows: np.ndarray,
    constants: tuple[float, float, float],
    pair: tuple[int, int],
    time: float,
    flags: tuple[Flag, Flag],
    bernstein: tuple[np.ndarray, np.ndarray],
    spin: bool,
) -> float:
    """A pair's next contact by its run's model (rolling_times or spin_times.
    pair_contact), from the rows motion_now wrote; constants: _constants'. (Numbers and
    two arrays: every array a compiled call takes costs it two atomic reference counts,
    and a flush asks dozens of pairs.)"""
    if spin:
        return spin_times.pair_contact(rows, constants, pair, time, flags, bernstein)
    return pair_contact(rows, constants, pair, time, flags, bernstein)


@inline
def _wanted(gone: np.ndarray, rows: np.ndarray, pair: tuple[int, int], spin: bool) -> bool:
    """Whether a pair is asked at all: neither ball gone (calendar.gone), and one still
    moving by the rows motion_now wrote (rolling: rolling on; spin: sliding or rolling).
    (Arrays, not the run's structures: each structure an inlined call takes costs it two
    atomic reference counts an array, and a flush asks every pair.)"""
    first, second = pair
    if gone[first] or gone[second]:
        return False
    if spin:
        return rows[first, spin_times.MOVES] != 0 or rows[second, spin_times.MOVES] != 0
    return not (rows[first, REST] == 0 and rows[second, REST] == 0)


@kernel
def motion_now(anchors: Anchors, calendar: Calendar, table: Table, time: float) -> float:
    """Every ball's row of calendar.pair_rows (rolling_times.PAIR_COLUMNS, or spin_times'
    columns) at `time`; returns the run's reach (its largest coordinate), as the model's
    law's pair_times finds them."""
    if table.model == MODEL_SPIN:
        return _spin_motion_now(anchors, calendar, table, time)
    count = len(anchors.t0)
    rows = calendar.pair_rows
    rolling = rolling_anchors(anchors)
    reach = 0.0
    for ball in range(count):
        row = rows[ball]
        rolling_state(rolling, ball, time, table.decel, row)  # X to AY
        row[REST] = remaining(rolling, ball, time)
        row[END] = calendar.edge_time[ball]
        row[SPEED], row[T0] = anchors.speed[ball], anchors.t0[ball]
        row[REST_X], row[REST_Y] = anchors.rest_position[ball, 0], anchors.rest_position[ball, 1]
        row[UX], row[UY] = anchors.direction[ball, 0], anchors.direction[ball, 1]
        _path_box(row, time)
        for axis in range(2):
            size = abs(row[axis])
            reach = size if ball == 0 and axis == 0 else np_maximum(reach, size)
    return reach


@inline
def _path_box(row: np.ndarray, time: float) -> None:
    """A rolling ball's path box (rolling_times.BOX) from its row: from where it is now
    to where it is at its next edge contact, or at rest if that comes first (a straight
    path, slowing, so these two ends bound it); unbounded where that time is not a
    finite one ahead."""
    ahead = np_minimum(row[REST], row[END] - time)
    bounded = ahead >= 0 and math.isfinite(ahead)
    end_x = row[X] + row[VX] * ahead + 0.5 * row[AX] * (ahead * ahead)
    end_y = row[Y] + row[VY] * ahead + 0.5 * row[AY] * (ahead * ahead)
    row[BOX], row[BOX + 1] = np_minimum(row[X], end_x), np_maximum(row[X], end_x)
    row[BOX + 2], row[BOX + 3] = np_minimum(row[Y], end_y), np_maximum(row[Y], end_y)
    if not bounded:
        row[BOX], row[BOX + 2] = -math.inf, -math.inf
        row[BOX + 1], row[BOX + 3] = math.inf, math.inf


@kernel
def _spin_motion_now(anchors: Anchors, calendar: Calendar, table: Table, time: float) -> float:
    """motion_now for the spin model (spin.law.SpinLaw.pair_times' motion rows)."""
    count = len(anchors.t0)
    rows = calendar.pair_rows
    now = calendar.now
    spinning = spin_anchors(anchors)
    reach = 0.0
    for ball in range(count):
        row = rows[ball]
        spin_state(spinning, ball, time, table.spin_decel, now)
        state = anchors.state[ball]
        flying = state == FLYING
        moving = state in (SLIDING, ROLLING) or flying
        for axis in range(2):
            row[spin_times.X + axis] = now[axis]
            row[spin_times.VX + axis] = now[2 + axis]
            half = 0.5 * anchors.acceleration[ball, axis]
            row[spin_times.HALF_AX + axis] = half if moving else 0.0
            size = abs(now[axis])
            reach = size if ball == 0 and axis == 0 else np_maximum(reach, size)
        row[spin_times.MOVES] = 1.0 if moving else 0.0
        row[spin_times.END] = calendar.edge_time[ball]
        row[spin_times.CHANGE] = anchors.change_time[ball]
        if table.flies:  # the third axis (a run that never flies reads none of it)
            flight_height(anchors, ball, time, table, now)
            row[spin_times.Z], row[spin_times.VZ] = now[9], now[10]
            row[spin_times.HALF_AZ] = -0.5 * table.flight[0] if flying else 0.0
            row[spin_times.FLIES] = 1.0 if flying else 0.0
    return reach


@kernel
def ask_return(world: tuple, first: int, second: int, time: float) -> bool:
    """Set a touching pair's entry to its return (a graze: only a return counts), or to
    never if that is not after `time` (engine.calendar.Calendar._ask_return)."""
    anchors, calendar, table, _ = world
    reach = motion_now(anchors, calendar, table, time)
    rows, gone = calendar.pair_rows, calendar.gone
    spin = table.model == MODEL_SPIN
    returns = math.inf
    if _wanted(gone, rows, (first, second), spin):
        flags = (np.bool_(False), np.bool_(True))  # values, not constants (_ask_pairs)
        constants = _constants(table, reach)
        returns = _pair_contact(
            rows, constants, (first, second), time, flags, table.bernstein, spin
        )
    set_pair_time(calendar, first, second, returns if returns > time else math.inf)
    return returns > time
