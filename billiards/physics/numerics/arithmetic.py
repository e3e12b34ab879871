"""Arithmetic whose every bit IEEE 754 fixes: the physics' dot products, lengths and sums.

numpy's `@`, `dot`, `einsum` and `linalg` go to BLAS and LAPACK, whose kernels add in
different orders by CPU; `hypot`, `power` and the transcendentals round differently by
machine. Elementwise + - * / and sqrt are correctly rounded everywhere, so what is built
from them here, in a fixed order, gives the same float on every machine
(tests/physics/test_machine_independence.py holds the physics to them).
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.numerics.arrays import BoolArray, Constant, FloatArray, IntArray

# ln 2 split so that k * _LN2_HIGH is exact for |k| < 2^11 (Cody and Waite's reduction).
_LN2_HIGH = 0.693145751953125
_LN2_LOW = 1.4286068203094172321e-06
_SQRT_HALF = 0.70710678118654752440


def log(x: float) -> float:
    """Natural logarithm of x > 0, to about an ulp: x = m 2^e with m in [sqrt(1/2),
    sqrt(2)) (frexp is exact), then ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.172,
    by its series to s^41 (the next term is below 2^-60 of the sum)."""
    if not x > 0 or not math.isfinite(x):
        raise ValueError(f"log of {x!r}: expected a finite number > 0")
    mantissa, exponent = math.frexp(x)
    if mantissa < _SQRT_HALF:
        mantissa, exponent = 2.0 * mantissa, exponent - 1
    s = (mantissa - 1.0) / (mantissa + 1.0)
    square = s * s
    series = 0.0
    for power in range(41, 0, -2):
        series = series * square + 1.0 / power
    return (exponent * _LN2_HIGH + 2.0 * s * series) + exponent * _LN2_LOW


def exp(x: float) -> float:
    """e^x to about an ulp (for |x| < 700): x = k ln 2 + r, |r| <= ln 2 / 2, then e^r
    by its Taylor series to r^24, scaled by 2^k exactly."""
    k = math.floor(x / (_LN2_HIGH + _LN2_LOW) + 0.5)
    r = (x - k * _LN2_HIGH) - k * _LN2_LOW
    series = 1.0
    for power in range(24, 0, -1):
        series = 1.0 + series * r / power
    return math.ldexp(series, k)


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
    """|v| over the last axis: sqrt(v . v); 0 below 1.5e-162 (callers: rest)."""
    return np.asarray(np.sqrt(dot(vectors, vectors)))


def length(x: float, y: float) -> float:
    """|(x, y)| of two Python floats, as `norm` computes it."""
    return math.sqrt(x * x + y * y)


def total(values: FloatArray) -> float:
    """The correctly rounded sum of all values (math.fsum: independent of their order)."""
    return math.fsum(np.ravel(values).tolist())


def at_rows(value: Constant, rows: IntArray | BoolArray | slice) -> Constant:
    """A constant's values at `rows` (the one number itself where all rows share it)."""
    return value if isinstance(value, float) else np.asarray(value[rows])


def column(value: Constant) -> Constant:
    """A constant shaped to scale rows of vectors (k, d): its values as a column (k, 1)."""
    return value if isinstance(value, float) else np.asarray(value[..., None])
