"""The earliest time a distance quartic falls to zero, for one pair (compiled):
billiards.physics.numerics.roots row by row, operation for operation (its docstring
says why each step is there): the cheap certificate, the Bernstein certificate on the
whole interval then eighths, the critical points of the cubic f', the first piece that
falls, safeguarded Newton to rounding, and the step back to the last f > 0.

Polynomials are tuples of coefficients, lowest power first (numbers the compiled code
keeps in registers: an array would cost an allocation for every pair asked).
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.arithmetic import np_maximum, np_minimum, ulp
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.state import Flag
from billiards.physics.numerics.roots import _EIGHTHS, _WHOLE, NEWTON_STEPS

EPS = float(np.finfo(np.float64).eps)
# The certificate's Bernstein maps (numerics.roots'), as the loop is given them (state.
# Table): numba would keep a kernel that reads an array global out of its cache.
BERNSTEIN = (_WHOLE, _EIGHTHS)
# first_downward_root's one signature: compiled once, whatever constant `parting` a
# caller passes (numba would compile a kernel again for each literal True or False).
FIRST_DOWNWARD_ROOT = "f8(UniTuple(f8, 5), f8, f8, b1, f8, b1, UniTuple(f8[:, ::1], 2))"
_BACKOFF_STEPS = 49  # _last_positive's steps back: 0 ulps, then 1, 2, 4, ... 2^47


@kernel
def evaluate(poly: tuple[float, ...], x: float) -> float:
    """Horner's f(x), from the top coefficient down (roots.evaluate)."""
    result = poly[len(poly) - 1]
    for power in range(len(poly) - 2, -1, -1):
        result = result * x + poly[power]
    return result


@kernel
def newton_in_bracket(
    poly: tuple[float, ...], low: float, high: float, f_low: float, f_high: float
) -> float:
    """The root of a monotone polynomial between low and high (roots._newton_one)."""
    if f_high == 0:
        return high
    x = low + (high - low) * (f_low / (f_low - f_high))
    if not (low < x and x < high):
        x = 0.5 * (low + high)
    return newton_steps(poly, x, low, high, f_low < 0, NEWTON_STEPS)


@kernel
def newton_steps(
    poly: tuple[float, ...], x: float, low: float, high: float, rising: bool, steps: int
) -> float:
    """At most `steps` of safeguarded Newton from x in (low, high) (roots._newton_steps)."""
    top = len(poly) - 1
    for _ in range(steps):
        value = poly[top] * x + poly[top - 1]
        slope = poly[top]
        for power in range(top - 2, -1, -1):
            slope = slope * x + value
            value = value * x + poly[power]
        step = x - value / slope if slope != 0 else math.inf
        if (value < 0) == rising:
            low = x
        else:
            high = x
        ulps = 2.0 * ulp(abs(x))
        if value == 0 or abs(step - x) <= ulps or high - low <= ulps:
            return x
        x = step if (low < step and step < high) else 0.5 * (low + high)
    return x


@kernel
def cubic_roots_within(
    cubic: tuple[float, float, float, float], low: float, high: float
) -> tuple[float, float, float]:
    """The real roots in (low, high] of a cubic, ascending, padded with `high` (roots.
    cubic_roots_within, whose NaN padding first_downward_root turns into the end)."""
    c1, c2, c3 = cubic[1], cubic[2], cubic[3]
    a, b = 3.0 * c3, 2.0 * c2
    discriminant = b * b - 4.0 * a * c1
    q = -0.5 * (b + math.copysign(math.sqrt(np_maximum(discriminant, 0.0)), b))
    first, second = q / a, c1 / q
    if not (discriminant >= 0 and first > low and first < high):
        first = high
    if not (discriminant >= 0 and second > low and second < high):
        second = high
    lower, upper = (first, second) if first <= second else (second, first)
    breaks = (low, lower, upper, high)
    roots = (high, high, high)
    found = 0
    left = evaluate(cubic, low)
    for piece in range(3):
        right = evaluate(cubic, breaks[piece + 1])
        if (left < 0 and right >= 0) or (left > 0 and right <= 0):
            root = newton_in_bracket(cubic, breaks[piece], breaks[piece + 1], left, right)
            if root == root:  # np.sort puts NaN last: each root takes the next place
                if found == 0:
                    roots = (root, high, high)
                elif found == 1:
                    roots = (roots[0], root, high)
                else:
                    roots = (roots[0], roots[1], root)
                found += 1
        left = right
    return roots


@kernel
def _never_falls_to_zero(
    scaled: tuple[float, ...], touching: float, bernstein: tuple[np.ndarray, np.ndarray]
) -> bool:
    """roots._never_falls_to_zero for one row: the cheap certificate, then Bernstein's."""
    b0, b1, b2, b3 = scaled[0], scaled[1], scaled[2], scaled[3]
    vertex = -b2 / (2.0 * b3 if b3 > 0 else math.inf)
    vertex = np_minimum(np_maximum(vertex, 0.0), 1.0)  # np.clip
    lowest = np_minimum(np_minimum(b1, b1 + b2 + b3), b1 + (b2 + b3 * vertex) * vertex)
    if (b0 + np_minimum(lowest, 0.0) > 0) or ((b0 >= -touching) and (lowest > 0)):
        return True
    return _stays_positive(scaled, bernstein)


@kernel
def _stays_positive(scaled: tuple[float, ...], bernstein: tuple[np.ndarray, np.ndarray]) -> bool:
    """roots._stays_positive for one row: every Bernstein coefficient above the margin,
    on the whole interval, else on each eighth."""
    size = abs(scaled[0]) + abs(scaled[1]) + abs(scaled[2]) + abs(scaled[3]) + abs(scaled[4])
    margin = 16.0 * EPS * size
    if _least_above(scaled, bernstein[0], margin):
        return True
    return _least_above(scaled, bernstein[1], margin)


@kernel
def _least_above(scaled: tuple[float, ...], bernstein: np.ndarray, margin: float) -> bool:
    """Whether the least Bernstein coefficient (roots._least_coefficient) > margin
    (a NaN one is not, as numpy's min would carry it)."""
    for column in range(bernstein.shape[1]):
        coefficient = scaled[0] * bernstein[0, column] + scaled[1] * bernstein[1, column]
        for power in range(2, 5):
            coefficient += scaled[power] * bernstein[power, column]
        if not coefficient > margin:
            return False
    return True


@kernel
def _last_positive(poly: tuple[float, ...], x: float, low: float) -> float:
    """At or just below x, f > 0 (roots._last_positive): Newton may end past it."""
    step = ulp(np_maximum(abs(x), 1e-300))
    back = 0.0
    for count in range(_BACKOFF_STEPS):
        trial = np_maximum(x - step * back, low)
        if evaluate(poly, trial) > 0:
            return trial
        back = 1.0 if count == 0 else 2.0 * back  # exact powers of two
    return low


@kernel(FIRST_DOWNWARD_ROOT)
def first_downward_root(
    quartic: tuple[float, float, float, float, float],
    horizon: float,
    touching: float,
    parting: Flag,
    level: float,
    hair: Flag,
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """Earliest t in [0, horizon] where f falls to zero, inf if it does not
    (roots.first_downward_root for one row; hair: the spin model's pairs, touching and
    parting by so little that f never leaves the touching band, contact now);
    bernstein: BERNSTEIN."""
    c0, c1, c2, c3, c4 = quartic
    closing_now = (c0 <= touching) and ((c1 < 0) or ((c1 <= level) and (c2 < 0)))
    if hair and not closing_now:
        in_band = (touching - c0) * 4.0 * -c2 >= c1 * c1
        closing_now = (c0 <= touching) and (c2 < 0) and in_band and (c1 <= -c2 * horizon)
    if closing_now and not parting:
        return 0.0
    if not horizon > 0:
        return math.inf
    h = horizon
    h2 = h * h
    scaled = (c0, c1 * h, c2 * h2, c3 * (h2 * h), c4 * (h2 * h2))
    if _never_falls_to_zero(scaled, touching, bernstein):
        return math.inf
    slope = (scaled[1] * 1.0, scaled[2] * 2.0, scaled[3] * 3.0, scaled[4] * 4.0)
    critical = cubic_roots_within(slope, 0.0, 1.0)
    breaks = (
        0.0,
        critical[0] if critical[0] < 1 else 1.0,
        critical[1] if critical[1] < 1 else 1.0,
        critical[2] if critical[2] < 1 else 1.0,
        1.0,
    )
    left = evaluate(scaled, breaks[0])
    for piece in range(4):
        right = evaluate(scaled, breaks[piece + 1])
        # The first piece starts at a graze when parting: only later pieces count.
        if left > 0 and right <= 0 and not (parting and piece == 0):
            low, high = breaks[piece], breaks[piece + 1]
            x = newton_in_bracket(scaled, low, high, left, right)
            if evaluate(scaled, x) != 0:
                x = _last_positive(scaled, x, low)
            return x * h
        left = right
    return math.inf
