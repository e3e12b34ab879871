"""The array types every part of the physics speaks in (one home, not one a module)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]
# Balls' states as rows: positions (k, 2), velocities (k, 2), spins (k, 3).
Kinematics = tuple[FloatArray, FloatArray, FloatArray]
# The same and their accelerations (k, 2).
Dynamics = tuple[FloatArray, FloatArray, FloatArray, FloatArray]
# A constant of the physics in a batch of runs (billiards.physics.engine.batch): one
# number where every run shares it, else an array with one value a row (a ball's, or
# a pair's: its run's value). Both give the same bits in + - * / sqrt, row by row.
Constant = float | FloatArray
