"""When a ball of the spin model next meets a cushion, a jaw, a capture line or another
ball, compiled (spin.contact_times, ball by ball and pair by pair, in the same
operations and order): a cushion or capture line is a quadratic gap (falling_roots), a
jaw or a pair a quartic (roots.first_downward_root), each within the ball's motion
state. All times are absolute."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum, np_minimum, py_min
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.rolling_times import on_cushion
from billiards.physics.compiled.roots import EPS, first_downward_root
from billiards.physics.compiled.state import Anchors, Flag, Table
from billiards.physics.rolling.contact_times import PRUNE_FROM
from billiards.physics.spin.motion import ROLLING, SLIDING

__all__ = ["PRUNE_FROM", "edge_contact", "falling_roots", "moves", "pair_contact"]


@kernel
def falling_roots(c: float, b: float, a: float) -> float:
    """The first root tau > 0 where the gap c + b tau + a tau^2 falls to zero, inf where
    none, 0 where closed (by rounding) and closing (contact_times.falling_roots)."""
    discriminant = b * b - 4.0 * a * c
    root = math.sqrt(np_maximum(discriminant, 0.0))
    q = -0.5 * (b + (root if b >= 0 else -root))
    first = q / a if a != 0 else math.inf
    second = c / q if q != 0 else math.inf
    if not (discriminant >= 0 and math.isfinite(first) and first > 0 and b + 2.0 * a * first < 0):
        first = math.inf
    if not (
        discriminant >= 0 and math.isfinite(second) and second > 0 and b + 2.0 * a * second < 0
    ):
        second = math.inf
    if c <= 0 and (b < 0 or (b == 0 and a < 0)):
        return 0.0
    return py_min(first, second)


@kernel
def moves(anchors: Anchors, ball: int) -> bool:
    """Whether the ball slides or rolls (only such a ball meets anything)."""
    state = anchors.state[ball]
    return state in (SLIDING, ROLLING)


@kernel
def _wall_time(anchors: Anchors, ball: int, bounds: np.ndarray, wall: int) -> float:
    """When after its anchor the ball's centre reaches cushion line `wall`, with no limit
    of time (contact_times.cushion_roots)."""
    axis = wall // 2
    side = 1.0 if wall % 2 else -1.0
    p, v = anchors.p0[ball, axis], anchors.v0[ball, axis]
    a = anchors.acceleration[ball, axis]
    return falling_roots(side * (bounds[wall] - p), -side * v, -0.5 * side * a)


@kernel
def edge_contact(
    anchors: Anchors, ball: int, table: Table, skip: int, size: float
) -> tuple[float, int]:
    """The ball's first edge contact within its motion state, and which edge
    (contact_times.cushion_contacts; skip: an edge it ignores, or -1, as there only with
    pockets; size: the flush's largest anchor coordinate, the jaws' rounding level)."""
    duration = anchors.duration[ball]
    if not table.pockets:
        best, wall = math.inf, 0
        for each in range(4):
            tau = _wall_time(anchors, ball, table.bounds, each)
            tau = tau if tau <= duration else math.inf
            if tau < best or (tau != tau and best == best):  # argmin: the first least
                best, wall = tau, each
        return anchors.t0[ball] + best, wall
    if not moves(anchors, ball):
        return math.inf, 0  # every edge inf: t0 + inf, the first
    best, edge = math.inf, 0
    for each in range(4 + len(table.jaws) + len(table.capture_level)):
        tau = _pocket_edge_time(anchors, ball, table, each, size)
        tau = math.inf if each == skip else tau
        tau = tau if tau <= duration else math.inf
        if tau < best or (tau != tau and best == best):
            best, edge = tau, each
    return anchors.t0[ball] + best, edge


@kernel
def _pocket_edge_time(anchors: Anchors, ball: int, table: Table, edge: int, size: float) -> float:
    """The time after its anchor of the ball's contact with `edge` on a table with
    pockets: a wall where its cushion exists, a jaw (within the state's duration, or
    max_time), a capture line (contact_times.pocket_edge_times)."""
    x, y = anchors.p0[ball, 0], anchors.p0[ball, 1]
    vx, vy = anchors.v0[ball, 0], anchors.v0[ball, 1]
    half_x, half_y = 0.5 * anchors.acceleration[ball, 0], 0.5 * anchors.acceleration[ball, 1]
    if edge < 4:
        tau = _wall_time(anchors, ball, table.bounds, edge)
        at = tau if math.isfinite(tau) else 0.0
        # Where it meets the line, along it: the other coordinate.
        start, speed, half = (y, vy, half_y) if edge // 2 == 0 else (x, vx, half_x)
        hit = start + speed * at + half * at * at
        return tau if on_cushion(hit, table, edge, 0.0) else math.inf
    jaw_count = len(table.jaws)
    if edge >= 4 + jaw_count:
        pocket = edge - 4 - jaw_count
        nx, ny = table.capture_normal[pocket, 0], table.capture_normal[pocket, 1]
        gap = table.capture_level[pocket] - (x * nx + y * ny)
        return falling_roots(gap, -(vx * nx + vy * ny), -(half_x * nx + half_y * ny))
    jaw = edge - 4
    dx, dy = x - table.jaws[jaw, 0], y - table.jaws[jaw, 1]
    reach = table.jaw_reach * table.jaw_reach
    speed_squared = vx * vx + vy * vy
    quartic = (
        (dx * dx + dy * dy) - reach,
        2.0 * (dx * vx + dy * vy),
        speed_squared + 2.0 * (dx * half_x + dy * half_y),
        2.0 * (vx * half_x + vy * half_y),
        half_x * half_x + half_y * half_y,
    )
    duration = anchors.duration[ball]
    horizon = duration if math.isfinite(duration) else table.max_time
    touching = reach * 1e-12
    level = 32.0 * EPS * size * math.sqrt(speed_squared)
    # Touching at a normal speed within rounding and curving away: a graze, only a
    # return counts.
    grazing = quartic[0] <= touching and abs(quartic[1]) <= level and quartic[2] > 0
    return first_downward_root(quartic, horizon, touching, grazing, level, False, table.bernstein)


# The columns of the rows (a row a ball) the spin model's pair times read (anchoring.
# motion_now): the ball now (position, velocity, half its acceleration where it moves),
# whether it moves, its next edge contact and its state's end.
X, Y, VX, VY, HALF_AX, HALF_AY, MOVES, END, CHANGE = range(9)


@inline
def pair_contact(
    rows: np.ndarray,
    constants: tuple[float, float, float],
    pair: tuple[int, int],
    now: float,
    flags: tuple[Flag, Flag],
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """Absolute time of a pair's next contact after `now`, within both balls' motion
    states and before either's next edge contact, inf if none (contact_times.
    pair_contacts; asked only of a pair with a ball that moves). constants: (radius,
    max_time, reach); flags: (prune: at least PRUNE_FROM pairs asked, parting)."""
    first, second = pair
    prune, parting = flags
    radius, max_time, reach = constants
    ends = np_minimum(rows[first, CHANGE], rows[first, END])
    horizon = np_minimum(ends, np_minimum(rows[second, CHANGE], rows[second, END])) - now
    horizon = horizon if math.isfinite(horizon) else max_time
    if prune and _too_far(rows, first, second, radius, horizon):
        return math.inf
    dx, dy = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    wx, wy = rows[first, VX] - rows[second, VX], rows[first, VY] - rows[second, VY]
    kx = rows[first, HALF_AX] - rows[second, HALF_AX]
    ky = rows[first, HALF_AY] - rows[second, HALF_AY]
    reach_squared = 4.0 * radius * radius
    speed_squared = wx * wx + wy * wy
    quartic = (
        (dx * dx + dy * dy) - reach_squared,
        2.0 * (dx * wx + dy * wy),
        speed_squared + 2.0 * (dx * kx + dy * ky),
        2.0 * (wx * kx + wy * ky),
        kx * kx + ky * ky,
    )
    touching = reach_squared * 1e-12
    level = 32.0 * EPS * reach * math.sqrt(speed_squared)
    length = np_maximum(horizon, 0.0)
    return now + first_downward_root(quartic, length, touching, parting, level, True, bernstein)


@inline
def _too_far(rows: np.ndarray, first: int, second: int, radius: float, horizon: float) -> bool:
    """A gap wider than both can travel in the window (|v| t + |k| t^2 each), by
    rolling's margin (contact_times.pair_contacts' pruning)."""
    window = np_maximum(horizon, 0.0)
    speeds = _size(rows, first, VX) + _size(rows, second, VX)
    curves = _size(rows, first, HALF_AX) + _size(rows, second, HALF_AX)
    travel = speeds * window + curves * (window * window)
    gap_x, gap_y = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    gap = math.sqrt(gap_x * gap_x + gap_y * gap_y) - 2.0 * radius
    return gap > travel * (1.0 + 1e-6) + 1e-9


@inline
def _size(rows: np.ndarray, ball: int, column: int) -> float:
    """|(rows[ball, column], rows[ball, column + 1])|, as norm computes it."""
    x, y = rows[ball, column], rows[ball, column + 1]
    return math.sqrt(x * x + y * y)
