"""When a ball of the spin model next meets a cushion, a jaw, a capture line or another
ball, compiled (spin.contact_times, ball by ball and pair by pair, in the same
operations and order): a cushion or capture line is a quadratic gap (falling_roots), a
jaw or a pair a quartic (roots.first_downward_root), each within the ball's motion
state. All times are absolute."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.airborne.contacts import (
    FACE,
    NOSE,
    cushion_contact_in_flight,
)
from billiards.physics.compiled.airborne.contacts import separation_quartic as quartic_3d
from billiards.physics.compiled.arithmetic import np_maximum, np_minimum, py_min
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.rolling_times import separation_quartic, stays_apart
from billiards.physics.compiled.roots import EPS, first_downward_root
from billiards.physics.compiled.state import Anchors, Flag, Table
from billiards.physics.rolling.contact_times import PRUNE_FROM
from billiards.physics.spin.motion import FLYING, ROLLING, SLIDING

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


@inline
def moves(anchors: Anchors, ball: int) -> bool:
    """Whether the ball slides, rolls or flies (only such a ball meets anything)."""
    return anchors.state[ball] in (SLIDING, ROLLING, FLYING)


# A ball's anchor as the edge times read it: position, velocity, acceleration.
Motion = tuple[float, float, float, float, float, float]


@inline
def _wall_time(motion: Motion, bounds: np.ndarray, wall: int) -> float:
    """When after its anchor the ball's centre reaches cushion line `wall`, with no limit
    of time (contact_times.cushion_roots)."""
    axis = wall // 2
    side = 1.0 if wall % 2 else -1.0
    p, v, a = motion[axis], motion[2 + axis], motion[4 + axis]
    return falling_roots(side * (bounds[wall] - p), -side * v, -0.5 * side * a)


@kernel
def edge_contact(
    anchors: Anchors, ball: int, table: Table, skip: int, size: float, times: np.ndarray
) -> tuple[float, int]:
    """The ball's first edge contact within its motion state, and which edge
    (contact_times.cushion_contacts; skip: an edge it ignores, or -1, as there only with
    pockets; size: the flush's largest anchor coordinate, the jaws' rounding level;
    times: room for each edge's time, 4 + J + P)."""
    p0, v0, acceleration = anchors.p0, anchors.v0, anchors.acceleration
    ax, ay = acceleration[ball, 0], acceleration[ball, 1]
    motion = (p0[ball, 0], p0[ball, 1], v0[ball, 0], v0[ball, 1], ax, ay)
    duration, bounds = anchors.duration[ball], table.bounds
    if table.flies and anchors.state[ball] == FLYING:
        return _flying_edge_contact(anchors, ball, table, skip, size)
    if not table.pockets:
        best, wall = math.inf, 0
        for each in range(4):
            tau = _wall_time(motion, bounds, each)
            tau = tau if tau <= duration else math.inf
            if tau < best or (tau != tau and best == best):  # argmin: the first least
                best, wall = tau, each
        return anchors.t0[ball] + best, wall
    if not moves(anchors, ball):
        return math.inf, 0  # every edge inf: t0 + inf, the first
    jaw_count = len(table.jaws)
    for wall in range(4):
        segments = table.segments[wall, : table.segment_count[wall]]
        times[wall] = _covered_wall_time(motion, bounds, segments, wall)
    horizon = duration if math.isfinite(duration) else table.max_time
    sizes = (table.jaw_reach * table.jaw_reach, horizon, size)
    for jaw in range(jaw_count):
        times[4 + jaw] = _jaw_time(motion, table.jaws[jaw], sizes, table.bernstein)
    for pocket in range(len(table.capture_level)):
        nx, ny = table.capture_normal[pocket, 0], table.capture_normal[pocket, 1]
        gap = table.capture_level[pocket] - (motion[0] * nx + motion[1] * ny)
        closing = -(motion[2] * nx + motion[3] * ny)
        half_x, half_y = 0.5 * motion[4], 0.5 * motion[5]
        times[4 + jaw_count + pocket] = falling_roots(gap, closing, -(half_x * nx + half_y * ny))
    best, edge = math.inf, 0
    for each in range(len(times)):
        tau = math.inf if each == skip else times[each]
        tau = tau if tau <= duration else math.inf
        if tau < best or (tau != tau and best == best):
            best, edge = tau, each
    return anchors.t0[ball] + best, edge


# A flying ball's wall contact as an edge (calendar.resolve_edge): the face is the wall's
# own edge (0-3, met as on the cloth); its nose and its crossing over the rail are
# negative, -(2 + wall) and -(6 + wall) (airborne.contacts' NOSE and OVER_THE_RAIL; -1
# is calendar.skip's "none").
@inline
def flying_wall_edge(wall: int, kind: int) -> int:
    """The edge number of a flying ball's contact of `kind` with cushion `wall`."""
    if kind == FACE:
        return wall
    return -(2 + wall) if kind == NOSE else -(6 + wall)


@kernel
def _flying_edge_contact(
    anchors: Anchors, ball: int, table: Table, skip: int, size: float
) -> tuple[float, int]:
    """edge_contact for a ball in the air: each cushion met on its face, on its nose or
    crossed over the rail (airborne.contacts.cushion_contact_in_flight: the centre's
    distance across the wall's plane is linear in time, its height the parabola), where
    the cushion exists at the hit point (pockets: its segments); jaws and capture lines
    as on the cloth, in the plane (the flight has no acceleration there), a jaw passed
    over where the centre is higher than h + R (_over; the capture line's height:
    calendar._edge_outcome)."""
    x, y = anchors.p0[ball, 0], anchors.p0[ball, 1]
    vx, vy = anchors.v0[ball, 0], anchors.v0[ball, 1]
    duration, bounds, radius = anchors.duration[ball], table.bounds, table.radius
    shape = (radius, table.cushion.cushion_height, table.flight[0])
    height = (anchors.lift[ball, 0], anchors.lift[ball, 1])
    best, edge = math.inf, 0
    for wall in range(4):
        axis = wall // 2
        side = 1.0 if wall % 2 else -1.0
        p, v = (x, vx) if axis == 0 else (y, vy)
        across = (side * (bounds[wall] - p) + radius, (0.0 - side) * v)
        tau, kind = cushion_contact_in_flight(across, height, shape, duration, table.bernstein)
        code = flying_wall_edge(wall, kind)
        if table.pockets and math.isfinite(tau):
            hit = (y + vy * tau) if axis == 0 else (x + vx * tau)
            segments = table.segments[wall, : table.segment_count[wall]]
            covered = False
            for segment in range(len(segments)):
                if hit >= segments[segment, 0] and hit <= segments[segment, 1]:
                    covered = True
            tau = tau if covered else math.inf
        tau = math.inf if code == skip else tau
        if tau < best:
            best, edge = tau, code
    if table.pockets:
        motion = (x, y, vx, vy, 0.0, 0.0)
        jaw_count = len(table.jaws)
        horizon = duration if math.isfinite(duration) else table.max_time
        sizes = (table.jaw_reach * table.jaw_reach, horizon, size)
        for jaw in range(jaw_count):
            tau = _jaw_time(motion, table.jaws[jaw], sizes, table.bernstein)
            tau = math.inf if 4 + jaw == skip or not tau <= duration else tau
            if _over(height, tau, shape):  # higher than the jaw's top: passes over it
                tau = math.inf
            if tau < best:
                best, edge = tau, 4 + jaw
        for pocket in range(len(table.capture_level)):
            nx, ny = table.capture_normal[pocket, 0], table.capture_normal[pocket, 1]
            gap = table.capture_level[pocket] - (x * nx + y * ny)
            tau = falling_roots(gap, -(vx * nx + vy * ny), 0.0)
            code = 4 + jaw_count + pocket
            tau = math.inf if code == skip or not tau <= duration else tau
            if tau < best:
                best, edge = tau, code
    return anchors.t0[ball] + best, edge


@inline
def _over(height: tuple[float, float], tau: float, shape: tuple[float, float, float]) -> bool:
    """Whether a flying ball (height: z, v_z at its anchor) is higher than h + R `tau` s
    on (shape: R, h, g): its centre there clears a cushion's or a jaw's top."""
    radius, cushion_height, gravity = shape
    if not math.isfinite(tau):
        return False
    z = (height[0] + height[1] * tau) - 0.5 * gravity * (tau * tau)
    return z > cushion_height + radius


@inline
def _covered_wall_time(
    motion: Motion, bounds: np.ndarray, segments: np.ndarray, wall: int
) -> float:
    """The wall's time where its cushion exists at the hit point (the wall's segments
    (S, 2)), else inf (contact_times.pocket_edge_times)."""
    tau = _wall_time(motion, bounds, wall)
    at = tau if math.isfinite(tau) else 0.0
    # Where it meets the line, along it: the other coordinate.
    other = 1 - wall // 2
    half = 0.5 * motion[4 + other]
    hit = motion[other] + motion[2 + other] * at + half * at * at
    for segment in range(len(segments)):
        if hit >= segments[segment, 0] + 0.0 and hit <= segments[segment, 1] - 0.0:
            return tau
    return math.inf


@inline
def _jaw_time(
    motion: Motion,
    jaw: np.ndarray,
    sizes: tuple[float, float, float],
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """When after its anchor the ball touches a jaw (|p - J| = r + rho), within the
    horizon (contact_times.pocket_edge_times); sizes: ((r + rho)^2, horizon, the
    positions' size)."""
    reach, horizon, size = sizes
    x, y, vx, vy, ax, ay = motion
    half_x, half_y = 0.5 * ax, 0.5 * ay
    dx, dy = x - jaw[0], y - jaw[1]
    gap, closing, curve = (dx, dy), (vx, vy), (half_x, half_y)
    quartic, touching, level = separation_quartic(gap, closing, curve, reach, size)
    # Touching at a normal speed within rounding and curving away: a graze, only a
    # return counts.
    grazing = quartic[0] <= touching and abs(quartic[1]) <= level and quartic[2] > 0
    return first_downward_root(quartic, horizon, touching, grazing, level, False, bernstein)


# The columns of the rows (a row a ball) the spin model's pair times read (anchoring.
# motion_now): the ball now (position, velocity, half its acceleration where it moves),
# whether it moves, its next edge contact and its state's end; in a run that lets a
# ball fly (Table.flies), its height, vertical velocity, half its vertical acceleration
# and whether it flies.
X, Y, VX, VY, HALF_AX, HALF_AY, MOVES, END, CHANGE = range(9)
Z, VZ, HALF_AZ, FLIES = 9, 10, 11, 12


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
    if rows[first, FLIES] != 0 or rows[second, FLIES] != 0:
        return now + _flying_pair_time(rows, pair, (radius, reach), horizon, parting, bernstein)
    dx, dy = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    wx, wy = rows[first, VX] - rows[second, VX], rows[first, VY] - rows[second, VY]
    kx = rows[first, HALF_AX] - rows[second, HALF_AX]
    ky = rows[first, HALF_AY] - rows[second, HALF_AY]
    length = np_maximum(horizon, 0.0)
    if stays_apart((dx, dy), (wx, wy), (kx, ky), 2.0 * radius, length):
        return math.inf  # what the root search finds, at a fraction of its cost
    pair_reach = 4.0 * radius * radius
    quartic, touching, level = separation_quartic((dx, dy), (wx, wy), (kx, ky), pair_reach, reach)
    return now + first_downward_root(quartic, length, touching, parting, level, True, bernstein)


@kernel
def _flying_pair_time(
    rows: np.ndarray,
    pair: tuple[int, int],
    sizes: tuple[float, float],
    horizon: float,
    parting: Flag,
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """Seconds until a pair with a ball in the air touches (airborne.contacts: the
    separation quartic in 3D, z's terms added last), within the window; sizes: (R, the
    positions' size). No hair's-breadth rule: that is the cloth's (a flying ball's pair
    is no pair of sliding balls)."""
    first, second = pair
    radius, size = sizes
    gap = (
        rows[first, X] - rows[second, X],
        rows[first, Y] - rows[second, Y],
        rows[first, Z] - rows[second, Z],
    )
    closing = (
        rows[first, VX] - rows[second, VX],
        rows[first, VY] - rows[second, VY],
        rows[first, VZ] - rows[second, VZ],
    )
    curving = (
        rows[first, HALF_AX] - rows[second, HALF_AX],
        rows[first, HALF_AY] - rows[second, HALF_AY],
        rows[first, HALF_AZ] - rows[second, HALF_AZ],
    )
    reach_squared = 4.0 * radius * radius
    quartic, speed_squared = quartic_3d(gap, closing, curving, reach_squared)
    touching = reach_squared * 1e-12
    level = 32.0 * EPS * size * math.sqrt(speed_squared)
    window = np_maximum(horizon, 0.0)
    return first_downward_root(
        quartic, window, touching, parting, level, np.bool_(False), bernstein
    )


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
