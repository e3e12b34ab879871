"""Cushion contact laws: what a cushion does to a ball's velocity (the README's model
section, "cushions"; the source report's eq. 2.7)."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.motion import FloatArray, IntArray


def mirror(
    velocities: FloatArray, axes: IntArray, retention: float
) -> tuple[FloatArray, FloatArray]:
    """Mirror each ball's velocity component normal to its cushion (along `axes`: 0 for
    an x cushion, 1 for a y cushion) and keep `retention` of the kinetic energy.

    velocities (k, 2). Returns (new velocities, approach speeds into the cushions)."""
    rows = np.arange(len(velocities))
    bounced = np.array(velocities, dtype=np.float64)
    approach = np.abs(bounced[rows, axes])
    bounced[rows, axes] = -bounced[rows, axes]
    return bounced * math.sqrt(retention), approach
