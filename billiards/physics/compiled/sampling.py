"""Runs sampled from their logs, compiled: each run's ball centres at given times, bit for
bit what its SimulationResult's positions_at gives (engine.result), without the result.

A ball's segment in force at a time is the last it logged at or before it, else its first
(AnchoredMotion.segments_at); the segment moves it there in closed form, by its model's
own kernels (motion.rolling_state for rolling.result.RollingMotion, spin_motion's
state_laws and spin_state for spin.result.SpinMotion); on a table without pockets the
centre is clamped to the cushion lines (SimulationResult.positions_at). With the samples,
whether every number the run's result would hold is finite (simulation.finite's: its rest
time and final positions, its contacts' times and speeds, its motion's anchors and
constants), so that a caller needs the result only when one is not.
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum, np_minimum
from billiards.physics.compiled.jit import entry, kernel
from billiards.physics.compiled.motion import rest_duration, rolling_state
from billiards.physics.compiled.spin_motion import spin_state, state_laws
from billiards.physics.compiled.state import (
    DECEL,
    MODEL,
    MODEL_SPIN,
    POCKETS,
    RADIUS,
    ROW_WIDTH,
    SLIDE_DECEL,
    SPIN_DECEL,
    Logs,
    Runs,
)

# The room a run's sampling works in, made once for all the runs of a call (the inner
# kernels allocate nothing: jit.INNER): the log's segments grouped by ball (order,
# first, filled), each segment as the motion kernels read it (motion.RollingAnchors:
# t0, p0, speed, direction, rest_after; spin_motion.SpinAnchors: t0, duration, p0, v0,
# acceleration, w0, angular), a ball's state at one time (9,), the final positions
# (2 N_max) and the rest time (1,).
Room = tuple[
    tuple[np.ndarray, np.ndarray, np.ndarray],
    tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    tuple[np.ndarray, np.ndarray, np.ndarray],
]


@entry
def sample_many(
    runs: Runs,
    logs: Logs,
    rest_time: np.ndarray,
    times: np.ndarray,
    time_starts: np.ndarray,
    out: np.ndarray,
    out_starts: np.ndarray,
    finite: np.ndarray,
) -> None:
    """Run r's ball centres at times[time_starts[r]:time_starts[r + 1]] (T of them) into
    out[out_starts[r]:out_starts[r + 1]], as (T, N, 2) in C order, and finite[r]: whether
    every number of its result is (its result's rest time rest_time[r]). A run whose log
    overflowed is skipped (it runs again with more room)."""
    segments = logs.segment_rows.shape[1]
    balls = 1
    for run in range(len(runs.constants)):
        balls = max(balls, runs.starts[run + 1] - runs.starts[run])
    t0 = np.empty(segments)
    p0 = np.empty((segments, 2))
    room = (
        (
            np.empty(segments, dtype=np.int64),
            np.empty(balls + 1, dtype=np.int64),
            np.empty(balls, dtype=np.int64),
        ),
        (t0, p0, np.empty(segments), np.empty((segments, 2)), np.empty(segments)),
        (
            t0,
            np.empty(segments),
            p0,
            np.empty((segments, 2)),
            np.empty((segments, 2)),
            np.empty((segments, 3)),
            np.empty((segments, 2)),
        ),
        (np.empty(9), np.empty(2 * balls), np.empty(1)),
    )
    for run in range(len(runs.constants)):
        if logs.filled[run, 2] != 0:
            continue
        own = times[time_starts[run] : time_starts[run + 1]]
        block = out[out_starts[run] : out_starts[run + 1]]
        finite[run] = sample_run(runs, logs, run, rest_time[run], own, block, room)


@kernel
def sample_run(
    runs: Runs,
    logs: Logs,
    run: int,
    rest_time: float,
    times: np.ndarray,
    out: np.ndarray,
    room: Room,
) -> bool:
    """One run's centres at `times` into out (T * N * 2, flat); whether its result is
    finite."""
    constants = runs.constants[run]
    balls = runs.starts[run + 1] - runs.starts[run]
    contacts, anchors = logs.filled[run, 0], logs.filled[run, 1]
    rows = logs.segment_rows[run]
    spin = constants[MODEL] == MODEL_SPIN
    finite = math.isfinite(rest_time) and math.isfinite(constants[DECEL])
    if spin:
        for column in (RADIUS, SLIDE_DECEL, SPIN_DECEL):
            finite = finite and math.isfinite(constants[column])
    for contact in range(contacts):
        finite = finite and math.isfinite(logs.contact_time[run, contact])
        finite = finite and math.isfinite(logs.contact_speed[run, contact])
    # The motion's anchors: t0, p0, v0 (and the spin model's w0; its state is an integer).
    width = ROW_WIDTH[MODEL_SPIN] - 1 if spin else ROW_WIDTH[0]
    for segment in range(anchors):
        for column in range(width):
            finite = finite and math.isfinite(rows[segment, column])
    grouping, rolling, spinning, (state, final, ended) = room
    segments_by_ball(logs.segment_ball[run], anchors, balls, grouping)
    # The final positions: at the rest time.
    ended[0] = rest_time
    if spin:
        spin_segments(rows, anchors, constants, spinning)
        sample_spin(spinning, grouping, balls, times, constants[SPIN_DECEL], state, out)
        sample_spin(spinning, grouping, balls, ended, constants[SPIN_DECEL], state, final)
    else:
        rolling_segments(rows, anchors, constants[DECEL], rolling)
        sample_rolling(rolling, grouping, balls, times, constants[DECEL], state, out)
        sample_rolling(rolling, grouping, balls, ended, constants[DECEL], state, final)
    if constants[POCKETS] == 0:
        bounds = runs.bounds[run]
        clamp_to(out, len(out), bounds)
        clamp_to(final, 2 * balls, bounds)
    for at in range(2 * balls):
        finite = finite and math.isfinite(final[at])
    return finite


@kernel
def segments_by_ball(
    segment_ball: np.ndarray,
    count: int,
    balls: int,
    grouping: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> None:
    """The log's first `count` segments grouped by ball, each ball's in the order logged
    (a stable counting sort), into grouping = (order, first, filled): ball b's segments
    are order[first[b]:first[b + 1]]."""
    order, first, filled = grouping
    first[: balls + 1] = 0
    for segment in range(count):
        first[segment_ball[segment] + 1] += 1
    for ball in range(balls):
        first[ball + 1] += first[ball]
        filled[ball] = first[ball]
    for segment in range(count):
        ball = segment_ball[segment]
        order[filled[ball]] = segment
        filled[ball] += 1


@kernel
def segment_at(
    grouping: tuple[np.ndarray, np.ndarray, np.ndarray], t0: np.ndarray, ball: int, time: float
) -> int:
    """The segment of `ball` in force at `time`: the last it logged at or before it, else
    its first (AnchoredMotion.segments_at; a ball's t0 never falls)."""
    order, first, _ = grouping
    low, high = first[ball], first[ball + 1]
    while low < high:  # the first of its segments anchored after `time`
        middle = (low + high) // 2
        if t0[order[middle]] <= time:
            low = middle + 1
        else:
            high = middle
    return order[max(low - 1, first[ball])]


@kernel
def rolling_segments(
    rows: np.ndarray,
    count: int,
    decel: float,
    rolling: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
) -> None:
    """The first `count` logged rows (t0, p0, v0) as motion.RollingAnchors, a row a
    segment (rolling.result.RollingMotion.segment_state: unit_directions, rest_duration)."""
    t0, p0, speed, direction, rest_after = rolling
    for segment in range(count):
        vx, vy = rows[segment, 3], rows[segment, 4]
        t0[segment] = rows[segment, 0]
        p0[segment, 0], p0[segment, 1] = rows[segment, 1], rows[segment, 2]
        speed[segment] = math.sqrt(vx * vx + vy * vy)
        moving = speed[segment] > 0
        direction[segment, 0] = vx / speed[segment] if moving else 0.0
        direction[segment, 1] = vy / speed[segment] if moving else 0.0
        rest_after[segment] = rest_duration(speed[segment], decel)


@kernel
def sample_rolling(
    rolling: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    grouping: tuple[np.ndarray, np.ndarray, np.ndarray],
    balls: int,
    times: np.ndarray,
    decel: float,
    state: np.ndarray,
    out: np.ndarray,
) -> None:
    """Every ball's centre at each time into out (T * N * 2, flat): rolling_state."""
    for sample in range(len(times)):
        time = times[sample]
        for ball in range(balls):
            segment = segment_at(grouping, rolling[0], ball, time)
            rolling_state(rolling, segment, time, decel, state)
            at = (sample * balls + ball) * 2
            out[at], out[at + 1] = state[0], state[1]


@kernel
def spin_segments(
    rows: np.ndarray,
    count: int,
    constants: np.ndarray,
    spinning: tuple[
        np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
    ],
) -> None:
    """The first `count` logged rows (t0, p0, v0, w0, state) as spin_motion.SpinAnchors,
    a row a segment (spin.result.SpinMotion.segment_spin_state: state_laws of each)."""
    t0, duration, p0, v0, acceleration, w0, angular = spinning
    decels = (constants[RADIUS], constants[SLIDE_DECEL], constants[DECEL], constants[SPIN_DECEL])
    for segment in range(count):
        row = rows[segment]
        t0[segment] = row[0]
        p0[segment, 0], p0[segment, 1] = row[1], row[2]
        v0[segment, 0], v0[segment, 1] = row[3], row[4]
        w0[segment, 0], w0[segment, 1], w0[segment, 2] = row[5], row[6], row[7]
        ax, ay, alpha_x, alpha_y, lasts = state_laws(
            int(row[8]), (row[3], row[4]), (row[5], row[6], row[7]), decels
        )
        acceleration[segment, 0], acceleration[segment, 1] = ax, ay
        angular[segment, 0], angular[segment, 1] = alpha_x, alpha_y
        duration[segment] = lasts


@kernel
def sample_spin(
    spinning: tuple[
        np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
    ],
    grouping: tuple[np.ndarray, np.ndarray, np.ndarray],
    balls: int,
    times: np.ndarray,
    spin_decel: float,
    state: np.ndarray,
    out: np.ndarray,
) -> None:
    """Every ball's centre at each time into out (T * N * 2, flat): spin_state."""
    for sample in range(len(times)):
        time = times[sample]
        for ball in range(balls):
            segment = segment_at(grouping, spinning[0], ball, time)
            spin_state(spinning, segment, time, spin_decel, state)
            at = (sample * balls + ball) * 2
            out[at], out[at + 1] = state[0], state[1]


@kernel
def clamp_to(out: np.ndarray, count: int, bounds: np.ndarray) -> None:
    """The first `count` numbers of out (x, y pairs) clamped to the cushion lines (r,
    L - r, r, W - r), as np.clip clamps them (SimulationResult.positions_at)."""
    for at in range(0, count, 2):
        out[at] = np_minimum(np_maximum(out[at], bounds[0]), bounds[1])
        out[at + 1] = np_minimum(np_maximum(out[at + 1], bounds[2]), bounds[3])
