"""Each ball's animation keys: translations at its events and state changes only,
rotations sampled to an angle-error bound, and when a dropped ball is hidden.

All in the physics frame (x along the table, y across, z up, metres, cloth at z = 0);
billiards.export.gltf turns them into glTF's +Y-up frame.

Translations. Between two of a ball's events or state changes its centre is a
polynomial of degree 2 in time (rolling or sliding under constant friction), so a
cubic Hermite piece through the two end points, leaving the first with the ball's
velocity there and arriving with 2 (p1 - p0) / h - v0 (the quadratic's own end
slope), *is* the simulated path: glTF's CUBICSPLINE keys, with in- and out-tangents
per key, store it exactly up to float32 rounding. A ball's keys are its own events
(ball, cushion, pocket), its motion-state changes (the spin model's transitions) and,
in the rolling model, the instant it comes to rest (found from its speed, which falls
linearly). `deviation` measures the curve against the simulation.

Rotations. The orientation is read from billiards.record.trajectory (the same integration
the film turns its balls by) on a fine grid (FINE_STEP, and every path break), and a
ball's keys are chosen greedily from it: each run of grid points is spanned by one
spherical-linear (slerp) piece as long as that piece stays within `angle_bound` of
every grid orientation inside it.

A pocketed ball falls: from where it crossed the capture line its centre sinks under
gravity (billiards.record.drop.drop_heights, a quadratic again: two more keys) while
moving to the middle of its hole, and it is hidden (scale 0) once it has sunk
DROP_GONE radii, as the film takes it away.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np
import numpy.typing as npt

from billiards.record import quaternions
from billiards.record.drop import (
    DROP_GONE,
    DROP_GRAVITY,
    GONE_DEPTH,
    departures,
    flight_at,
    out_of_sight,
)
from billiards.record.orientations import rolling_orientations, spin_orientations
from billiards.record.pocket_shapes import PocketShapes
from billiards.record.trajectory import RecordedMotion, Trajectory
from billiards.stage.rack_turns import rack_turns, turns_of

FloatArray = npt.NDArray[np.float64]

# s: the grid the rotation keys are chosen from, and measured on. The slerp error of a
# ball turning about a fixed axis with angular deceleration a over h is a h^2 / 8:
# at this step and the seed's cloth (a = 3.4 rad/s^2) 3e-5 rad (0.002 degrees), far
# below any bound, so what holds on the grid holds between its points.
FINE_STEP = 1.0 / 120.0
DEFAULT_ANGLE_BOUND = 0.5  # degrees: the rotation keys' error bound by default


class ExportedMotion(RecordedMotion, Protocol):
    """A simulation result, as the export reads it (billiards.physics' SimulationResult)."""

    @property
    def method(self) -> str: ...

    def velocities_at(self, times: FloatArray) -> FloatArray:
        """Velocities (T, N, 2); at an event's own time, those just after it."""
        ...


class StateChange(Protocol):
    """A motion-state change (billiards.physics' Transition): a key of its ball."""

    @property
    def time(self) -> float: ...
    @property
    def ball(self) -> str: ...


@dataclass(frozen=True)
class BallTrack:
    """One ball's keys, physics frame."""

    ball: str
    # Translation: times (K,), values (K, 3), and for CUBICSPLINE the in- and
    # out-tangents (K, 3) in m/s; None tangents: LINEAR keys (a saved trajectory).
    times: FloatArray
    values: FloatArray
    in_tangents: FloatArray | None
    out_tangents: FloatArray | None
    # Rotation: times (R,), unit quaternions (R, 4) x, y, z, w, body to world.
    rotation_times: FloatArray
    rotations: FloatArray
    hidden_from: float | None = None  # s: hidden (scale 0) from then on; None: never


@dataclass(frozen=True)
class Tracks:
    """Every ball's keys and what they came from."""

    ball_ids: tuple[str, ...]
    radius: float
    table_size: tuple[float, float]
    balls: tuple[BallTrack, ...]
    end: float  # s: the animation's last key time
    angle_bound: float  # degrees
    exact: bool  # True: translations from the exact simulation; False: sampled (.npz)

    def hermite_positions(self, times: FloatArray) -> FloatArray:
        """Ball centres (T, N, 3) on the keys' curves (float64), clamped at the ends."""
        curves = [
            evaluate_keys(ball.times, ball.values, ball.in_tangents, ball.out_tangents, times)
            for ball in self.balls
        ]
        return np.stack(curves, axis=1)


def evaluate_keys(
    keys: FloatArray,
    values: FloatArray,
    in_tangents: FloatArray | None,
    out_tangents: FloatArray | None,
    times: FloatArray,
) -> FloatArray:
    """glTF's CUBICSPLINE (or, without tangents, LINEAR) interpolation at `times`."""
    times = np.clip(times, keys[0], keys[-1])
    if len(keys) == 1:
        return np.repeat(values[:1], len(times), axis=0)
    k = np.clip(np.searchsorted(keys, times, side="right") - 1, 0, len(keys) - 2)
    h = keys[k + 1] - keys[k]
    s = ((times - keys[k]) / h)[:, None]
    p0, p1 = values[k], values[k + 1]
    if in_tangents is None or out_tangents is None:
        return np.asarray(p0 + (p1 - p0) * s)
    m0 = out_tangents[k] * h[:, None]
    m1 = in_tangents[k + 1] * h[:, None]
    s2, s3 = s * s, s * s * s
    return np.asarray(
        (2 * s3 - 3 * s2 + 1) * p0
        + (s3 - 2 * s2 + s) * m0
        + (-2 * s3 + 3 * s2) * p1
        + (s3 - s2) * m1
    )


def linear_track(track: BallTrack, error: float) -> BallTrack:
    """The track with LINEAR translation keys within `error` (m) of its cubic curve:
    each piece (a quadratic, second derivative (in1 - out0) / h) cut into n equal
    chords, n the fewest whose chord error a (h / n)^2 / 8 is at most `error`.
    For importers that ignore CUBICSPLINE tangents (Blender 5.0's joins the values
    with its own automatic handles)."""
    if track.in_tangents is None or track.out_tangents is None:
        return track
    times = [track.times[:1]]
    for k in range(len(track.times) - 1):
        h = track.times[k + 1] - track.times[k]
        bend = float(np.linalg.norm(track.in_tangents[k + 1] - track.out_tangents[k])) / h
        count = max(1, math.ceil(h * math.sqrt(bend / (8 * error))))
        times.append(track.times[k] + h * np.arange(1, count + 1) / count)
    grid = np.concatenate(times)
    grid[-1] = track.times[-1]
    values = evaluate_keys(track.times, track.values, track.in_tangents, track.out_tangents, grid)
    return replace(track, times=grid, values=values, in_tangents=None, out_tangents=None)


# --- from a simulation ---------------------------------------------------------------


def motion_tracks(
    motion: ExportedMotion,
    transitions: Sequence[StateChange] = (),
    angle_bound: float = DEFAULT_ANGLE_BOUND,
) -> Tracks:
    """Every ball's keys from an exact simulation result, from t = 0 to its rest time."""
    ids = motion.ball_ids
    radius = motion.radius
    end = max(float(motion.rest_time), 0.0)
    drops = _drops(motion)
    flown = {departure[0]: departure for departure in departures(motion)}  # left the table
    linear = motion.method == "naive"  # stepped: straight between its steps
    key_times: list[FloatArray] = []
    for index, ball in enumerate(ids):
        stop = drops[index][0] if index in drops else end
        if index in flown:
            stop = next(e.time for e in motion.events if e.kind == "pocket" and ball in e.balls)
        own: list[float] = [0.0, stop]
        if linear:
            breaks = motion.path_breaks()
            own.extend(breaks[(breaks > 0) & (breaks < stop)].tolist())
        own.extend(e.time for e in motion.events if ball in e.balls and 0 < e.time < stop)
        own.extend(c.time for c in transitions if c.ball == ball and 0 < c.time < stop)
        key_times.append(np.unique(np.array(own)))
    if motion.model != "spin" and not linear:
        key_times = _with_rest_times(motion, key_times)

    balls = []
    grid = _rotation_grid(motion, end)
    orientations = (
        spin_orientations(motion, grid)
        if motion.model == "spin"
        else rolling_orientations(motion, grid)
    )
    # The balls lie as the film's: each object ball's number turned as the rack is set.
    start = np.column_stack([motion.positions_at(np.array([0.0]))[0], np.full(len(ids), radius)])
    orientations = quaternions.multiply(orientations, turns_of(ids, start)[None, :, :])
    for index, ball in enumerate(ids):
        keys = key_times[index]
        values, in_t, out_t = _spline_keys(motion, index, keys, linear=linear)
        hidden = None
        last = keys[-1]
        if index in drops:
            keys, values, in_t, out_t, hidden = _with_fall(
                keys, values, in_t, out_t, drops[index][1], radius
            )
        if index in flown:
            keys, values, in_t, out_t, hidden = _with_flight_off(
                keys, values, (in_t, out_t), flown[index]
            )
        within = grid <= last
        turns = choose_rotation_keys(
            grid[within], orientations[within, index], math.radians(angle_bound)
        )
        balls.append(
            BallTrack(
                ball=ball,
                times=keys,
                values=values,
                in_tangents=in_t,
                out_tangents=out_t,
                rotation_times=turns[0],
                rotations=turns[1],
                hidden_from=hidden,
            )
        )
    ends = [end, *(ball.times[-1] for ball in balls)]
    return Tracks(
        ball_ids=ids,
        radius=radius,
        table_size=motion.table_size,
        balls=tuple(balls),
        end=float(max(ends)),
        angle_bound=angle_bound,
        exact=True,
    )


def _spline_keys(
    motion: ExportedMotion, index: int, keys: FloatArray, *, linear: bool
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A ball's CUBICSPLINE translation keys at its key times: values (K, 3), in- and
    out-tangents (K, 3); for a stepped (naive) run, the chords: straight between keys."""
    flat = motion.positions_at(keys)[:, index]
    velocity = motion.velocities_at(keys)[:, index]
    height, climb = np.full(len(keys), motion.radius), np.zeros(len(keys))
    if hasattr(motion, "heights_at") and hasattr(motion, "climbs_at"):
        # A flying ball's z: the parabola between its keys (each flight's ends are keys:
        # its take-off, a contact or its landing), a quadratic as the plane's paths are.
        height, climb = motion.heights_at(keys)[:, index], motion.climbs_at(keys)[:, index]
    values = np.column_stack([flat, height])
    out_t = np.column_stack([velocity, climb])
    in_t = np.zeros_like(out_t)
    if len(keys) > 1:
        h = np.diff(keys)[:, None]
        chord = (values[1:] - values[:-1]) / h
        if linear:
            out_t[:-1] = chord
            in_t[1:] = chord
        else:  # the quadratic's slope at the piece's end
            in_t[1:] = 2 * chord - out_t[:-1]
    out_t[-1] = 0.0
    in_t[0] = out_t[0]
    return values, in_t, out_t


def _drops(motion: RecordedMotion) -> dict[int, tuple[float, FloatArray]]:
    """Pocketed balls: index -> (drop time, the centre (2,) of the hole it drops into)."""
    if motion.pockets is None:
        return {}
    shapes = PocketShapes.of(motion.pockets)
    found = {}
    for event in motion.events:
        if event.kind == "pocket" and event.pocket is not None:
            index = motion.ball_ids.index(event.balls[0])
            found[index] = (event.time, shapes.holes[shapes.names.index(event.pocket), :2])
    return found


def fall_duration(radius: float) -> float:
    """s from the capture line until a ball has sunk DROP_GONE radii and is taken away."""
    return math.sqrt(2 * DROP_GONE * radius / DROP_GRAVITY)


def _with_fall(
    keys: FloatArray,
    values: FloatArray,
    in_t: FloatArray,
    out_t: FloatArray,
    hole: FloatArray,
    radius: float,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, float]:
    """The keys of a ball that drops at keys[-1]: a last piece down into its hole."""
    duration = fall_duration(radius)
    start = values[-1]
    bottom = np.array([hole[0], hole[1], radius - DROP_GONE * radius])
    across = (bottom[:2] - start[:2]) / duration
    out_t = out_t.copy()
    out_t[-1] = [across[0], across[1], 0.0]
    arrive = np.array([across[0], across[1], -DROP_GRAVITY * duration])
    gone = keys[-1] + duration
    return (
        np.append(keys, gone),
        np.vstack([values, bottom]),
        np.vstack([in_t, arrive]),
        np.vstack([out_t, np.zeros(3)]),
        float(gone),
    )


def _with_flight_off(
    keys: FloatArray,
    values: FloatArray,
    tangents: tuple[FloatArray, FloatArray],
    departure: tuple[int, float, FloatArray, FloatArray],
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, float]:
    """The keys of a ball that left the table at keys[-1] (record.drop.departures): its
    last key moved onto its flight, and one more where it is out of sight (its
    parabola, which cubic keys with its tangents draw exactly)."""
    in_t, out_t = (each.copy() for each in tangents)
    _, time, centre, velocity = departure
    gone = out_of_sight(time, centre, velocity)
    ends, slopes = flight_at(departure, np.array([keys[-1], gone]))
    values = np.vstack([values[:-1], ends])
    if len(keys) > 1:  # the piece into the last key: its quadratic's slope there
        chord = (values[-2] - values[-3]) / (keys[-1] - keys[-2])
        in_t[-1] = 2 * chord - out_t[-2]
    out_t[-1] = slopes[0]
    return (
        np.append(keys, gone),
        values,
        np.vstack([in_t, slopes[1]]),
        np.vstack([out_t, np.zeros(3)]),
        float(gone),
    )


def _with_rest_times(motion: ExportedMotion, key_times: list[FloatArray]) -> list[FloatArray]:
    """Add the instant each ball comes to rest between two of its keys (rolling model).

    A rolling ball's speed falls linearly until it is exactly 0, so two probes with a
    non-zero speed on one piece give the stop by extrapolation; a probe that finds the
    ball already stopped halves the span searched."""
    result = []
    for index, keys in enumerate(key_times):
        found: list[float] = []
        for start, stop in itertools.pairwise(keys):
            probe = np.array([start, start + (stop - start) * (1 - 1e-9)])
            speeds = np.hypot(*motion.velocities_at(probe)[:, index].T)
            if speeds[0] == 0 or speeds[1] > 0:
                continue  # at rest all the way, or moving all the way
            low, low_speed, high = float(start), float(speeds[0]), float(probe[1])
            for _ in range(60):
                middle = 0.5 * (low + high)
                speed = float(np.hypot(*motion.velocities_at(np.array([middle]))[0, index]))
                if speed > 0:
                    rest = middle + speed * (middle - low) / (low_speed - speed)
                    found.append(min(max(rest, middle), high))
                    break
                high = middle
            else:
                found.append(low)
        result.append(np.unique(np.concatenate([keys, found])))
    return result


def _rotation_grid(motion: RecordedMotion, end: float) -> FloatArray:
    breaks = motion.path_breaks()
    grid = np.union1d(np.arange(0.0, end, FINE_STEP), breaks[(breaks > 0) & (breaks < end)])
    return np.union1d(grid, [0.0, end])


# --- the rotation keys -----------------------------------------------------------------


def slerp(first: FloatArray, second: FloatArray, weight: FloatArray) -> FloatArray:
    """Spherical linear interpolation (M, 4) along the shorter arc, as glTF's LINEAR
    rotation sampler: from `first` to `second` (rows (M, 4), or one (4,)) at `weight` (M,)."""
    dot = np.sum(first * second, axis=-1)
    sign = np.where(dot < 0, -1.0, 1.0)
    dot = np.minimum(np.abs(dot), 1.0)
    angle = np.arccos(dot)
    small = angle < 1e-9
    sine = np.where(small, 1.0, np.sin(angle))
    a = np.where(small, 1 - weight, np.sin((1 - weight) * angle) / sine)
    b = np.where(small, weight, np.sin(weight * angle) / sine) * sign
    out = a[:, None] * first + b[:, None] * second
    return np.asarray(out / np.linalg.norm(out, axis=-1, keepdims=True))


def rotation_angle(first: FloatArray, second: FloatArray) -> FloatArray:
    """Radians (M,) between rotations (rows of unit quaternions)."""
    dot = np.minimum(np.abs(np.sum(first * second, axis=1)), 1.0)
    return np.asarray(2 * np.arccos(dot))


def _span_error(times: FloatArray, orientations: FloatArray, i: int, j: int) -> float:
    """The largest angle between a slerp from grid point i to j and the grid inside."""
    if j - i < 2:
        return 0.0
    inside = slice(i + 1, j)
    weight = (times[inside] - times[i]) / (times[j] - times[i])
    count = j - i - 1
    curve = slerp(
        np.tile(orientations[i], (count, 1)), np.tile(orientations[j], (count, 1)), weight
    )
    return float(np.max(rotation_angle(curve, orientations[inside])))


def choose_rotation_keys(
    times: FloatArray, orientations: FloatArray, bound: float
) -> tuple[FloatArray, FloatArray]:
    """A subset of the grid (times (G,), quaternions (G, 4)) whose slerp pieces stay
    within `bound` radians of every grid orientation: greedily the longest piece from
    each key (galloping, then halving), signs flipped so neighbours have dot >= 0."""
    last = len(times) - 1
    chosen = [0]
    i = 0
    while i < last:
        step = 1
        while i + step * 2 <= last and _span_error(times, orientations, i, i + step * 2) <= bound:
            step *= 2
        low, high = i + step, min(i + step * 2, last)  # low fits; find the last that fits
        if high > low and _span_error(times, orientations, i, high) <= bound:
            low = high
        else:
            while high - low > 1:
                middle = (low + high) // 2
                if _span_error(times, orientations, i, middle) <= bound:
                    low = middle
                else:
                    high = middle
        chosen.append(low)
        i = low
    keys = orientations[chosen].copy()
    for k in range(1, len(keys)):
        if np.dot(keys[k - 1], keys[k]) < 0:
            keys[k] = -keys[k]
    return times[chosen].copy(), keys


# --- from a saved trajectory -----------------------------------------------------------


def trajectory_tracks(trajectory: Trajectory, angle_bound: float = DEFAULT_ANGLE_BOUND) -> Tracks:
    """Keys from a saved trajectory: its samples are all it has, so translations are
    LINEAR between them (as billiards.record.trajectory.ball_state reads it), at the samples
    where the ball moves; a ball sent below the table (GONE_DEPTH) is hidden then.
    glTF's time starts at 0: a film's lead before the shot (the balls waiting at their
    places) is left out."""
    shot = np.asarray(trajectory.times, dtype=np.float64) >= 0
    if not shot.any():
        raise ValueError("the trajectory ends before the shot starts (t = 0)")
    times = np.asarray(trajectory.times, dtype=np.float64)[shot]
    # As the film draws it: the rack's turns after the recorded rolling.
    drawn = quaternions.multiply(trajectory.orientations[shot], rack_turns(trajectory)[None, :, :])
    balls = []
    for index, ball in enumerate(trajectory.ball_ids):
        positions = trajectory.positions[shot, index]
        gone = np.flatnonzero(positions[:, 2] == GONE_DEPTH)
        visible = len(times) if len(gone) == 0 else max(int(gone[0]), 1)
        hidden = None if len(gone) == 0 else float(times[visible])
        keep = _moving_samples(positions[:visible])
        rotation_times, rotations = choose_rotation_keys(
            times[:visible],
            drawn[:visible, index],
            math.radians(angle_bound),
        )
        balls.append(
            BallTrack(
                ball=ball,
                times=times[:visible][keep],
                values=positions[:visible][keep],
                in_tangents=None,  # LINEAR keys: a saved trajectory has no tangents
                out_tangents=None,
                rotation_times=rotation_times,
                rotations=rotations,
                hidden_from=hidden,
            )
        )
    return Tracks(
        ball_ids=trajectory.ball_ids,
        radius=trajectory.radius,
        table_size=trajectory.table_size,
        balls=tuple(balls),
        end=float(times[-1]),
        angle_bound=angle_bound,
        exact=False,
    )


def _moving_samples(positions: FloatArray) -> npt.NDArray[np.bool_]:
    """Samples to keep: the ends, and each one whose neighbours are not all equal to it."""
    keep = np.ones(len(positions), dtype=bool)
    if len(positions) > 2:
        same_before = np.all(positions[1:-1] == positions[:-2], axis=1)
        same_after = np.all(positions[1:-1] == positions[2:], axis=1)
        keep[1:-1] = ~(same_before & same_after)
    return keep
