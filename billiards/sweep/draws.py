"""A sweep's random numbers and point grids, the same bits on every machine.

A sweep's runs.csv must not depend on which worker drew a run's inputs. numpy's
`Generator.normal` calls libm's `exp` (its ziggurat's wedges) and `np.geomspace` calls
SIMD `log`, `exp` and `power` loops, whose last bits differ between machines. Here a
uniform draw is an exact function of the generator's 64-bit integers (PCG64 is defined
bit for bit), a normal one is Wichura's AS241 quantile of it, and logarithms and powers
are series written from + - * / alone (billiards.physics.numerics.arithmetic's `log` and
`exp`, which the physics' ball friction uses too).
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.numerics.arithmetic import exp, log

_UNIT = math.ldexp(1.0, -53)


def uniform(rng: np.random.Generator, low: float, high: float) -> float:
    """A draw from [low, high): the generator's top 53 bits as a fraction (exact)."""
    bits = int(rng.integers(0, 1 << 53, dtype=np.uint64))
    return low + (high - low) * (bits * _UNIT)


def normal(rng: np.random.Generator, mean: float, deviation: float) -> float:
    """A draw from N(mean, deviation^2): the AS241 quantile of a uniform in (0, 1)."""
    bits = int(rng.integers(0, 1 << 53, dtype=np.uint64))
    return mean + deviation * normal_quantile((bits + 0.5) * _UNIT)


def geometric_points(low: float, high: float, count: int) -> tuple[float, ...]:
    """count points from low to high (0 < low < high) evenly spaced in log: low, then
    low * e^(k ln(high/low) / (count - 1)), ending exactly at high."""
    span = log(high / low)
    inner = tuple(low * exp(span * k / (count - 1)) for k in range(1, count - 1))
    return (low, *inner, high)


# Wichura, M. J. (1988), "Algorithm AS 241: The percentage points of the normal
# distribution", Applied Statistics 37 (3), 477-484: PPND16, relative error about 1e-16.
# Numerator and denominator coefficients, highest power first.
_CENTRAL = (
    (2509.0809287301226727, 33430.575583588128105, 67265.770927008700853,
     45921.953931549871457, 13731.693765509461125, 1971.5909503065514427,
     133.14166789178437745, 3.387132872796366608),
    (5226.495278852545561, 28729.085735721942674, 39307.89580009271061,
     21213.794301586595867, 5394.1960214247511077, 687.1870074920579083,
     42.313330701600911252, 1.0),
)  # fmt: skip
_NEAR_TAIL = (
    (7.7454501427834140764e-4, 0.0227238449892691845833, 0.24178072517745061177,
     1.27045825245236838258, 3.64784832476320460504, 5.7694972214606914055,
     4.6303378461565452959, 1.42343711074968357734),
    (1.05075007164441684324e-9, 5.475938084995344946e-4, 0.0151986665636164571966,
     0.14810397642748007459, 0.68976733498510000455, 1.6763848301838038494,
     2.05319162663775882187, 1.0),
)  # fmt: skip
_FAR_TAIL = (
    (2.01033439929228813265e-7, 2.71155556874348757815e-5, 0.0012426609473880784386,
     0.026532189526576123093, 0.29656057182850489123, 1.7848265399172913358,
     5.4637849111641143699, 6.6579046435011037772),
    (2.04426310338993978564e-15, 1.4215117583164458887e-7, 1.8463183175100546818e-5,
     7.868691311456132591e-4, 0.0148753612908506148525, 0.13692988092273580531,
     0.59983220655588793769, 1.0),
)  # fmt: skip


def _ratio(coefficients: tuple[tuple[float, ...], tuple[float, ...]], r: float) -> float:
    numerator, denominator = 0.0, 0.0
    for a, b in zip(*coefficients, strict=True):
        numerator = numerator * r + a
        denominator = denominator * r + b
    return numerator / denominator


def normal_quantile(p: float) -> float:
    """The standard normal's quantile at p in (0, 1) (AS241, with the logarithm above)."""
    q = p - 0.5
    if abs(q) <= 0.425:
        return q * _ratio(_CENTRAL, 0.180625 - q * q)
    r = math.sqrt(-log(p if q < 0 else 1.0 - p))
    x = _ratio(_NEAR_TAIL, r - 1.6) if r <= 5.0 else _ratio(_FAR_TAIL, r - 5.0)
    return -x if q < 0 else x
