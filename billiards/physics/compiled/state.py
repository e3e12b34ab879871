"""The compiled loop's data: one run's constants, its balls' anchors, its calendar and
its log, each a NamedTuple of numbers and flat arrays (numba passes them as structs)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from billiards.physics.compiled.laws import CushionNumbers

# A yes or no the loop passes on: a Python bool, or numpy's (np.bool_(False) is a value
# to numba, where a constant False would make it compile the callee once more).
Flag = bool | np.bool_


class Table(NamedTuple):
    """A run's constants (engine.setup.Setup) and, with pockets, its PocketTable's arrays
    (pockets.PocketTable; zero rows without)."""

    model: int  # MODEL_ROLLING or MODEL_SPIN: which motion kernels move the balls
    ball_law: int  # laws.BALL_LAW_IDS' id (laws.dispatch.ball_law)
    cushion_law: int  # laws.CUSHION_LAW_IDS' id (laws.dispatch.cushion_law)
    radius: float
    bounds: np.ndarray  # (4,) the cushion lines: r, L - r, r, W - r
    decel: float  # mu g (rolling: mu_r g)
    slide_decel: float  # the spin model's mu_s g
    spin_decel: float  # the spin model's 5 mu_sp g / (2R)
    max_time: float  # a jaw's horizon for a state without end (spin_times)
    restitution: float  # ball-ball
    retention: float  # cushion (mirror)
    cushion: CushionNumbers  # what every cushion law reads of the run
    ball_friction: tuple[float, float, float]  # the frictional law's mu = a + b exp(-c s)
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
    # Off the cloth (issue 45): whether a ball may leave it (a run whose setup drives a
    # ball into the bed: Setup.drives), and then (g, the bed's e_t, its mu_t, the
    # settling speed sqrt(2 g h)); a run that never flies reads none of them.
    flies: bool
    flight: tuple[float, float, float, float]


class Anchors(NamedTuple):
    """Every ball's last anchor, one run's: the fields both models share, then the
    rolling model's (rolling.motion.Anchors), then the spin model's (spin.law.SpinLaw);
    a model leaves the other's as they started."""

    t0: np.ndarray  # (N,)
    p0: np.ndarray  # (N, 2)
    v0: np.ndarray  # (N, 2)
    # When each ball's motion state ends by itself (inf: never; always, rolling).
    change_time: np.ndarray  # (N,)
    speed: np.ndarray  # (N,)
    direction: np.ndarray  # (N, 2)
    rest_after: np.ndarray  # (N,)
    stop_time: np.ndarray  # (N,)
    rest_position: np.ndarray  # (N, 2)
    w0: np.ndarray  # (N, 3)
    acceleration: np.ndarray  # (N, 2)
    angular: np.ndarray  # (N, 2) of w_xy
    state: np.ndarray  # (N,) int64: spin.motion.SLIDING .. REST
    duration: np.ndarray  # (N,) how long the state lasts (inf: no end)
    # The centre's height z0 and vertical velocity v_z0 at t0 (R and 0 on the cloth; a
    # flying ball's parabola starts there: compiled.airborne.flight). One array, not two:
    # each array a kernel takes costs every call that passes the anchors.
    lift: np.ndarray  # (N, 2)


class Calendar(NamedTuple):
    """Every ball's next edge and pair entries and the run's contact rules' memory
    (engine.calendar.Calendar's and engine.batch.Batch's rows of one run)."""

    edge_time: np.ndarray  # (N,)
    edge: np.ndarray  # (N,) int64
    pair_time: np.ndarray  # (N, N), [i, j] for i < j
    pair_least: np.ndarray  # (N,) each row's first least entry (pair_table)
    pair_partner: np.ndarray  # (N,) int64: its column
    gone: np.ndarray  # (N,) bool: pocketed
    contact_time: np.ndarray  # (N,) each ball's latest ball-ball contact (the TC rule)
    pressed_at: np.ndarray  # (N, N) when a pair was pressed apart (NaN: never)
    speed_scale: np.ndarray  # (1,) the fastest any ball has gone
    counts: np.ndarray  # (2,) int64: events resolved, holds
    # Balls held (laws.held), when and along what (a second holder at one instant is a
    # wedge); pairs held, when and after how many holds (held again only after another).
    held_time: np.ndarray  # (N,) -inf: never
    held_into: np.ndarray  # (N, 2)
    held_pair_time: np.ndarray  # (N, N) NaN: never
    held_pair_holds: np.ndarray  # (N, N) int64
    skip: np.ndarray  # (2,) int64: (ball, edge) the next anchoring's ball ignores, or -1
    # The anchoring an event asks for, done after it (Batch.queue, then flush): how many
    # balls and which rows' new states to log (1 << row), the balls, and each one's
    # position, velocity, spin, height and vertical velocity.
    queue: np.ndarray  # (2,) int64
    queued_balls: np.ndarray  # (2,) int64
    queued: np.ndarray  # (2, 9)
    # Room the anchoring reuses (no allocation an event): every ball's numbers the pair
    # times read (N, rolling_times.PAIR_COLUMNS), whether it was just anchored (N,).
    pair_rows: np.ndarray
    anchored: np.ndarray
    # Scratch the kernels write and read within one step (jit.INNER: they allocate
    # nothing): one ball's state at the moment (STATE_WIDTH,), one ball's edge candidates
    # (4 + J + P,), exact_sum's partials (5,).
    now: np.ndarray
    edge_times: np.ndarray
    partials: np.ndarray


class Log(NamedTuple):
    """One run's log in buffers of fixed size (batch_log.ContactLog's entries): contacts
    (time, kind, balls, speed, pocket), anchors (ball, then the model's row: t0, p0, v0,
    and the spin model's w0 and state) and motion-state changes (time, ball, state);
    `filled` counts them, and whether a buffer was too small (the run is then asked
    again)."""

    contact_time: np.ndarray  # (C,)
    contact_kind: np.ndarray  # (C,) int64: KIND_BALL, KIND_CUSHION, KIND_POCKET
    contact_balls: np.ndarray  # (C, 2) int64, the second -1 for one ball
    contact_speed: np.ndarray  # (C,)
    contact_pocket: np.ndarray  # (C,) int64, -1 for none
    segment_ball: np.ndarray  # (S,) int64
    # (S, 5) rolling: t0, p0, v0; (S, 11) spin: and w0, state, z0, vz0
    segment_rows: np.ndarray
    transition_time: np.ndarray  # (T,)
    transition_ball: np.ndarray  # (T,) int64
    transition_state: np.ndarray  # (T,) int64
    # (4,) int64: contacts, segments, 1 if a buffer overflowed, transitions
    filled: np.ndarray


KIND_BALL, KIND_CUSHION, KIND_POCKET = 0, 1, 2
KIND_NAMES = ("ball", "cushion", "pocket")


# The columns of Runs.constants.
(RADIUS, DECEL, RESTITUTION, RETENTION, MAX_TIME, MAX_EVENTS, STEPPING, DT, JAW_REACH,
 POCKETS, MODEL, SLIDE_DECEL, SPIN_DECEL, BALL_LAW, CUSHION_LAW) = range(15)  # fmt: skip
# Then the cushion laws' constants (CushionNumbers' fields after radius and retention,
# in its order) and the frictional law's mu = a + b exp(-c s).
CUSHION_RESTITUTION, CUSHION_FRICTION, CUSHION_HEIGHT, SLIDING_FRICTION = 15, 16, 17, 18
CUSHION_RESTITUTION_SPEED = 19
BALL_FRICTION_A, BALL_FRICTION_B, BALL_FRICTION_C = 20, 21, 22
# Off the cloth (Table.flies, Table.flight): 1 if a ball may leave it, then g, the bed's
# e_t and mu_t, and the settling speed.
FLIES, GRAVITY, TABLE_RESTITUTION, TABLE_FRICTION, SETTLE_SPEED = 23, 24, 25, 26, 27
CONSTANTS = 28

# A ball's state at a moment as the loop's kernels pass it (spin_motion.spin_state_at,
# Calendar.now, the loop's `at` rows): position, velocity, acceleration (2 each), spin
# (3), then height and vertical velocity (R and 0 on the cloth).
STATE_WIDTH = 11

# The motion models (Table.model): engine.motion_law.MOTION_LAWS' names, by number.
MODEL_ROLLING, MODEL_SPIN = 0, 1
MODELS = ("rolling", "spin")
# The width of a model's anchor rows in the log (the numpy law's `anchor` rows).
ROW_WIDTH = (5, 11)


class Runs(NamedTuple):
    """R runs' setups, packed: run r's balls are rows starts[r]:starts[r + 1]."""

    starts: np.ndarray  # (R + 1,) int64
    positions: np.ndarray  # (B, 2)
    velocities: np.ndarray  # (B, 2)
    spins: np.ndarray  # (B, 3)
    drives: np.ndarray  # (B,) m/s into the bed at t = 0 (Setup.drives; 0: none)
    masses: np.ndarray  # (B,)
    constants: np.ndarray  # (R, CONSTANTS), the columns above
    bounds: np.ndarray  # (R, 4)
    jaws: np.ndarray  # (R, J, 2)
    jaw_pocket: np.ndarray  # (J,) int64
    capture_normal: np.ndarray  # (R, P, 2)
    capture_level: np.ndarray  # (R, P)
    segments: np.ndarray  # (R, 4, S, 2)
    segment_count: np.ndarray  # (4,) int64
    # roots.BERNSTEIN, as two arrays.
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
    segment_rows: np.ndarray  # (R, S, ROW_WIDTH)
    transition_time: np.ndarray  # (R, T)
    transition_ball: np.ndarray  # (R, T)
    transition_state: np.ndarray  # (R, T)
    filled: np.ndarray  # (R, 4)
    outcome: np.ndarray  # (R, 2) int64
    stop: np.ndarray  # (R,)
