"""Closed-form rolling between contacts (the README's model section): from its anchor
(t0, p0, v0, just after its last contact) a ball slows at a = mu g along u until it stops,

    s(tau) = |v0| tau - a tau^2 / 2,   tau = clamp(t - t0, 0, |v0| / a)
    p(t)   = p0 + u s(tau),            v(t) = u (|v0| - a tau)

Nothing here changes its inputs, and no rounding depends on how often it is evaluated.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from billiards.physics.numerics.arithmetic import at_rows, column, norm
from billiards.physics.numerics.arrays import Constant, FloatArray, IntArray


@dataclass
class Anchors:
    """Every ball's last anchor, as flat arrays (one row a ball). Mutated by the stepper."""

    t0: FloatArray  # (N,) s
    p0: FloatArray  # (N, 2) m
    v0: FloatArray  # (N, 2) m/s
    speed: FloatArray  # (N,) |v0|
    direction: FloatArray  # (N, 2) v0 / |v0|, zero for a ball at rest
    rest_after: FloatArray  # (N,) |v0| / a: how long after t0 the ball rolls
    stop_time: FloatArray  # (N,) t0 + rest_after (inf without friction)
    decel: Constant  # m/s^2, mu g (one, or one a ball: a batch's runs may differ)
    # (N, 2) where each ball comes to rest: p0 + direction path_length(speed, decel,
    # rest_after), kept at its anchor (the pair times ask it of every ball at rest).
    rest_position: FloatArray

    @classmethod
    def start(cls, positions: FloatArray, velocities: FloatArray, decel: Constant) -> Anchors:
        count = len(positions)
        anchors = cls(
            t0=np.zeros(count),
            p0=np.array(positions, dtype=np.float64),
            v0=np.zeros((count, 2)),
            speed=np.zeros(count),
            direction=np.zeros((count, 2)),
            rest_after=np.zeros(count),
            stop_time=np.zeros(count),
            decel=decel,
            rest_position=np.array(positions, dtype=np.float64),
        )
        anchors.set(np.arange(count), 0.0, anchors.p0.copy(), np.asarray(velocities, float))
        return anchors

    def set(
        self,
        balls: IntArray,
        time: float | FloatArray,
        positions: FloatArray,
        velocities: FloatArray,
    ) -> None:
        """Re-anchor some balls at `time` (one, or one a ball; just after a contact)."""
        speed, direction = unit_directions(velocities)
        self.t0[balls] = time
        self.p0[balls] = positions
        self.v0[balls] = np.where((speed > 0)[:, None], velocities, 0.0)
        self.speed[balls] = speed
        self.direction[balls] = direction
        decel = self.decel_of(balls)
        rest_after = rest_duration(speed, decel)
        self.rest_after[balls] = rest_after
        self.stop_time[balls] = time + rest_after
        # Without friction no ball comes to rest (inf 0: NaN, never asked).
        with np.errstate(invalid="ignore", over="ignore"):
            distance = path_length(speed, decel, rest_after)
            self.rest_position[balls] = self.p0[balls] + direction * distance[:, None]

    def decel_of(self, balls: IntArray | slice) -> Constant:
        """The deceleration of `balls` (the one number, where every ball shares it)."""
        return at_rows(self.decel, balls)


def unit_directions(velocities: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Rows of velocities as speeds |v| and directions v / |v| (zero at rest)."""
    speed = norm(velocities)
    moving = speed > 0
    direction = np.zeros_like(velocities)
    direction[moving] = velocities[moving] / speed[moving, None]
    return speed, direction


def rest_duration(speed: FloatArray, decel: Constant) -> FloatArray:
    """Time to roll to a stop from `speed`: |v| / a (inf without friction, 0 at rest)."""
    if isinstance(decel, float):
        if decel > 0:
            return np.asarray(speed / decel, dtype=np.float64)
        return np.where(speed > 0, np.inf, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(decel > 0, speed / decel, np.where(speed > 0, np.inf, 0.0))


def path_length(speed: FloatArray, decel: Constant, tau: FloatArray) -> FloatArray:
    """Distance rolled `tau` seconds after the anchor (tau already clamped to the stop)."""
    return np.asarray(speed * tau - 0.5 * decel * tau * tau, dtype=np.float64)


def rolling_state(
    p0: FloatArray,
    direction: FloatArray,
    speed: FloatArray,
    t0: FloatArray,
    rest_after: FloatArray,
    decel: Constant,
    times: FloatArray | float,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The one closed-form evaluator: positions, velocities and accelerations at `times`
    (broadcasting) of paths rolling from their anchors, slowing for `rest_after` s."""
    elapsed = np.maximum(times - t0, 0.0)
    moving = elapsed < rest_after
    tau = np.where(moving, elapsed, rest_after)
    distance = path_length(speed, decel, tau)
    positions = p0 + direction * distance[..., None]
    speed_now = np.where(moving, speed - decel * tau, 0.0)
    velocities = direction * speed_now[..., None]
    accelerations = np.where(moving[..., None], column(-decel) * direction, 0.0)
    return positions, velocities, accelerations


def state_at(
    anchors: Anchors, balls: IntArray | slice, times: FloatArray | float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """rolling_state of `balls` (indices, or a slice) at `times` (one, or one a ball)."""
    return rolling_state(
        anchors.p0[balls],
        anchors.direction[balls],
        anchors.speed[balls],
        anchors.t0[balls],
        anchors.rest_after[balls],
        anchors.decel_of(balls),
        times,
    )
