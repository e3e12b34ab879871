"""When the next contacts happen: cushions (a quadratic) and ball pairs (a quartic).

All times are absolute. Both functions are evaluated only when a ball is re-anchored
(after its own contact), so their results do not depend on any time step.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.motion import Anchors, FloatArray, IntArray, path_length, state_at
from billiards.physics.roots import first_downward_root

# Cushion walls, in the order that breaks exact ties (x before y): the ball centre
# touches a cushion when x = r, x = L - r, y = r or y = W - r.
WALLS = ("x_low", "x_high", "y_low", "y_high")


def travel_time(speed: FloatArray, decel: float, distance: FloatArray) -> FloatArray:
    """Time to roll `distance` from `speed` (inf if the ball stops first).

    Solves |v| t - a t^2 / 2 = d in the cancellation-free form 2d / (|v| + sqrt(|v|^2 - 2ad)).
    """
    discriminant = speed * speed - 2.0 * decel * distance
    with np.errstate(divide="ignore", invalid="ignore"):
        time = 2.0 * distance / (speed + np.sqrt(np.maximum(discriminant, 0.0)))
    return np.where((discriminant >= 0) & (speed > 0), time, np.inf)


def cushion_contacts(
    anchors: Anchors, balls: IntArray, bounds: FloatArray
) -> tuple[FloatArray, IntArray]:
    """Each ball's next cushion time and wall index, from its anchor.

    bounds = (r, L - r, r, W - r): the lines a ball centre cannot cross.
    """
    axis = _WALL_AXIS
    along = anchors.direction[balls][:, axis]  # (k, 4): velocity direction along each wall's axis
    heading = np.where(_WALL_HIGH, along > 0, along < 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = (bounds - anchors.p0[balls][:, axis]) / along
    # A ball on (or, by rounding, just past) the wall and heading into it: now.
    distance = np.where(heading, np.maximum(distance, 0.0), np.inf)
    times = travel_time(anchors.speed[balls][:, None], anchors.decel, distance)
    wall = np.argmin(times, axis=1)
    return anchors.t0[balls] + times[np.arange(len(balls)), wall], wall


_WALL_AXIS = np.array([0, 0, 1, 1])
_WALL_HIGH = np.array([False, True, False, True])


def rest_positions(anchors: Anchors, balls: IntArray) -> FloatArray:
    """Where balls come to rest (or are now, if they already have)."""
    distance = path_length(anchors.speed[balls], anchors.decel, anchors.rest_after[balls])
    return np.asarray(anchors.p0[balls] + anchors.direction[balls] * distance[:, None])


def pair_contacts(
    anchors: Anchors,
    first: IntArray,
    second: IntArray,
    now: float,
    cushion_time: FloatArray,
    radius: float,
) -> FloatArray:
    """Next contact time of each pair (first[k], second[k]) after `now`; inf if none
    before either ball's next cushion contact (which re-anchors it and asks again).

    A pair's relative motion is piecewise: both rolling until the first stops (a
    quartic in time), then one rolling towards one at rest (a quadratic in the
    distance rolled). Pairs whose balls both rest are never examined.
    """
    times = np.full(len(first), np.inf)
    remaining_first = _remaining_roll(anchors, first, now)
    remaining_second = _remaining_roll(anchors, second, now)
    horizon = np.minimum(cushion_time[first], cushion_time[second]) - now
    horizon = np.where(np.isinf(horizon), np.maximum(remaining_first, remaining_second), horizon)
    both_end = np.minimum(np.minimum(remaining_first, remaining_second), horizon)
    one_end = np.minimum(np.maximum(remaining_first, remaining_second), horizon)
    contact = 4.0 * radius * radius
    touching = contact * 1e-12

    # Piece 1: both balls rolling, from now: the quartic.
    rows = np.flatnonzero(both_end > 0)
    if rows.size:
        start = np.full(rows.size, now)
        p1, v1, a1 = state_at(anchors, first[rows], start)
        p2, v2, a2 = state_at(anchors, second[rows], start)
        times[rows] = now + _both_rolling_contact(p1, v1, a1, p2, v2, a2, both_end[rows], radius)

    # Piece 2: one ball rolling, the other at rest (from when it stopped, or from now).
    rows = np.flatnonzero((one_end > both_end) & np.isinf(times))
    if rows.size:
        start_offset = both_end[rows]
        first_moves = remaining_first[rows] > remaining_second[rows]
        mover = np.where(first_moves, first[rows], second[rows])
        rester = np.where(first_moves, second[rows], first[rows])
        position, _, _ = state_at(anchors, mover, now + start_offset)
        speed = anchors.speed[mover] - anchors.decel * (now + start_offset - anchors.t0[mover])
        distance = _distance_to_touch(
            position - rest_positions(anchors, rester), anchors.direction[mover], contact, touching
        )
        found = travel_time(speed, anchors.decel, distance)
        times[rows] = np.where(
            found <= one_end[rows] - start_offset, now + start_offset + found, np.inf
        )
    return times


def _distance_to_touch(
    separation: FloatArray, direction: FloatArray, contact: float, touching: float
) -> FloatArray:
    """How far a ball rolling along `direction` goes before it touches a ball at rest.

    |D + u s|^2 = (2r)^2 is s^2 + 2 b s + c = 0 with b = u.D, c = |D|^2 - (2r)^2; the
    first root in the cancellation-free form c / (-b + sqrt(b^2 - c)). inf if it misses
    or moves away; 0 if it already touches and closes.
    """
    b = _dot(direction, separation)
    c = _dot(separation, separation) - contact
    discriminant = b * b - c
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = c / (-b + np.sqrt(np.maximum(discriminant, 0.0)))
    hits = (b < 0) & (discriminant >= 0)
    distance = np.where(hits, np.maximum(distance, 0.0), np.inf)
    return np.where((c <= touching) & (b < 0), 0.0, distance)


def _remaining_roll(anchors: Anchors, balls: IntArray, now: float) -> FloatArray:
    elapsed = now - anchors.t0[balls]
    return np.maximum(anchors.rest_after[balls] - elapsed, 0.0)


def _both_rolling_contact(
    p1: FloatArray,
    v1: FloatArray,
    a1: FloatArray,
    p2: FloatArray,
    v2: FloatArray,
    a2: FloatArray,
    length: FloatArray,
    radius: float,
) -> FloatArray:
    """First contact within [0, length] of two balls on uniformly decelerated paths."""
    result = np.full(len(length), np.inf)
    reach = _swept_segments_apart(p1, v1, a1, p2, v2, a2, length, radius) > 2 * radius * (1 + 1e-9)
    rows = np.flatnonzero(~reach)
    if rows.size == 0:
        return result
    d = p1[rows] - p2[rows]
    w = v1[rows] - v2[rows]
    k = 0.5 * (a1[rows] - a2[rows])
    contact = 4.0 * radius * radius
    coefficients = np.stack(
        [
            _dot(d, d) - contact,
            2.0 * _dot(d, w),
            _dot(w, w) + 2.0 * _dot(d, k),
            2.0 * _dot(w, k),
            _dot(k, k),
        ],
        axis=1,
    )
    result[rows] = first_downward_root(
        coefficients, length[rows], np.full(rows.size, contact * 1e-12)
    )
    return result


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.asarray(a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1])


def _swept_segments_apart(
    p1: FloatArray,
    v1: FloatArray,
    a1: FloatArray,
    p2: FloatArray,
    v2: FloatArray,
    a2: FloatArray,
    length: FloatArray,
    radius: float,
) -> FloatArray:
    """Smallest distance between the straight segments the two centres sweep
    (or a lower bound on it where that already exceeds 2r).

    Each ball moves monotonically along a line during a piece, so balls whose
    segments stay more than 2r apart cannot touch: the cheap test that makes most
    far-apart pairs cost nothing.
    """
    t = length[:, None]
    end1 = p1 + v1 * t + 0.5 * a1 * t * t
    end2 = p2 + v2 * t + 0.5 * a2 * t * t
    # Bounding circles of the two segments first: far-apart pairs stop here, cheaply.
    centre_gap = 0.5 * (p1 + end1 - p2 - end2)
    spread = 0.5 * (_norm(end1 - p1) + _norm(end2 - p2))
    circles_apart = _norm(centre_gap) - spread
    near = np.flatnonzero(circles_apart <= 2 * radius)
    result = circles_apart
    result[near] = segment_distance(p1[near], end1[near], p2[near], end2[near])
    return result


def _norm(vectors: FloatArray) -> FloatArray:
    return np.asarray(np.hypot(vectors[:, 0], vectors[:, 1]))


def segment_distance(a0: FloatArray, a1: FloatArray, b0: FloatArray, b1: FloatArray) -> FloatArray:
    """Distance between segments a0-a1 and b0-b1, row by row (Ericson, RTCD 5.1.9)."""
    da = a1 - a0
    db = b1 - b0
    r = a0 - b0
    aa = _dot(da, da)
    bb = _dot(db, db)
    f = _dot(db, r)
    c = _dot(da, r)
    ab = _dot(da, db)
    denominator = aa * bb - ab * ab
    with np.errstate(divide="ignore", invalid="ignore"):
        # General case: closest points of the infinite lines, clamped to segment a ...
        s = np.where(denominator > 0, np.clip((ab * f - c * bb) / denominator, 0.0, 1.0), 0.0)
        t = np.where(bb > 0, (ab * s + f) / bb, 0.0)
        # ... then re-clamped to segment b, with s recomputed for the clamped t.
        s = np.where(t < 0, np.clip(-c / aa, 0.0, 1.0), s)
        s = np.where(t > 1, np.clip((ab - c) / aa, 0.0, 1.0), s)
        t = np.clip(t, 0.0, 1.0)
        # Degenerate segments (a ball at rest): a point against a segment, or two points.
        t = np.where(aa > 0, t, np.where(bb > 0, np.clip(f / bb, 0.0, 1.0), 0.0))
        s = np.where(aa > 0, np.where(bb > 0, s, np.clip(-c / aa, 0.0, 1.0)), 0.0)
    gap = a0 + da * s[:, None] - b0 - db * t[:, None]
    return np.asarray(np.hypot(gap[:, 0], gap[:, 1]))
