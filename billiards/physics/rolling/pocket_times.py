"""When a rolling ball next meets a table with pockets: a cushion, a jaw or a capture line.

The path is straight, so with s the distance along it a cushion line is linear in s
(counted only where the cushion exists), a jaw |p0 + u s - J|^2 = (r + rho)^2 a
quadratic, a capture line n . p = level linear (heading in); the time follows from
contact_times.travel_time. Edges: 0-3 the cushion walls, then the jaws, then the
capture lines; equal times go to the lowest index (the tie rule's order).

Only balls whose path could meet a pocket pay for the jaws and capture lines: a path
that starts and ends on the table, and ends where a cushion exists if on a cushion
line, meets neither (jaw circles lie beyond the cushion lines, and n . p is linear
along the path, so it cannot cross a capture line and come back).
"""

from __future__ import annotations

import numpy as np

from billiards.physics.engine.motion_law import Skips
from billiards.physics.numerics.arithmetic import column, projections
from billiards.physics.numerics.arrays import FloatArray, IntArray
from billiards.physics.pockets import PocketRows, PocketTable, on_cushion
from billiards.physics.rolling.contact_times import (
    WALL_AXIS,
    cushion_contacts,
    first_touch,
    travel_time,
    wall_distances,
)
from billiards.physics.rolling.motion import Anchors, path_length

# How close (m) a path's end may come to a pocket's features and still skip the full
# check: generous against the rounding of the end point (the full check is exact).
MARGIN = 1e-9


def edge_contacts(
    anchors: Anchors,
    balls: IntArray,
    bounds: FloatArray,
    pockets: PocketTable | PocketRows,
    skip: Skips = None,
) -> tuple[FloatArray, IntArray]:
    """Each ball's next contact time with the table's edges, and which edge. bounds (4,)
    or each ball's (k, 4); pockets: one table's, or a row a ball. skip (rows, edges):
    those of `balls` (a mask) each ignore an edge (grazed, or held on)."""
    times, walls = cushion_contacts(anchors, balls, bounds)
    # Which balls' paths (to their first cushion line, or rest) could meet a pocket.
    p0 = anchors.p0[balls]
    tau = np.where(np.isfinite(times), times - anchors.t0[balls], anchors.rest_after[balls])
    tau = np.where(np.isfinite(tau), tau, 0.0)  # no friction and no cushion: stays put
    rolled = path_length(anchors.speed[balls], anchors.decel_of(balls), tau)[:, None]
    end = p0 + anchors.direction[balls] * rolled
    x, y = p0[:, 0], p0[:, 1]
    inside_x = (x >= bounds[..., 0] - MARGIN) & (x <= bounds[..., 1] + MARGIN)
    inside = inside_x & (y >= bounds[..., 2] - MARGIN) & (y <= bounds[..., 3] + MARGIN)
    past = (projections(end, pockets.capture_normal) > pockets.capture_level - MARGIN).any(axis=1)
    along = end[np.arange(len(balls)), 1 - WALL_AXIS[walls]]
    in_gap = np.ones(len(balls), dtype=bool)
    for wall, segments in enumerate(pockets.segments):
        in_gap &= ~((walls == wall) & on_cushion(along, segments, MARGIN))
    near = ~inside | past | (np.isfinite(times) & in_gap)
    if skip is not None:
        near |= skip[0]
    rows = near.nonzero()[0]
    if rows.size:
        kept = None if skip is None else (skip[0][rows], skip[1][rows])
        if isinstance(pockets, PocketRows):
            pockets = pockets.at(rows)
        if bounds.ndim == 2:
            bounds = bounds[rows]
        times[rows], walls[rows] = _full_contacts(anchors, balls[rows], bounds, pockets, kept)
    return times, walls


def _full_contacts(
    anchors: Anchors,
    balls: IntArray,
    bounds: FloatArray,
    pockets: PocketTable | PocketRows,
    skip: Skips,
) -> tuple[FloatArray, IntArray]:
    """Each ball's next wall, jaw or capture line, as distances along the path, then times."""
    p0, u = anchors.p0[balls], anchors.direction[balls]
    # Walls: the line's distance, counted where the hit point has a cushion.
    wall_distance = wall_distances(p0, u, bounds)
    for wall, segments in enumerate(pockets.segments):
        other = 1 - WALL_AXIS[wall]
        finite = np.isfinite(wall_distance[:, wall])
        hit = p0[:, other] + u[:, other] * np.where(finite, wall_distance[:, wall], 0.0)
        covered = on_cushion(hit, segments)
        wall_distance[:, wall] = np.where(covered, wall_distance[:, wall], np.inf)
    # Jaws: |D + u s|^2 = R^2 for every (ball, jaw), D = p0 - J, R = r + rho: first_touch's
    # root with b^2 - c computed as R^2 - (u x D)^2 (the same number: at a graze a small
    # difference of small numbers, so the time stays accurate to the miss's rounding).
    reach = column(pockets.jaw_reach * pockets.jaw_reach)  # one, or a row a ball
    separation = p0[:, None, :] - pockets.jaws
    d_x, d_y, u_x, u_y = separation[..., 0], separation[..., 1], u[:, None, 0], u[:, None, 1]
    b, c = u_x * d_x + u_y * d_y, d_x * d_x + d_y * d_y - reach
    cross = u_x * d_y - u_y * d_x
    jaw_distance = first_touch(b, c, reach - cross * cross, reach * 1e-12)
    # Capture lines: n . (p0 + u s) = level, heading in.
    into = projections(u, pockets.capture_normal)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        capture_distance = (pockets.capture_level - projections(p0, pockets.capture_normal)) / into
    capture_distance = np.where(into > 0, np.maximum(capture_distance, 0.0), np.inf)
    distance = np.concatenate((wall_distance, jaw_distance, capture_distance), axis=1)
    # A ball at rest has no direction (u = 0): it meets nothing.
    distance = np.where((anchors.speed[balls] > 0)[:, None], distance, np.inf)
    if skip is not None:
        skipping = skip[0].nonzero()[0]
        distance[skipping, skip[1][skipping]] = np.inf
    times = travel_time(anchors.speed[balls][:, None], column(anchors.decel_of(balls)), distance)
    edge = times.argmin(axis=1)
    return anchors.t0[balls] + times[np.arange(len(balls)), edge], edge.astype(np.intp)
