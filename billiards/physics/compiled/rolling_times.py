"""When a rolling ball next meets a cushion, a jaw, a capture line or another ball,
compiled (rolling.contact_times and rolling.pocket_times, ball by ball and pair by
pair, in the same operations and order). All times are absolute."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum, np_minimum
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.motion import path_length
from billiards.physics.compiled.roots import EPS, first_downward_root
from billiards.physics.compiled.state import Anchors, Flag, Table
from billiards.physics.rolling.pocket_times import MARGIN


@kernel
def travel_time(speed: float, decel: float, distance: float) -> float:
    """Time to roll `distance` from `speed`, inf if the ball stops first
    (contact_times.travel_time)."""
    discriminant = speed * speed - 2.0 * decel * distance
    time = 2.0 * distance / (speed + math.sqrt(np_maximum(discriminant, 0.0)))
    return time if (discriminant >= 0 and speed > 0) else math.inf


@kernel
def wall_distance(path: tuple[float, float], bounds: np.ndarray, wall: int) -> float:
    """How far a path (the coordinate and direction along the wall's axis) goes to
    cushion line `wall` (contact_times.wall_distances)."""
    start, along = path
    heading = along > 0 if wall % 2 == 1 else along < 0
    distance = (bounds[wall] - start) / along
    return np_maximum(distance, 0.0) if heading else math.inf


@kernel
def cushion_contact(anchors: Anchors, ball: int, table: Table) -> tuple[float, int]:
    """The ball's next cushion time and wall (contact_times.cushion_contacts)."""
    best, wall = math.inf, 0
    for each in range(4):
        axis = each // 2
        path = (anchors.p0[ball, axis], anchors.direction[ball, axis])
        distance = wall_distance(path, table.bounds, each)
        time = travel_time(anchors.speed[ball], table.decel, distance)
        if time < best or (time != time and best == best):  # argmin: the first least
            best, wall = time, each
    return anchors.t0[ball] + best, wall


@kernel
def first_touch(b: float, c: float, discriminant: float, touching: float) -> float:
    """The first root of s^2 + 2 b s + c = 0 (contact_times.first_touch)."""
    distance = c / (-b + math.sqrt(np_maximum(discriminant, 0.0)))
    hits = b < 0 and discriminant >= 0
    distance = np_maximum(distance, 0.0) if hits else math.inf
    return 0.0 if (c <= touching and b < 0) else distance


@kernel
def on_cushion(along: float, table: Table, wall: int, margin: float) -> bool:
    """Whether a point `along` a wall lies where its cushion exists (pockets.on_cushion)."""
    for segment in range(table.segment_count[wall]):
        low, high = table.segments[wall, segment, 0], table.segments[wall, segment, 1]
        if along >= low + margin and along <= high - margin:
            return True
    return False


@kernel
def edge_contact(
    anchors: Anchors, ball: int, table: Table, skip: int, distance: np.ndarray
) -> tuple[float, int]:
    """The ball's next cushion, jaw or capture line, and which (pocket_times.edge_contacts;
    skip: an edge it ignores, or -1; distance: room for each edge's distance, 4 + J + P).
    Only a path that could meet a pocket pays for it."""
    time, wall = cushion_contact(anchors, ball, table)
    if not table.pockets:
        return time, wall
    p0, u, bounds = anchors.p0, anchors.direction, table.bounds
    tau = time - anchors.t0[ball] if math.isfinite(time) else anchors.rest_after[ball]
    tau = tau if math.isfinite(tau) else 0.0
    rolled = path_length(anchors.speed[ball], table.decel, tau)
    end_x, end_y = p0[ball, 0] + u[ball, 0] * rolled, p0[ball, 1] + u[ball, 1] * rolled
    x, y = p0[ball, 0], p0[ball, 1]
    inside = x >= bounds[0] - MARGIN and x <= bounds[1] + MARGIN
    inside = inside and y >= bounds[2] - MARGIN and y <= bounds[3] + MARGIN
    past = False
    for pocket in range(len(table.capture_level)):
        normal = table.capture_normal[pocket]
        projected = end_x * normal[0] + end_y * normal[1]
        past = past or projected > table.capture_level[pocket] - MARGIN
    along = end_y if wall // 2 == 0 else end_x
    in_gap = not on_cushion(along, table, wall, MARGIN)
    near = not inside or past or (math.isfinite(time) and in_gap) or skip >= 0
    if not near:
        return time, wall
    return _full_contact(anchors, ball, table, skip, distance)


@kernel
def _full_contact(
    anchors: Anchors, ball: int, table: Table, skip: int, distance: np.ndarray
) -> tuple[float, int]:
    """The ball's next wall (where a cushion exists), jaw or capture line, as distances
    along its path (into `distance`), then times (pocket_times._full_contacts)."""
    jaw_count, pocket_count = len(table.jaws), len(table.capture_level)
    x, y = anchors.p0[ball, 0], anchors.p0[ball, 1]
    ux, uy = anchors.direction[ball, 0], anchors.direction[ball, 1]
    for wall in range(4):
        path = (x, ux) if wall // 2 == 0 else (y, uy)
        to_wall = wall_distance(path, table.bounds, wall)
        # Where it meets the line, along it: the other coordinate.
        start, step = (y, uy) if wall // 2 == 0 else (x, ux)
        hit = start + step * (to_wall if math.isfinite(to_wall) else 0.0)
        distance[wall] = to_wall if on_cushion(hit, table, wall, 0.0) else math.inf
    reach = table.jaw_reach * table.jaw_reach
    for jaw in range(jaw_count):
        d_x, d_y = x - table.jaws[jaw, 0], y - table.jaws[jaw, 1]
        b, c = ux * d_x + uy * d_y, d_x * d_x + d_y * d_y - reach
        cross = ux * d_y - uy * d_x
        distance[4 + jaw] = first_touch(b, c, reach - cross * cross, reach * 1e-12)
    for pocket in range(pocket_count):
        n_x, n_y = table.capture_normal[pocket, 0], table.capture_normal[pocket, 1]
        into = ux * n_x + uy * n_y
        to_line = (table.capture_level[pocket] - (x * n_x + y * n_y)) / into
        distance[4 + jaw_count + pocket] = np_maximum(to_line, 0.0) if into > 0 else math.inf
    speed = anchors.speed[ball]
    best, edge = math.inf, 0
    for each in range(len(distance)):
        # A ball at rest meets nothing; a skipped edge is not there.
        gone = not speed > 0 or each == skip
        time = travel_time(speed, table.decel, math.inf if gone else distance[each])
        if time < best or (time != time and best == best):  # argmin: the first least
            best, edge = time, each
    return anchors.t0[ball] + best, edge


# The columns of the rows (a row a ball) the pair times read, written once an anchoring
# (anchoring.motion_now): the ball now (position, velocity, acceleration), how long it
# still rolls, its next edge contact, and its anchor's speed, time, rest position and
# direction; then the box its path fills until its next edge contact or rest (x from,
# x to, y from, y to: anchoring._boxes_apart). One array, not the run's structures: every
# array a compiled call takes costs it two atomic reference counts, and a flush asks
# dozens of pairs.
X, Y, VX, VY, AX, AY, REST, END, SPEED, T0, REST_X, REST_Y, UX, UY = range(14)
BOX = 14
PAIR_COLUMNS = 18


@inline
def pair_contact(
    rows: np.ndarray,
    constants: tuple[float, float, float],
    pair: tuple[int, int],
    now: float,
    flags: tuple[Flag, Flag],
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """Next contact time of a pair after `now`, inf if none before either's next edge
    contact (contact_times.pair_contacts): both rolling (the quartic), then one rolling
    towards one at rest. constants: (radius, decel, reach); flags: (prune: the flush
    asked at least PRUNE_FROM pairs, parting: only a return counts)."""
    first, second = pair
    prune, parting = flags
    radius, _, reach = constants
    remaining_first, remaining_second = rows[first, REST], rows[second, REST]
    one_end = pair_window(rows, pair, now)
    if prune:
        one_end = _pruned(rows, first, second, radius, one_end)
    both_end = np_minimum(np_minimum(remaining_first, remaining_second), one_end)
    time = math.inf
    if both_end > 0:
        found = _quartic_contact(rows, pair, both_end, (radius, reach), parting, bernstein)
        time = now + found
    if one_end > both_end and math.isinf(time):
        first_moves = remaining_first > remaining_second
        mover, rester = (first, second) if first_moves else (second, first)
        window = (both_end, one_end)
        time = _one_rolling_time(rows, constants, mover, rester, now, window, parting)
    return time


@inline
def pair_window(rows: np.ndarray, pair: tuple[int, int], now: float) -> float:
    """How long after `now` a pair's contact is looked for: until the first of the two
    balls' next edge contacts (where either has one), and no longer than the later of
    the two rolls."""
    first, second = pair
    remaining_first, remaining_second = rows[first, REST], rows[second, REST]
    horizon = np_minimum(rows[first, END], rows[second, END]) - now
    if math.isinf(horizon):
        horizon = np_maximum(remaining_first, remaining_second)
    return np_minimum(np_maximum(remaining_first, remaining_second), horizon)


@inline
def _pruned(rows: np.ndarray, first: int, second: int, radius: float, one_end: float) -> float:
    """one_end, or 0 for a pair too far apart to meet in it (contact_times.pair_contacts)."""
    speed_first = math.sqrt(rows[first, VX] * rows[first, VX] + rows[first, VY] * rows[first, VY])
    speed_second = math.sqrt(
        rows[second, VX] * rows[second, VX] + rows[second, VY] * rows[second, VY]
    )
    gap_x, gap_y = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    gap = math.sqrt(gap_x * gap_x + gap_y * gap_y) - 2.0 * radius
    rolls_first = speed_first * np_minimum(rows[first, REST], one_end)
    travel = rolls_first + speed_second * np_minimum(rows[second, REST], one_end)
    return 0.0 if gap > travel * (1.0 + 1e-6) + 1e-9 else one_end


@inline
def _quartic_contact(
    rows: np.ndarray,
    pair: tuple[int, int],
    length: float,
    sizes: tuple[float, float],
    parting: Flag,
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """First contact within [0, length] of two balls on uniformly accelerated paths
    (contact_times.quartic_contact, separation_quartic and rounding_levels); sizes:
    (radius, reach)."""
    first, second = pair
    radius, reach = sizes
    dx, dy = rows[first, X] - rows[second, X], rows[first, Y] - rows[second, Y]
    wx, wy = rows[first, VX] - rows[second, VX], rows[first, VY] - rows[second, VY]
    kx = rows[first, AX] * 0.5 - rows[second, AX] * 0.5
    ky = rows[first, AY] * 0.5 - rows[second, AY] * 0.5
    if stays_apart((dx, dy), (wx, wy), (kx, ky), 2.0 * radius, length):
        return math.inf  # what the root search finds, at a fraction of its cost
    pair_reach = 4.0 * radius * radius
    quartic, touching, level = separation_quartic((dx, dy), (wx, wy), (kx, ky), pair_reach, reach)
    return first_downward_root(quartic, length, touching, parting, level, False, bernstein)


# How far beyond the reach stays_apart asks a pair to stay (m, and a part of the sizes it
# adds): a millionth of a millimetre, a million times the rounding of what it computes
# and far above the root search's touching band (1e-12 of the reach squared).
APART_SLACK = 1e-9


@inline
def stays_apart(
    gap: tuple[float, float],
    closing: tuple[float, float],
    curve: tuple[float, float],
    reach: float,
    length: float,
) -> bool:
    """Whether a relative position d + w t + k t^2 (gap d, velocity w, half acceleration
    k) stays farther than `reach` from 0 by APART_SLACK throughout [0, length]: then the
    separation quartic has no root there and first_downward_root finds none. Judged on
    two axes (|p| >= |p . n| for a unit n): along d, where a pair parts or closes, and
    across w, where a pair closing on a line that misses passes by. Most pairs of a
    crowded table are told apart here, without the quartic's certificate."""
    dx, dy = gap
    distance = math.sqrt(dx * dx + dy * dy)
    if not (distance > reach and length >= 0):
        return False
    wx, wy = closing
    kx, ky = curve
    squared = length * length
    along_w = (dx * wx + dy * wy) / distance
    along_k = (dx * kx + dy * ky) / distance
    least = np_minimum(distance, distance + along_w * length + along_k * squared)
    turn = -along_w / (2.0 * along_k) if along_k > 0 else -1.0
    if turn > 0 and turn < length:
        least = np_minimum(least, distance - along_w * along_w / (4.0 * along_k))
    sizes = distance + abs(along_w) * length + abs(along_k) * squared
    if least > reach + APART_SLACK * (1.0 + sizes):
        return True
    speed = math.sqrt(wx * wx + wy * wy)
    if not speed > 0:
        return False
    # Across w: (n . d) + (n . k) t^2 with n the unit normal to w on d's side.
    across_d = abs(dx * wy - dy * wx) / speed
    sign = 1.0 if dx * wy - dy * wx >= 0 else -1.0
    across_k = sign * (kx * wy - ky * wx) / speed
    least = across_d + np_minimum(across_k * squared, 0.0)
    sizes = across_d + abs(across_k) * squared
    return least > reach + APART_SLACK * (1.0 + sizes)


@kernel
def separation_quartic(
    gap: tuple[float, float],
    closing: tuple[float, float],
    curve: tuple[float, float],
    reach_squared: float,
    size: float,
) -> tuple[tuple[float, float, float, float, float], float, float]:
    """|d + w t + k t^2|^2 - reach^2 for a relative position d, velocity w and half
    acceleration k (contact_times.separation_quartic: two balls at 2r, or a ball and a
    jaw at r + rho), in its order; with the touching band and the rounding level of
    f'(0) (rounding_levels; size: the coordinates' largest)."""
    dx, dy = gap
    wx, wy = closing
    kx, ky = curve
    speed_squared = wx * wx + wy * wy
    quartic = (
        (dx * dx + dy * dy) - reach_squared,
        2.0 * (dx * wx + dy * wy),
        speed_squared + 2.0 * (dx * kx + dy * ky),
        2.0 * (wx * kx + wy * ky),
        kx * kx + ky * ky,
    )
    touching = reach_squared * 1e-12
    level = 32.0 * EPS * size * math.sqrt(speed_squared)
    return quartic, touching, level


@inline
def _one_rolling_time(
    rows: np.ndarray,
    constants: tuple[float, float, float],
    mover: int,
    rester: int,
    now: float,
    window: tuple[float, float],
    parting: Flag,
) -> float:
    """The absolute time a rolling ball (mover) meets one at rest (rester) within the
    window, inf if not (contact_times._one_rolling_times)."""
    radius, decel, _ = constants
    both_end, one_end = window
    offset = both_end
    start_x = rows[mover, X] + rows[mover, VX] * offset + 0.5 * rows[mover, AX] * (offset * offset)
    start_y = rows[mover, Y] + rows[mover, VY] * offset + 0.5 * rows[mover, AY] * (offset * offset)
    speed = rows[mover, SPEED] - decel * (now + offset - rows[mover, T0])
    contact = 4.0 * radius * radius
    separation_x = start_x - rows[rester, REST_X]
    separation_y = start_y - rows[rester, REST_Y]
    b = rows[mover, UX] * separation_x + rows[mover, UY] * separation_y
    c = (separation_x * separation_x + separation_y * separation_y) - contact
    distance = first_touch(b, c, b * b - c, contact * 1e-12)
    if parting and offset == 0:
        distance = math.inf  # a straight path past a ball at rest never returns to it
    found = travel_time(speed, decel, distance)
    return now + offset + found if found <= one_end - offset else math.inf
