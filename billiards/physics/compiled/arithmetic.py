"""The compiled physics' arithmetic: numpy's and Python's own operations, bit for bit.

Each function here is the one the numpy physics calls, spelled out in + - * / sqrt in
the same order (billiards.physics.numerics.arithmetic): numpy's maximum and minimum
(which keep the second argument on a tie, so that 0.0 and -0.0 come out as numpy's),
Python's max and min (the first), math.fsum's exactly rounded sum, math.ulp, Python's
float division (which raises on a zero divisor), and the project's own exp.
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.jit import kernel
from billiards.physics.numerics.arithmetic import _LN2_HIGH, _LN2_LOW


@kernel
def np_maximum(a: float, b: float) -> float:
    """np.maximum(a, b): NaN if either is, else the larger, `b` on a tie."""
    if a != a:
        return a
    return a if a > b else b


@kernel
def np_minimum(a: float, b: float) -> float:
    """np.minimum(a, b): NaN if either is, else the smaller, `b` on a tie."""
    if a != a:
        return a
    return a if a < b else b


@kernel
def py_max(a: float, b: float) -> float:
    """Python's max(a, b): `a` unless b > a."""
    return b if b > a else a


@kernel
def py_min(a: float, b: float) -> float:
    """Python's min(a, b): `a` unless b < a."""
    return b if b < a else a


@kernel
def ulp(x: float) -> float:
    """math.ulp(x) of x >= 0: the gap to the next float up (nextUp, exact)."""
    return math.nextafter(x, math.inf) - x


@kernel
def length(x: float, y: float) -> float:
    """|(x, y)| as numerics.arithmetic.length computes it."""
    return math.sqrt(x * x + y * y)


@kernel
def exact_sum(values: tuple[float, ...], partials: np.ndarray) -> float:
    """math.fsum(values): the correctly rounded sum (CPython's algorithm, Shewchuk's
    partials and its round-half-even repair, step for step); partials: room for
    len(values) + 1 numbers."""
    count = 0
    special = 0.0
    infinities = 0.0
    for value in values:
        x = value
        kept = 0
        for index in range(count):
            y = partials[index]
            if abs(x) < abs(y):
                x, y = y, x
            high = x + y
            low = y - (high - x)
            if low != 0.0:
                partials[kept] = low
                kept += 1
            x = high
        count = kept
        if x != 0.0:
            if not math.isfinite(x):
                if math.isinf(value):
                    infinities += value
                special += value
                count = 0
            else:
                partials[count] = x
                count += 1
    if special != 0.0:
        return infinities if math.isnan(infinities) else special
    return _rounded(partials, count)


@kernel
def _rounded(partials: np.ndarray, count: int) -> float:
    """fsum's last step: the partials' sum, rounded half-even as one number."""
    high = 0.0
    low = 0.0
    if count > 0:
        count -= 1
        high = partials[count]
        while count > 0:
            x = high
            count -= 1
            y = partials[count]
            high = x + y
            low = y - (high - x)
            if low != 0.0:
                break
        if count > 0 and (
            (low < 0.0 and partials[count - 1] < 0.0) or (low > 0.0 and partials[count - 1] > 0.0)
        ):
            y = low * 2.0
            x = high + y
            if y == x - high:
                high = x
    return high


@kernel
def quotient(dividend: float, divisor: float) -> float:
    """dividend / divisor of two Python floats: ZeroDivisionError on a zero divisor, as
    Python raises it (numba's numpy error model gives inf or NaN instead)."""
    if divisor == 0.0:
        raise ZeroDivisionError("float division by zero")
    return dividend / divisor


@kernel
def exp(x: float) -> float:
    """numerics.arithmetic.exp, step for step: x = k ln 2 + r, e^r by its Taylor series
    to r^24, scaled by 2^k exactly."""
    k = math.floor(x / (_LN2_HIGH + _LN2_LOW) + 0.5)
    r = (x - k * _LN2_HIGH) - k * _LN2_LOW
    series = 1.0
    for power in range(24, 0, -1):
        series = 1.0 + series * r / power
    return math.ldexp(series, k)
