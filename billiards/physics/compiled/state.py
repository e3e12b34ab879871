"""The compiled loop's data: one run's constants, its balls' anchors, its calendar and
its log, each a NamedTuple of numbers and flat arrays (numba passes them as structs)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

# A yes or no the loop passes on: a Python bool, or numpy's (np.bool_(False) is a value
# to numba, where a constant False would make it compile the callee once more).
Flag = bool | np.bool_


class Table(NamedTuple):
    """A run's constants (engine.setup.Setup) and, with pockets, its PocketTable's arrays
    (pockets.PocketTable; zero rows without)."""

    radius: float
    bounds: np.ndarray  # (4,) the cushion lines: r, L - r, r, W - r
    decel: float  # mu g
    restitution: float  # ball-ball
    retention: float  # cushion (mirror)
    masses: np.ndarray  # (N,)
    pockets: bool
    jaws: np.ndarray  # (J, 2)
    jaw_pocket: np.ndarray  # (J,) int64
    jaw_reach: float  # r + rho
    capture_normal: np.ndarray  # (P, 2)
    capture_level: np.ndarray  # (P,)
    segments: np.ndarray  # (4, S, 2) where each wall's cushion exists (padded)
    segment_count: np.ndarray  # (4,) int64: each wall's own S
    bernstein: tuple[np.ndarray, np.ndarray]  # the root certificate's (roots.BERNSTEIN)


class Anchors(NamedTuple):
    """Every ball's last anchor (rolling.motion.Anchors, one run's)."""

    t0: np.ndarray  # (N,)
    p0: np.ndarray  # (N, 2)
    v0: np.ndarray  # (N, 2)
    speed: np.ndarray  # (N,)
    direction: np.ndarray  # (N, 2)
    rest_after: np.ndarray  # (N,)
    stop_time: np.ndarray  # (N,)
    rest_position: np.ndarray  # (N, 2)


class Calendar(NamedTuple):
    """Every ball's next edge and pair entries and the run's contact rules' memory
    (engine.calendar.Calendar's and engine.batch.Batch's rows of one run)."""

    edge_time: np.ndarray  # (N,)
    edge: np.ndarray  # (N,) int64
    pair_time: np.ndarray  # (N, N), [i, j] for i < j
    gone: np.ndarray  # (N,) bool: pocketed
    contact_time: np.ndarray  # (N,) each ball's latest ball-ball contact (the TC rule)
    pressed_at: np.ndarray  # (N, N) when a pair was pressed apart (NaN: never)
    speed_scale: np.ndarray  # (1,) the fastest any ball has gone
    counts: np.ndarray  # (2,) int64: events resolved, holds
    skip: np.ndarray  # (2,) int64: (ball, edge) the next anchoring's ball ignores, or -1
    # Room the anchoring reuses (no allocation an event): every ball's numbers the pair
    # times read (N, rolling_times.PAIR_COLUMNS), whether it was just anchored (N,).
    pair_rows: np.ndarray
    anchored: np.ndarray


class Log(NamedTuple):
    """One run's log in buffers of fixed size (batch_log.ContactLog's entries): contacts
    (time, kind, balls, speed, pocket) and anchors (ball, t0, p0, v0); `filled` counts
    both, and whether a buffer was too small (the run is then asked again)."""

    contact_time: np.ndarray  # (C,)
    contact_kind: np.ndarray  # (C,) int64: KIND_BALL, KIND_CUSHION, KIND_POCKET
    contact_balls: np.ndarray  # (C, 2) int64, the second -1 for one ball
    contact_speed: np.ndarray  # (C,)
    contact_pocket: np.ndarray  # (C,) int64, -1 for none
    segment_ball: np.ndarray  # (S,) int64
    segment_rows: np.ndarray  # (S, 5): t0, p0, v0
    filled: np.ndarray  # (3,) int64: contacts, segments, 1 if a buffer overflowed


KIND_BALL, KIND_CUSHION, KIND_POCKET = 0, 1, 2
KIND_NAMES = ("ball", "cushion", "pocket")


# The columns of Runs.constants.
(RADIUS, DECEL, RESTITUTION, RETENTION, MAX_TIME, MAX_EVENTS, STEPPING, DT, JAW_REACH,
 POCKETS) = range(10)  # fmt: skip


class Runs(NamedTuple):
    """R runs' setups, packed: run r's balls are rows starts[r]:starts[r + 1]."""

    starts: np.ndarray  # (R + 1,) int64
    positions: np.ndarray  # (B, 2)
    velocities: np.ndarray  # (B, 2)
    masses: np.ndarray  # (B,)
    constants: np.ndarray  # (R, 10), the columns above
    bounds: np.ndarray  # (R, 4)
    jaws: np.ndarray  # (R, J, 2)
    jaw_pocket: np.ndarray  # (J,) int64
    capture_normal: np.ndarray  # (R, P, 2)
    capture_level: np.ndarray  # (R, P)
    segments: np.ndarray  # (R, 4, S, 2)
    segment_count: np.ndarray  # (4,) int64
    # roots.BERNSTEIN, as two arrays (numba's threads take no tuple of arrays).
    bernstein_whole: np.ndarray  # (5, 5)
    bernstein_eighths: np.ndarray  # (5, 33)


class Logs(NamedTuple):
    """R runs' logs (Log, a row a run) and outcomes: events resolved and steps taken
    (R, 2), when the last ball stops (R,)."""

    contact_time: np.ndarray  # (R, C)
    contact_kind: np.ndarray  # (R, C)
    contact_balls: np.ndarray  # (R, C, 2)
    contact_speed: np.ndarray  # (R, C)
    contact_pocket: np.ndarray  # (R, C)
    segment_ball: np.ndarray  # (R, S)
    segment_rows: np.ndarray  # (R, S, 5)
    filled: np.ndarray  # (R, 3)
    outcome: np.ndarray  # (R, 2) int64
    stop: np.ndarray  # (R,)
