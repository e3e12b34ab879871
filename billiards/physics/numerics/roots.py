"""The earliest time a distance polynomial drops to zero, for many pairs at once.

Two balls on uniformly accelerated paths are d(t) = D + W t + K t^2 apart, and contact
is the first time the quartic f(t) = |d(t)|^2 - (2r)^2 falls from positive to zero.
The critical points of f (roots of the cubic f') cut [0, h] into at most four monotone
pieces; f at a critical point is accurate to second order in the point's error, so
"does f dip below zero" is exact to rounding even for a graze. The first piece with
f(left) > 0 >= f(right) holds the contact, which safeguarded Newton refines to
rounding from the positive side (the balls never overlap at the returned time).
Coefficient arrays have shape (M, 5), lowest power first.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from billiards.physics.numerics.arrays import BoolArray, FloatArray

NEWTON_STEPS = 60
# Up to this many rows, Newton runs on Python floats (see _newton_in_bracket).
PYTHON_ROWS = 8
# How many ulps _last_positive steps back: 0, then doubling (exact powers of two).
_BACKOFF_ULPS = np.concatenate([[0.0], np.ldexp(1.0, np.arange(48))])


def cubic_roots_within(coefficients: FloatArray, low: float, high: float) -> FloatArray:
    """Real roots (M, 3) in (low, high] of many cubics g (M, 4), ascending, NaN-padded.

    No eigenvalue solver (LAPACK's bits depend on the CPU), no cbrt or arccos (libm
    and SIMD loops differ by machine): g's critical points (the quadratic g' in closed
    form) cut [low, high] into monotone pieces; a piece whose ends differ in sign holds
    one root, which safeguarded Newton finds to rounding with + - * / only."""
    count = len(coefficients)
    c1, c2, c3 = coefficients[:, 1], coefficients[:, 2], coefficients[:, 3]
    # g'(x) = c1 + 2 c2 x + 3 c3 x^2 in the cancellation-free form (a line when c3 = 0).
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a, b = 3.0 * c3, 2.0 * c2
        discriminant = b * b - 4.0 * a * c1
        q = -0.5 * (b + np.copysign(np.sqrt(np.maximum(discriminant, 0.0)), b))
        turns = np.stack((q / a, c1 / q), axis=1)
    turns = np.where((discriminant >= 0)[:, None] & (turns > low) & (turns < high), turns, high)
    breaks = np.empty((count, 4))
    breaks[:, 0] = low
    breaks[:, 1:3] = np.sort(turns, axis=1)
    breaks[:, 3] = high
    values = evaluate(coefficients, breaks)
    left, right = values[:, :-1], values[:, 1:]
    # A root in (left end, right end]: a zero at a break counts for the piece it ends.
    bracketed = ((left < 0) & (right >= 0)) | ((left > 0) & (right <= 0))
    roots = np.full((count, 3), np.nan)
    rows, pieces = bracketed.nonzero()
    if rows.size:
        at, end = (rows, pieces), (rows, pieces + 1)  # each piece, and its right end
        roots[at] = _newton_in_bracket(
            coefficients[rows], breaks[at], breaks[end], left[at], right[at]
        )
    return np.sort(roots, axis=1)


def _newton_in_bracket(
    poly: FloatArray, low: FloatArray, high: FloatArray, f_low: FloatArray, f_high: FloatArray
) -> FloatArray:
    """The root of each monotone polynomial between low and high (signs differ, f(high)
    may be 0): Newton from the secant point, bisecting whenever a step leaves the
    bracket, until a step or the bracket is within two ulps, or f is exactly zero.
    Each row iterates on its own; a few rows as Python floats (numpy's per-call cost
    would dominate), many as arrays, by the same operations in the same order: the same
    bits (tests/physics/test_roots.py holds them equal)."""
    if len(poly) <= PYTHON_ROWS:
        columns = (poly.tolist(), low.tolist(), high.tolist(), f_low.tolist(), f_high.tolist())
        rows = zip(*columns, strict=True)
        return np.array([_newton_one(*row) for row in rows], dtype=np.float64)
    return _newton_arrays(poly, low, high, f_low, f_high)


def _newton_one(
    coefficients: list[float], low: float, high: float, f_low: float, f_high: float
) -> float:
    """_newton_arrays for one row, step for step."""
    if f_high == 0:
        return high
    x = low + (high - low) * (f_low / (f_low - f_high))
    if not low < x < high:
        x = 0.5 * (low + high)
    return _newton_steps(coefficients, x, low, high, f_low < 0, NEWTON_STEPS)


def _newton_steps(
    coefficients: list[float], x: float, low: float, high: float, rising: bool, steps: int
) -> float:
    """At most `steps` of _newton_arrays' iteration for one row, from x in (low, high)."""
    top, second, rest = coefficients[-1], coefficients[-2], coefficients[-3::-1]
    for _ in range(steps):
        value = top * x + second
        slope = top
        for coefficient in rest:
            slope = slope * x + value
            value = value * x + coefficient
        # numpy's x - value / 0 is infinite (or NaN with value 0, which ends anyway):
        # outside the bracket and never converged, as inf is here.
        step = x - value / slope if slope != 0 else math.inf
        if (value < 0) == rising:
            low = x
        else:
            high = x
        ulps = 2.0 * math.ulp(abs(x))
        if value == 0 or abs(step - x) <= ulps or high - low <= ulps:
            return x
        x = step if low < step < high else 0.5 * (low + high)
    return x


def _newton_arrays(
    poly: FloatArray, low: FloatArray, high: FloatArray, f_low: FloatArray, f_high: FloatArray
) -> FloatArray:
    columns = [poly[:, power] for power in range(poly.shape[1])]  # lowest power first
    rising = f_low < 0
    count = len(poly)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = low + (high - low) * (f_low / (f_low - f_high))
        x = np.where((x > low) & (x < high), x, 0.5 * (low + high))
        done = f_high == 0
        x = np.where(done, high, x)
        for iteration in range(NEWTON_STEPS):
            # f(x) and f'(x) by one Horner pass.
            value = columns[-1] * x + columns[-2]
            slope = columns[-1]
            for coefficient in columns[-3::-1]:
                slope = slope * x + value
                value = value * x + coefficient
            step = x - value / slope
            below = (value < 0) == rising  # x lies on the low end's side of the root
            low = np.where(below, x, low)
            high = np.where(below, high, x)
            ulps = 2.0 * np.spacing(np.abs(x))
            done |= (value == 0) | (np.abs(step - x) <= ulps) | (high - low <= ulps)
            converged = np.count_nonzero(done)
            if converged == count:
                break
            inside = (step > low) & (step < high)
            x = np.where(done, x, np.where(inside, step, 0.5 * (low + high)))
            if count - converged <= PYTHON_ROWS:
                # The last few rows (Newton's slow tail: a double root, a bisection)
                # go on as Python floats, each call of numpy costing more than them.
                rows = (~done).nonzero()[0]
                steps = NEWTON_STEPS - iteration - 1
                for row, coefficients, start, below_root, above_root, up in zip(
                    rows.tolist(),
                    poly[rows].tolist(),
                    x[rows].tolist(),
                    low[rows].tolist(),
                    high[rows].tolist(),
                    rising[rows].tolist(),
                    strict=True,
                ):
                    x[row] = _newton_steps(coefficients, start, below_root, above_root, up, steps)
                break
    return x


def evaluate(coefficients: FloatArray, x: FloatArray) -> FloatArray:
    """Horner evaluation; x has shape (M,) or (M, K)."""
    columns = coefficients.T if x.ndim == 1 else coefficients.T[:, :, None]
    result = columns[-1]
    for column in columns[-2::-1]:
        result = result * x + column
    return np.asarray(result)


def derivative(coefficients: FloatArray) -> FloatArray:
    powers = np.arange(1, coefficients.shape[1], dtype=np.float64)
    return coefficients[:, 1:] * powers


def first_downward_root(
    coefficients: FloatArray,
    horizon: FloatArray,
    touching: FloatArray,
    parting: BoolArray | None = None,
    level: FloatArray | None = None,
    hair: bool = False,
) -> FloatArray:
    """Earliest t in [0, horizon] where f (coefficients (M, 5)) falls to zero; inf where
    it does not. touching (M,): f(0) at or below it touches (rounding level), and
    contacts now if closing. parting (M,): rows whose touch now was judged a graze: only
    a return counts. level (M,): the rounding of f'(0): a touching pair within it whose
    f curves down is pressed, so contacts now. hair: also a touching pair parting by so
    little that f, curving down, never leaves the touching band (the spin model's)."""
    count = len(horizon)
    result = np.full(count, np.inf)
    if count == 0:
        return result
    # Contact at t = 0: touching and closing, or touching, level and curving in.
    c0, c1, c2 = coefficients[:, 0], coefficients[:, 1], coefficients[:, 2]
    level_c1 = 0.0 if level is None else level
    closing_now = (c0 <= touching) & ((c1 < 0) | ((c1 <= level_c1) & (c2 < 0)))
    if hair:
        # Touching, parting by a hair and curving in: f peaks at f(0) + f'(0)^2 / (4 |c2|);
        # in the touching band the pair never really parts (no fall from f > 0 exists),
        # so it is pressed now, if back (t = f'(0) / |c2|) within the horizon; else it
        # is asked again at the anchor that ends what presses it.
        in_band = (touching - c0) * 4.0 * -c2 >= c1 * c1
        closing_now |= (c0 <= touching) & (c2 < 0) & in_band & (c1 <= -c2 * horizon)
    if parting is not None:
        closing_now &= ~parting
    result[closing_now] = 0.0
    search = (~closing_now & (horizon > 0)).nonzero()[0]
    if search.size == 0:
        return result

    h = horizon[search]  # time scaled to x in [0, 1]: comparable coefficients
    scaled = coefficients[search]  # a copy: fancy indexing
    h2 = h * h
    scaled[:, 1] *= h
    scaled[:, 2] *= h2
    scaled[:, 3] *= h2 * h
    scaled[:, 4] *= h2 * h2

    # A cheap certificate first: most pairs provably never touch.
    keep = (~_never_falls_to_zero(scaled, touching[search])).nonzero()[0]
    if keep.size == 0:
        return result
    search, h, scaled = search[keep], h[keep], scaled[keep]

    critical = cubic_roots_within(derivative(scaled), 0.0, 1.0)
    breaks = np.ones((search.size, 5))
    breaks[:, 0] = 0.0
    breaks[:, 1:4] = np.where(critical < 1, critical, 1.0)  # ascending; NaN (none) -> 1
    values = evaluate(scaled, breaks)
    crossing = (values[:, :-1] > 0) & (values[:, 1:] <= 0)
    if parting is not None:
        # The first piece starts at the graze itself: a rounding-level dip there is not
        # a return (it was just judged no contact), so only later pieces count.
        crossing[parting[search], 0] = False
    found = crossing.any(axis=1)
    if not found.any():
        return result
    rows = np.nonzero(found)[0]
    piece = np.argmax(crossing[rows], axis=1)
    low, high = breaks[rows, piece], breaks[rows, piece + 1]
    poly = scaled[rows]
    x = _newton_in_bracket(poly, low, high, values[rows, piece], values[rows, piece + 1])
    # The largest point found with f > 0, or the root itself where f is exactly zero.
    x = np.where(evaluate(poly, x) == 0, x, _last_positive(poly, x, low))
    result[search[rows]] = x * h[rows]
    return result


def _never_falls_to_zero(scaled: FloatArray, touching: FloatArray) -> BoolArray:
    """True where f provably has no downward root on x in [0, 1]: with q(x) = b1 + b2 x
    + b3 x^2, f(x) = b0 + x q(x) + b4 x^4 >= b0 + x min(q) (b4 = |K|^2 >= 0), q's
    minimum at an end or its vertex; so f stays positive if b0 + min(min(q), 0) > 0,
    and cannot fall back after a touch if min(q) > 0. The rest: _stays_positive."""
    b0, b1, b2, b3 = scaled[:, 0], scaled[:, 1], scaled[:, 2], scaled[:, 3]
    # A vertex past [0, 1] is clipped to its end: with a denormal b3 (a ball at 1e-310
    # m/s) -b2 / (2 b3) overflows to that end's side of infinity, the same clip.
    with np.errstate(over="ignore"):
        vertex = np.clip(-b2 / np.where(b3 > 0, 2.0 * b3, np.inf), 0.0, 1.0)
    lowest = np.minimum(np.minimum(b1, b1 + b2 + b3), b1 + (b2 + b3 * vertex) * vertex)
    never = (b0 + np.minimum(lowest, 0.0) > 0) | ((b0 >= -touching) & (lowest > 0))
    rows = (~never).nonzero()[0]
    if rows.size:
        never[rows] = _stays_positive(scaled[rows])
    return never


def _bernstein_map(pieces: int) -> FloatArray:
    """(5, K): row j the Bernstein coefficients of x^j on `pieces` equal pieces of [0, 1]
    (their shared ends once), so that sum_j a_j row_j are f's. Exact, rounded once."""
    columns: list[list[Fraction | int]] = []
    for piece in range(pieces):
        start, width = Fraction(piece, pieces), Fraction(1, pieces)
        # x^j on [start, start + width] in s in [0, 1] is (start + width s)^j = sum_i
        # p_ji s^i, whose Bernstein coefficients are sum_{i<=k} C(k,i)/C(4,i) p_ji.
        p: list[list[Fraction | int]] = [[1]]
        for _ in range(4):
            p.append([start * a + width * b for a, b in zip([*p[-1], 0], [0, *p[-1]], strict=True)])
        for k in range(0 if piece == 0 else 1, 5):
            weights = [Fraction(math.comb(k, i), math.comb(4, i)) for i in range(k + 1)]
            columns.append([sum(w * q for w, q in zip(weights, p_j, strict=False)) for p_j in p])
    return np.array([[float(column[j]) for column in columns] for j in range(5)])


# _stays_positive's pieces of [0, 1]: the whole first, then eighths for what it leaves.
# In a hard break, the whole interval leaves 4.2 times as many pairs as have a root to
# the roots, 2 pieces 2.4 times, 4 pieces 1.5 times, 8 pieces 1.2 times.
_WHOLE = _bernstein_map(1)
_EIGHTHS = _bernstein_map(8)


def _stays_positive(scaled: FloatArray) -> BoolArray:
    """True where f > 0 on x in [0, 1], proven by its Bernstein coefficients (on each
    piece f is a convex combination of them). Each is rounded to a few ulps of sum
    |a_j|, as Horner's f is: the margin covers both, so where this says True no
    evaluation of f in first_downward_root is <= 0, and leaving the pair out changes
    no result."""
    a = [scaled[:, power, None] for power in range(5)]
    size = np.abs(a[0]) + np.abs(a[1]) + np.abs(a[2]) + np.abs(a[3]) + np.abs(a[4])
    margin = 16.0 * np.finfo(np.float64).eps * size[:, 0]
    positive = _least_coefficient(a, _WHOLE) > margin
    rows = (~positive).nonzero()[0]
    if rows.size:
        positive[rows] = _least_coefficient([part[rows] for part in a], _EIGHTHS) > margin[rows]
    return positive


def _least_coefficient(a: list[FloatArray], bernstein: FloatArray) -> FloatArray:
    """The least Bernstein coefficient of each row's f over the pieces of `bernstein`."""
    coefficients = a[0] * bernstein[0] + a[1] * bernstein[1]
    for power in (2, 3, 4):
        coefficients += a[power] * bernstein[power]
    return np.asarray(coefficients.min(axis=1))


def _last_positive(poly: FloatArray, x: FloatArray, low: FloatArray) -> FloatArray:
    """At or just below x, f > 0: Newton may end past it; balls must never overlap."""
    ulp = np.spacing(np.maximum(np.abs(x), 1e-300))
    trial = x[:, None] - ulp[:, None] * _BACKOFF_ULPS[None, :]
    trial = np.maximum(trial, low[:, None])
    positive = evaluate(poly, trial) > 0
    first = np.argmax(positive, axis=1)
    chosen = trial[np.arange(len(x)), first]
    return np.where(positive.any(axis=1), chosen, low)
