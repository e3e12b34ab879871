"""Arithmetic whose every bit IEEE 754 fixes: the physics' dot products, lengths and sums.

numpy's `@`, `dot`, `einsum` and `linalg` go to BLAS and LAPACK, whose kernels (picked
by the CPU, or by OPENBLAS_CORETYPE) add in different orders; `hypot`, `power` and the
transcendentals come from libm or from SIMD loops that round differently by machine.
Elementwise + - * / and sqrt are correctly rounded on every IEEE 754 machine, so what
is built from them here, in a fixed order, gives the same float everywhere.
tests/physics/test_machine_independence.py holds the physics to these operations.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def dot(a: FloatArray, b: FloatArray) -> FloatArray:
    """a . b over the last axis (2 or 3 components), added left to right."""
    total = a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]
    if a.shape[-1] == 3:
        total = total + a[..., 2] * b[..., 2]
    return np.asarray(total)


def projections(vectors: FloatArray, axes: FloatArray) -> FloatArray:
    """Every vector (N, 2) dotted with every axis (P, 2): (N, P), as `dot` adds them."""
    return np.asarray(
        vectors[:, None, 0] * axes[None, :, 0] + vectors[:, None, 1] * axes[None, :, 1]
    )


def norm(vectors: FloatArray) -> FloatArray:
    """|v| over the last axis: sqrt(v . v). Below 1e-154 (m/s, m) a length loses bits to
    underflow, and below 1.5e-162 it is 0: callers treat such a speed as rest."""
    return np.asarray(np.sqrt(dot(vectors, vectors)))


def length(x: float, y: float) -> float:
    """|(x, y)| of two Python floats, as `norm` computes it."""
    return math.sqrt(x * x + y * y)


def total(values: FloatArray) -> float:
    """The correctly rounded sum of all values (math.fsum: independent of their order)."""
    return math.fsum(np.ravel(values).tolist())
