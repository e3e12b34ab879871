"""When the spin model's next contacts happen: cushions, jaws, capture lines and pairs.

A ball moves on a parabola p(tau) = p0 + v0 tau + a tau^2 / 2 for the `duration` of
its motion state (spin.motion), so a cushion line is a quadratic gap (falling_roots),
a jaw the quartic |p(tau) - J|^2 = (r + rho)^2, a capture line n . p(tau) = level a
quadratic, and a pair the quartic |d(t)|^2 = (2r)^2. Edges and ties as the rolling
model's: 0-3 the cushion walls, then the jaws, then the capture lines, equal times to
the lowest index.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.engine.motion_law import Skips
from billiards.physics.numerics.arithmetic import at_rows, norm, projections
from billiards.physics.numerics.arrays import Constant, FloatArray, IntArray
from billiards.physics.numerics.roots import first_downward_root
from billiards.physics.pockets import PocketRows, PocketTable, on_cushion
from billiards.physics.rolling.contact_times import (
    PRUNE_FROM,
    WALL_AXIS,
    WALL_HIGH,
    quartic_contact,
    rounding_levels,
    separation_quartic,
)
from billiards.physics.spin.motion import ROLLING, SLIDING

# Each pair's two balls' rows of the positions and velocities (pair_contacts), and each
# pair's run's reach: given by a batch.
PairRows = tuple[IntArray, IntArray, float | FloatArray]


def cushion_roots(
    p0: FloatArray, v0: FloatArray, acceleration: FloatArray, bounds: FloatArray
) -> FloatArray:
    """Times (k, 4) after each anchor (rows (k, 2)) at which the ball's centre reaches
    each cushion line (Setup.bounds), with no limit of time, inf where never."""
    axis, side = WALL_AXIS, np.where(WALL_HIGH, 1.0, -1.0)
    p, v, a = p0[:, axis], v0[:, axis], acceleration[:, axis]
    return falling_roots(side * (bounds - p), -side * v, -0.5 * side * a)


def cushion_contacts(
    p0: FloatArray,
    v0: FloatArray,
    acceleration: FloatArray,
    t0: FloatArray,
    duration: FloatArray,
    state: IntArray,
    bounds: FloatArray,
    pockets: PocketTable | PocketRows | None,
    max_time: Constant,
    skip: Skips = None,
    reach: FloatArray | None = None,
) -> tuple[FloatArray, IntArray]:
    """Each ball's first edge contact within its motion state: absolute time (inf if
    none) and edge. skip: rows that ignore an edge; reach: each row's run's largest
    coordinate (a batch's), else of all rows."""
    tau = cushion_roots(p0, v0, acceleration, bounds)
    if pockets is not None:
        tau = pocket_edge_times(
            p0, v0, acceleration, duration, state, tau, pockets, max_time, skip, reach
        )
    tau = np.where(tau <= duration[:, None], tau, np.inf)
    wall = tau.argmin(axis=1)
    return t0 + tau[np.arange(len(t0)), wall], wall


def pocket_edge_times(
    p0: FloatArray,
    v0: FloatArray,
    acceleration: FloatArray,
    duration: FloatArray,
    state: IntArray,
    walls: FloatArray,
    pockets: PocketTable | PocketRows,
    max_time: Constant,
    skip: Skips = None,
    largest: FloatArray | None = None,
) -> FloatArray:
    """Times (k, 4 + J + P) after each anchor of the ball's contacts with every wall
    (`walls`, cushion_roots', kept where the cushion exists), jaw (within the state's
    duration, or max_time) and capture line, inf where none; only a ball sliding or
    rolling meets any. skip: as cushion_contacts'; largest (k,): its reach."""
    count = len(p0)
    half_a = 0.5 * acceleration
    walls = walls.copy()
    for wall, segments in enumerate(pockets.segments):
        other = 1 - int(WALL_AXIS[wall])
        tau = np.where(np.isfinite(walls[:, wall]), walls[:, wall], 0.0)
        hit = p0[:, other] + v0[:, other] * tau + half_a[:, other] * tau * tau
        covered = on_cushion(hit, segments)
        walls[:, wall] = np.where(covered, walls[:, wall], np.inf)
    jaw_count = pockets.jaws.shape[-2]
    relative = np.empty((count, jaw_count, 3, 2))
    relative[:, :, 0] = p0[:, None, :] - pockets.jaws  # one table's (J, 2), or each row's
    relative[:, :, 1] = v0[:, None, :]
    relative[:, :, 2] = half_a[:, None, :]
    rows = relative.reshape(-1, 3, 2)
    reach = pockets.jaw_reach * pockets.jaw_reach
    if not isinstance(reach, float):  # each row's table's: a (ball, jaw) row each
        reach = np.repeat(reach, jaw_count)
    coefficients, speed_squared = separation_quartic(rows, reach)
    horizon = np.where(np.isfinite(duration), duration, max_time)
    size = float(np.abs(p0).max()) if largest is None else np.repeat(largest, jaw_count)
    touching, level = rounding_levels(reach, size, speed_squared)
    # A ball touching a jaw at a normal speed within rounding and curving away grazes
    # it: only a return counts. (A gripping law leaves a few ulps of normal speed of
    # either sign; taken as closing, the contact came back at one instant for ever.)
    grazing = (coefficients[:, 0] <= touching) & (np.abs(coefficients[:, 1]) <= level)
    grazing &= coefficients[:, 2] > 0
    grazes = grazing if grazing.any() else None
    jaws = first_downward_root(
        coefficients, np.repeat(horizon, jaw_count), touching, grazes, level
    ).reshape(count, jaw_count)
    normal = pockets.capture_normal
    gap = pockets.capture_level - projections(p0, normal)  # to each capture line
    captures = falling_roots(gap, -projections(v0, normal), -projections(half_a, normal))
    edges = np.concatenate((walls, jaws, captures), axis=1)
    moving = (state == SLIDING) | (state == ROLLING)
    edges[~moving] = np.inf
    if skip is not None:
        skipping = skip[0].nonzero()[0]
        edges[skipping, skip[1][skipping]] = np.inf
    return edges


def pair_contacts(
    first: IntArray,
    second: IntArray,
    now: float | FloatArray,
    position: FloatArray,
    velocity: FloatArray,
    acceleration: FloatArray,
    state: IntArray,
    change_time: FloatArray,
    cushion_time: FloatArray,
    radius: Constant,
    max_time: Constant,
    parting: bool = False,
    rows_of: PairRows | None = None,
) -> FloatArray:
    """Absolute time of each pair's next contact after `now` (one, or its run's), within
    both balls' motion states and before either's next edge contact; inf if none.
    parting: only a return counts. rows_of: a batch's rows for its runs' balls only."""
    times = np.full(len(first), np.inf)
    if rows_of is None:
        row_first, row_second = first, second
        reach: float | FloatArray = float(np.abs(position).max())
    else:
        row_first, row_second, reach = rows_of
    moves = (state == SLIDING) | (state == ROLLING)
    rows = (moves[row_first] | moves[row_second]).nonzero()[0]
    if rows.size == 0:
        return times
    reach, radius, max_time = at_rows(reach, rows), at_rows(radius, rows), at_rows(max_time, rows)
    now_rows = at_rows(now, rows)
    first, second = first[rows], second[rows]
    row_first, row_second = row_first[rows], row_second[rows]
    ends = np.minimum(change_time[first], cushion_time[first])
    horizon = np.minimum(ends, np.minimum(change_time[second], cushion_time[second])) - now_rows
    horizon = np.where(np.isfinite(horizon), horizon, max_time)
    motion = np.empty((len(position), 3, 2))  # each row's (position, velocity, acceleration / 2)
    motion[:, 0], motion[:, 1] = position, velocity
    motion[:, 2] = np.where(moves[:, None], 0.5 * acceleration, 0.0)
    # Only the pairs that may touch: a gap within |v| t + |k| t^2 each, with rolling's
    # margin (asked only of many pairs, as in rolling.contact_times.pair_contacts).
    if len(rows) >= PRUNE_FROM:
        window = np.maximum(horizon, 0.0)
        speed, curve = norm(motion[:, 1]), norm(motion[:, 2])
        speeds, curves = speed[row_first] + speed[row_second], curve[row_first] + curve[row_second]
        travel = speeds * window + curves * (window * window)
        gap = norm(motion[row_first, 0] - motion[row_second, 0]) - 2.0 * radius
        near = (~(gap > travel * (1.0 + 1e-6) + 1e-9)).nonzero()[0]
        rows = rows[near]
        row_first, row_second, horizon = row_first[near], row_second[near], horizon[near]
        radius, reach = at_rows(radius, near), at_rows(reach, near)
        now_rows = at_rows(now_rows, near)
    relative = motion[row_first] - motion[row_second]
    found = quartic_contact(relative, np.maximum(horizon, 0.0), radius, reach, parting, hair=True)
    times[rows] = now_rows + found
    return times


def falling_roots(c: FloatArray, b: FloatArray, a: FloatArray) -> FloatArray:
    """The first root tau > 0 where each gap g(tau) = c + b tau + a tau^2 falls to zero
    (c >= 0 while apart; roots as q / a and c / q), inf where none, 0 where closed (by
    rounding) and closing. Any broadcast shape."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        discriminant = b * b - 4.0 * a * c
        root = np.sqrt(np.maximum(discriminant, 0.0))
        q = -0.5 * (b + np.where(b >= 0, root, -root))
        first = np.where(a != 0, q / a, np.inf)
        second = np.where(q != 0, c / q, np.inf)
        candidates = np.stack((first, second))
        # Only where the gap falls (a ball leaving the cushion it just left: none).
        falling = b + 2.0 * a * candidates < 0
    real = (discriminant >= 0) & np.isfinite(candidates) & (candidates > 0) & falling
    candidates = np.where(real, candidates, np.inf)
    tau = candidates.min(axis=0)
    # On (or by rounding past) the line and heading into it: now.
    return np.asarray(np.where((c <= 0) & ((b < 0) | ((b == 0) & (a < 0))), 0.0, tau))
