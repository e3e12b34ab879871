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

# Below this a sum of squares has lost bits to underflow (a 5e-324 m/s velocity squares
# to 0): such vectors are measured scaled up by an exact power of two, then down.
_TINY_SQUARE = math.ldexp(1.0, -960)
_UP = math.ldexp(1.0, 600)
_DOWN = math.ldexp(1.0, -600)


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
    """|v| over the last axis: sqrt(v . v), exact to rounding down to denormal inputs."""
    squared = dot(vectors, vectors)
    lengths = np.sqrt(squared)
    if squared.size and squared.min() < _TINY_SQUARE:  # rare: only then the mask
        tiny = squared < _TINY_SQUARE
        lengths = np.array(lengths, dtype=np.float64)
        scaled = vectors[tiny] * _UP
        lengths[tiny] = np.sqrt(dot(scaled, scaled)) * _DOWN
    return np.asarray(lengths)


def length(x: float, y: float) -> float:
    """|(x, y)| of two Python floats, as `norm` computes it."""
    squared = x * x + y * y
    if squared < _TINY_SQUARE:
        x, y = x * _UP, y * _UP
        return math.sqrt(x * x + y * y) * _DOWN
    return math.sqrt(squared)


def total(values: FloatArray) -> float:
    """The correctly rounded sum of all values (math.fsum: independent of their order)."""
    return math.fsum(np.ravel(values).tolist())
