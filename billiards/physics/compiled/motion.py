"""The rolling model's closed-form motion, compiled (rolling.motion, ball by ball):
anchoring a ball, and its position, velocity and acceleration at any time."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.state import Anchors


@kernel
def rest_duration(speed: float, decel: float) -> float:
    """|v| / a (rolling.motion.rest_duration): inf without friction, 0 at rest."""
    if decel > 0:
        return speed / decel
    return math.inf if speed > 0 else 0.0


@kernel
def path_length(speed: float, decel: float, tau: float) -> float:
    """Distance rolled `tau` seconds after the anchor (rolling.motion.path_length)."""
    return speed * tau - 0.5 * decel * tau * tau


@kernel
def anchor(
    anchors: Anchors, ball: int, time: float, x: float, y: float, vx: float, vy: float, decel: float
) -> None:
    """Re-anchor one ball at `time` (rolling.motion.Anchors.set)."""
    speed = math.sqrt(vx * vx + vy * vy)
    moving = speed > 0
    anchors.t0[ball] = time
    anchors.p0[ball, 0], anchors.p0[ball, 1] = x, y
    anchors.v0[ball, 0] = vx if moving else 0.0
    anchors.v0[ball, 1] = vy if moving else 0.0
    anchors.speed[ball] = speed
    ux = vx / speed if moving else 0.0
    uy = vy / speed if moving else 0.0
    anchors.direction[ball, 0], anchors.direction[ball, 1] = ux, uy
    rest_after = rest_duration(speed, decel)
    anchors.rest_after[ball] = rest_after
    anchors.stop_time[ball] = time + rest_after
    distance = path_length(speed, decel, rest_after)
    anchors.rest_position[ball, 0] = x + ux * distance
    anchors.rest_position[ball, 1] = y + uy * distance


# The anchors' arrays the rolling motion reads (t0, p0, speed, direction, rest_after):
# handed to a call made for every ball instead of all of Anchors (each array a compiled
# call takes costs it two atomic reference counts).
RollingAnchors = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]


@inline
def rolling_anchors(anchors: Anchors) -> RollingAnchors:
    return (anchors.t0, anchors.p0, anchors.speed, anchors.direction, anchors.rest_after)


@inline
def state_at(anchors: Anchors, ball: int, time: float, decel: float, out: np.ndarray) -> None:
    """out (6,) = position, velocity, acceleration of `ball` at `time` (rolling_state)."""
    rolling_state(rolling_anchors(anchors), ball, time, decel, out)


@kernel
def rolling_state(
    anchors: RollingAnchors, ball: int, time: float, decel: float, out: np.ndarray
) -> None:
    """out (6,) = position, velocity, acceleration of `ball` at `time`
    (rolling.motion.rolling_state)."""
    t0, p0, speeds, directions, rests = anchors
    elapsed = np_maximum(time - t0[ball], 0.0)
    rest_after = rests[ball]
    moving = elapsed < rest_after
    tau = elapsed if moving else rest_after
    speed = speeds[ball]
    distance = path_length(speed, decel, tau)
    speed_now = speed - decel * tau if moving else 0.0
    for axis in range(2):
        direction = directions[ball, axis]
        out[axis] = p0[ball, axis] + direction * distance
        out[2 + axis] = direction * speed_now
        out[4 + axis] = -decel * direction if moving else 0.0


@inline
def remaining(anchors: RollingAnchors, ball: int, time: float) -> float:
    """How long `ball` still rolls after `time` (rolling.law.RollingLaw.pair_times)."""
    t0, _, _, _, rests = anchors
    return np_maximum(rests[ball] - (time - t0[ball]), 0.0)
