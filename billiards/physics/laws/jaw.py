"""Jaw contact laws: what a cushion's rounded end (a pocket's jaw) does to a ball.

A jaw is the same rubber as its cushion, met along the line of centres instead of a
cushion's fixed normal, so each cushion law has its jaw form here under the same name.
"""

from __future__ import annotations

import math

from billiards.physics.arithmetic import dot
from billiards.physics.motion import FloatArray


def mirror(
    velocities: FloatArray, into: FloatArray, retention: float
) -> tuple[FloatArray, FloatArray]:
    """The seed's cushion law about any normal: mirror each ball's velocity component
    along its unit normal `into` (k, 2, pointing into the jaw) and keep `retention` of
    the kinetic energy. Returns (new velocities, approach speeds into the jaws)."""
    approach = dot(velocities, into)
    bounced = velocities - 2.0 * approach[:, None] * into
    return bounced * math.sqrt(retention), approach
