"""When the rolling model's next contacts happen: cushions (a quadratic in time) and
ball pairs (a quartic). All times are absolute; asked only when a ball is re-anchored.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.numerics.arithmetic import at_rows, column, dot, norm
from billiards.physics.numerics.arrays import Constant, FloatArray, IntArray
from billiards.physics.numerics.roots import first_downward_root
from billiards.physics.rolling.motion import Anchors, state_at


def travel_time(speed: FloatArray, decel: Constant, distance: FloatArray) -> FloatArray:
    """Time to roll `distance` from `speed` (inf if the ball stops first): |v| t - a t^2
    / 2 = d in the cancellation-free form 2d / (|v| + sqrt(|v|^2 - 2ad))."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        # Frictionless, an unreachable wall gives 0 * inf = NaN: a miss, inf below.
        discriminant = speed * speed - 2.0 * decel * distance
        time = 2.0 * distance / (speed + np.sqrt(np.maximum(discriminant, 0.0)))
    return np.where((discriminant >= 0) & (speed > 0), time, np.inf)


def cushion_contacts(
    anchors: Anchors, balls: IntArray, bounds: FloatArray
) -> tuple[FloatArray, IntArray]:
    """Each ball's next cushion time and wall index, from its anchor; bounds (Setup.
    bounds): (4,), or each ball's own (k, 4)."""
    distance = wall_distances(anchors.p0[balls], anchors.direction[balls], bounds)
    times = travel_time(anchors.speed[balls][:, None], column(anchors.decel_of(balls)), distance)
    wall = times.argmin(axis=1)
    return anchors.t0[balls] + times[np.arange(len(balls)), wall], wall


# Cushion walls 0..3, in the order that breaks exact ties (x before y): the ball
# centre touches one when x = r, x = L - r, y = r or y = W - r (Setup.bounds).
WALL_AXIS = np.array([0, 0, 1, 1])
WALL_HIGH = np.array([False, True, False, True])


def wall_distances(p0: FloatArray, direction: FloatArray, bounds: FloatArray) -> FloatArray:
    """How far (k, 4) each path from p0 along `direction` goes to each cushion line; 0
    on (or by rounding just past) a line and heading into it, inf heading away."""
    along = direction[:, WALL_AXIS]
    heading = np.where(WALL_HIGH, along > 0, along < 0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        distance = (bounds - p0[:, WALL_AXIS]) / along
    return np.where(heading, np.maximum(distance, 0.0), np.inf)


# The balls' states at their runs' `now` (rolling.law.RollingLaw): positions, velocities,
# accelerations (B, 2) and how long each still rolls (B,), each pair's rows into them,
# and each pair's run's reach (the largest coordinate of its balls now).
PairStates = tuple[
    FloatArray, FloatArray, FloatArray, FloatArray, IntArray, IntArray, float | FloatArray
]


# The fewest pairs for which pair_contacts first rules out those too far apart to meet.
PRUNE_FROM = 64


def pair_contacts(
    anchors: Anchors,
    first: IntArray,
    second: IntArray,
    now: float | FloatArray,
    cushion_time: FloatArray,
    radius: Constant,
    parting: bool = False,
    states: PairStates | None = None,
) -> FloatArray:
    """Next contact time of each pair after `now` (one, or its run's), inf if none before
    either's next cushion contact. parting: only a return counts. states: a batch's, else
    computed here. Piecewise: both rolling until the first stops (a quartic in time),
    then one rolling towards one at rest (a quadratic in the distance rolled)."""
    times = np.full(len(first), np.inf)
    if states is None:
        # Every ball's state now, once: pairs index into it.
        position, velocity, acceleration = state_at(anchors, slice(None), now)
        remaining = np.maximum(anchors.rest_after - (now - anchors.t0), 0.0)
        row_first, row_second = first, second
        reach: float | FloatArray = float(np.abs(position).max())
    else:
        position, velocity, acceleration, remaining, row_first, row_second, reach = states
    remaining_first, remaining_second = remaining[row_first], remaining[row_second]
    horizon = np.minimum(cushion_time[first], cushion_time[second]) - now
    horizon = np.where(np.isinf(horizon), np.maximum(remaining_first, remaining_second), horizon)
    one_end = np.minimum(np.maximum(remaining_first, remaining_second), horizon)
    # Pairs too far apart to meet in their window, ruled out before the quartic (for a
    # run's few pairs that costs more than it saves; about half of a break's go): a gap
    # wider than both can roll (at most speed now times the time still rolled), by a
    # margin (1e-6 of that, and a nanometre) that keeps every pair the quartic could find.
    if len(first) >= PRUNE_FROM:
        speed = norm(velocity)
        gap = norm(position[row_first] - position[row_second]) - 2.0 * radius
        rolls_first = speed[row_first] * np.minimum(remaining_first, one_end)
        travel = rolls_first + speed[row_second] * np.minimum(remaining_second, one_end)
        with np.errstate(invalid="ignore"):  # 0 * inf, frictionless: NaN, kept open
            one_end = np.where(gap > travel * (1.0 + 1e-6) + 1e-9, 0.0, one_end)
    both_end = np.minimum(np.minimum(remaining_first, remaining_second), one_end)

    # Piece 1: both balls rolling, from now: the quartic.
    rows = (both_end > 0).nonzero()[0]
    if rows.size:
        # Each ball's (position, velocity, acceleration / 2), then each pair's relative
        # (D, W, K): d(t) = D + W t + K t^2.
        motion = np.empty((len(position), 3, 2))
        motion[:, 0], motion[:, 1] = position, velocity
        np.multiply(acceleration, 0.5, out=motion[:, 2])
        relative = motion[row_first[rows]] - motion[row_second[rows]]
        # D carries the rounding of the positions, none larger than `reach`.
        found = quartic_contact(
            relative, both_end[rows], at_rows(radius, rows), at_rows(reach, rows), parting
        )
        times[rows] = at_rows(now, rows) + found

    # Piece 2: one ball rolling towards one at rest (from when it stopped, or from now).
    rows = ((one_end > both_end) & np.isinf(times)).nonzero()[0]
    if rows.size:
        first_moves = remaining_first[rows] > remaining_second[rows]
        mover = np.where(first_moves, first[rows], second[rows])
        mover_row = np.where(first_moves, row_first[rows], row_second[rows])
        rester = np.where(first_moves, second[rows], first[rows])
        mover_now = (position[mover_row], velocity[mover_row], acceleration[mover_row])
        window = (both_end[rows], one_end[rows])
        now_rows, radius_rows = at_rows(now, rows), at_rows(radius, rows)
        times[rows] = _one_rolling_times(
            anchors, mover, rester, mover_now, now_rows, window, radius_rows, parting
        )
    return times


def _one_rolling_times(
    anchors: Anchors,
    mover: IntArray,
    rester: IntArray,
    mover_now: tuple[FloatArray, FloatArray, FloatArray],
    now: float | FloatArray,
    window: tuple[FloatArray, FloatArray],
    radius: Constant,
    parting: bool,
) -> FloatArray:
    """Absolute times a rolling ball meets one at rest within the window, inf if not."""
    both_end, one_end = window
    offset = both_end[:, None]
    position, velocity, acceleration = mover_now
    # The mover is still rolling at the piece's start: plain kinematics from now.
    start = position + velocity * offset + 0.5 * acceleration * (offset * offset)
    decel = anchors.decel_of(mover)
    speed = anchors.speed[mover] - decel * (now + offset[:, 0] - anchors.t0[mover])
    contact = 4.0 * radius * radius
    # How far it rolls to touch the one at rest: |D + u s|^2 = (2r)^2 (first_touch).
    separation = start - anchors.rest_position[rester]
    b = dot(anchors.direction[mover], separation)
    c = dot(separation, separation) - contact
    distance = first_touch(b, c, b * b - c, contact * 1e-12)
    if parting:
        # A straight path past a ball at rest never returns to it.
        distance = np.where(offset[:, 0] == 0, np.inf, distance)
    found = travel_time(speed, decel, distance)
    return np.where(found <= one_end - offset[:, 0], now + offset[:, 0] + found, np.inf)


def first_touch(
    b: FloatArray, c: FloatArray, discriminant: FloatArray, touching: Constant
) -> FloatArray:
    """The first root of s^2 + 2 b s + c = 0 as c / (-b + sqrt(b^2 - c)), inf if it misses
    or moves away (b >= 0), 0 if touching (c <= `touching`) and closing."""
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = c / (-b + np.sqrt(np.maximum(discriminant, 0.0)))
    hits = (b < 0) & (discriminant >= 0)
    distance = np.where(hits, np.maximum(distance, 0.0), np.inf)
    return np.where((c <= touching) & (b < 0), 0.0, distance)


def quartic_contact(
    relative: FloatArray,
    length: FloatArray,
    radius: Constant,
    reach: float | FloatArray,
    parting: bool = False,
    hair: bool = False,
) -> FloatArray:
    """First contact within [0, length] of two balls on uniformly accelerated paths,
    relative (M, 3, 2) rows of (D, W, K): d(t) = D + W t + K t^2."""
    coefficients, speed_squared = separation_quartic(relative, 4.0 * radius * radius)
    touching, level = rounding_levels(4.0 * radius * radius, reach, speed_squared)
    partings = np.full(len(length), parting) if parting else None
    return first_downward_root(coefficients, length, touching, partings, level, hair)


def rounding_levels(
    reach_squared: Constant, size: float | FloatArray, speed_squared: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """A separation quartic's rounding levels (first_downward_root's touching and level)
    for rows of M: f(0) within 1e-12 of reach^2, and f'(0) = 2 D.W within a few ulps of
    |W| times the positions' size (the largest coordinate: |D| <= 2 sqrt(2) size)."""
    count = len(speed_squared)
    touching = reach_squared * 1e-12
    touching = np.full(count, touching) if isinstance(touching, float) else touching
    return touching, 32.0 * np.finfo(np.float64).eps * size * np.sqrt(speed_squared)


def separation_quartic(
    relative: FloatArray, reach_squared: Constant
) -> tuple[FloatArray, FloatArray]:
    """|d(t)|^2 - reach^2 by powers of t (M, 5), for rows (M, 3, 2) of (D, W, K), and
    |W|^2 (M,); reach^2 one, or one a row. Dot products as x1 y1 + x2 y2, not BLAS."""
    # dx, dy, wx, wy, kx, ky, each contiguous (a copy of the transpose).
    dx, dy, wx, wy, kx, ky = relative.reshape(len(relative), 6).T.copy()
    speed_squared = wx * wx + wy * wy
    coefficients = np.empty((5, len(relative)))
    coefficients[0] = (dx * dx + dy * dy) - reach_squared
    coefficients[1] = 2.0 * (dx * wx + dy * wy)
    coefficients[2] = speed_squared + 2.0 * (dx * kx + dy * ky)
    coefficients[3] = 2.0 * (wx * kx + wy * ky)
    coefficients[4] = kx * kx + ky * ky
    return coefficients.T, speed_squared
