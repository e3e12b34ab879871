"""The earliest time a distance polynomial drops to zero, for many pairs at once.

For two balls on straight, uniformly decelerated paths, d(t) = D + W t + K t^2 is
their separation and f(t) = |d(t)|^2 - (2r)^2 a quartic. Contact is the first
time f falls from positive to zero. Finding it robustly, without missing grazing
contacts or inventing them:

1. The critical points of f (roots of the cubic f') cut [0, h] into at most four
   pieces on which f is monotone. Evaluating f at a critical point is accurate to
   second order in the point's own error, so the sign test "does f dip below zero"
   is exact to rounding even for a graze.
2. The first monotone piece with f(left) > 0 >= f(right) holds the contact; a
   safeguarded Newton iteration refines it to rounding, from the positive side so
   that the balls never overlap at the returned time.

Coefficient arrays have shape (M, 5), lowest power first.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]

# A coefficient smaller than this share of the largest (on the scaled interval [0, 1])
# is dropped when seeding roots; Newton then works on the full polynomial.
NEGLIGIBLE = 1e-13
NEWTON_STEPS = 60


def cubic_roots_real(coefficients: FloatArray) -> FloatArray:
    """Real roots (M, 3) of many cubics (M, 4), lowest power first; NaN pads missing roots.

    Leading terms below NEGLIGIBLE of the row's largest coefficient are dropped: such
    rows are solved as quadratics or lines in closed form, the true cubics by one
    batched companion-matrix eigenvalue solve.
    """
    count = len(coefficients)
    roots = np.full((count, 3), np.nan)
    scale = np.abs(coefficients).max(axis=1)
    normalised = coefficients / np.where(scale > 0, scale, 1.0)[:, None]
    c0, c1, c2, c3 = normalised.T
    cubic = np.abs(c3) > NEGLIGIBLE
    quadratic = ~cubic & (np.abs(c2) > NEGLIGIBLE)
    linear = ~cubic & ~quadratic & (np.abs(c1) > NEGLIGIBLE)

    if not cubic.all():
        _quadratic_roots(roots, c0, c1, c2, quadratic, linear)
    rows = cubic.nonzero()[0]
    if rows.size:
        companion = np.zeros((rows.size, 3, 3))
        companion[:, 1, 0] = 1.0
        companion[:, 2, 1] = 1.0
        companion[:, :, 2] = -normalised[rows, :3] / normalised[rows, 3:4]
        eigen = np.linalg.eigvals(companion)
        # Keep near-real roots: a real double root may come back as a close complex pair.
        near_real = np.abs(eigen.imag) <= 1e-6 * np.maximum(1.0, np.abs(eigen.real))
        roots[rows] = np.where(near_real, eigen.real, np.nan)
    return roots


def _quadratic_roots(
    roots: FloatArray,
    c0: FloatArray,
    c1: FloatArray,
    c2: FloatArray,
    quadratic: BoolArray,
    linear: BoolArray,
) -> None:
    """Fill roots[:, :2] of the rows that are quadratics or lines."""
    with np.errstate(divide="ignore", invalid="ignore"):
        # Quadratics in the cancellation-free form q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2.
        discriminant = c1 * c1 - 4.0 * c2 * c0
        real = quadratic & (discriminant >= 0)
        q = -0.5 * (c1 + np.copysign(np.sqrt(np.maximum(discriminant, 0.0)), c1))
        roots[:, 0] = np.where(real, q / c2, np.where(linear, -c0 / c1, roots[:, 0]))
        roots[:, 1] = np.where(real & (q != 0), c0 / q, roots[:, 1])


def evaluate(coefficients: FloatArray, x: FloatArray) -> FloatArray:
    """Horner evaluation; x has shape (M,) or (M, K)."""
    if x.ndim == 2:
        result = np.repeat(coefficients[:, -1:], x.shape[1], axis=1)
        for power in range(coefficients.shape[1] - 2, -1, -1):
            result = result * x + coefficients[:, power : power + 1]
        return result
    result = coefficients[:, -1].copy()
    for power in range(coefficients.shape[1] - 2, -1, -1):
        result = result * x + coefficients[:, power]
    return result


def derivative(coefficients: FloatArray) -> FloatArray:
    powers = np.arange(1, coefficients.shape[1], dtype=np.float64)
    return coefficients[:, 1:] * powers


def first_downward_root(
    coefficients: FloatArray,
    horizon: FloatArray,
    touching: FloatArray,
    parting: BoolArray | None = None,
    level: FloatArray | None = None,
) -> FloatArray:
    """Earliest t in [0, horizon] where f falls to zero; inf where it does not.

    coefficients: (M, 5) of f(t). touching: (M,) the value of f(0) at or below which
    the pair already touches (rounding level); such a pair that is closing contacts
    at t = 0. parting: (M,) rows whose touch at t = 0 was judged a rounding-level graze:
    for them only a return counts, a fall that starts at a local maximum of f after 0.
    level: (M,) the rounding of f'(0): a touching pair whose f'(0) is no more than that
    and whose f curves down (f''(0) < 0) is pressed together, so contacts now.
    """
    count = len(horizon)
    result = np.full(count, np.inf)
    if count == 0:
        return result
    c0 = coefficients[:, 0]
    c1 = coefficients[:, 1]
    c2 = coefficients[:, 2]
    # Already touching and closing (or touching, level, and curving in): contact now.
    level_c1 = 0.0 if level is None else level
    closing_now = (c0 <= touching) & ((c1 < 0) | ((c1 <= level_c1) & (c2 < 0)))
    if parting is not None:
        closing_now &= ~parting
    result[closing_now] = 0.0
    search = (~closing_now & (horizon > 0)).nonzero()[0]
    if search.size == 0:
        return result

    # Scale time to x in [0, 1] so the coefficients are comparable.
    h = horizon[search]
    powers = h[:, None] ** np.arange(5)
    scaled = coefficients[search] * powers

    # Cheap certificate first: most pairs provably never touch, and skip the roots.
    keep = (~_never_falls_to_zero(scaled, touching[search])).nonzero()[0]
    if keep.size == 0:
        return result
    search, h, scaled = search[keep], h[keep], scaled[keep]

    critical = cubic_roots_real(derivative(scaled))
    critical = np.where((critical > 0) & (critical < 1), critical, 1.0)
    breaks = np.concatenate(
        [np.zeros((search.size, 1)), np.sort(critical, axis=1), np.ones((search.size, 1))], axis=1
    )
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
    low = breaks[rows, piece]
    high = breaks[rows, piece + 1]
    poly = scaled[rows]
    x = _refine(poly, low, high, values[rows, piece], values[rows, piece + 1])
    result[search[rows]] = x * h[rows]
    return result


def _never_falls_to_zero(scaled: FloatArray, touching: FloatArray) -> BoolArray:
    """True where f provably has no downward root on x in [0, 1].

    With q(x) = b1 + b2 x + b3 x^2, f(x) = b0 + x q(x) + b4 x^4 >= b0 + x min(q), since
    b4 = |K|^2 >= 0. The minimum of a quadratic over [0, 1] lies at an end or at its
    vertex. So f stays positive if b0 + min(min(q), 0) > 0, and cannot fall back to
    zero after leaving a touch (b0 at rounding level) if min(q) > 0.
    """
    b0, b1, b2, b3 = scaled[:, 0], scaled[:, 1], scaled[:, 2], scaled[:, 3]
    vertex = np.clip(-b2 / np.where(b3 > 0, 2.0 * b3, np.inf), 0.0, 1.0)
    lowest = np.minimum(np.minimum(b1, b1 + b2 + b3), b1 + (b2 + b3 * vertex) * vertex)
    return (b0 + np.minimum(lowest, 0.0) > 0) | ((b0 >= -touching) & (lowest > 0))


def _refine(
    poly: FloatArray, low: FloatArray, high: FloatArray, f_low: FloatArray, f_high: FloatArray
) -> FloatArray:
    """Newton inside the bracket [low, high] (f(low) > 0 >= f(high)); returns the
    largest point found with f > 0, or the root itself where f hits zero exactly."""
    slope_poly = derivative(poly)
    # Start from the secant point: inside the bracket and usually close.
    x = low + (high - low) * f_low / (f_low - f_high)
    x = np.where((x > low) & (x < high), x, 0.5 * (low + high))
    exact = np.zeros(len(x), dtype=bool)
    for _ in range(NEWTON_STEPS):
        value = evaluate(poly, x)
        zero = value == 0
        exact |= zero
        positive = value > 0
        low = np.where(positive, x, low)
        high = np.where(positive | zero, high, x)
        high = np.where(zero, x, high)
        slope = evaluate(slope_poly, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = x - value / slope
        bisect = 0.5 * (low + high)
        candidate = np.where(np.isfinite(step) & (step > low) & (step < high), step, bisect)
        done = exact | (np.abs(candidate - x) <= 2.0 * np.spacing(np.maximum(x, 1e-300)))
        x = np.where(done, x, candidate)
        if done.all():
            break
    return np.where(exact, x, _last_positive(poly, x, low))


def _last_positive(poly: FloatArray, x: FloatArray, low: FloatArray) -> FloatArray:
    """The point at or just below x (by a few ulps, doubling) where f is still positive.

    Newton converges to the root from one side only; when that side is f < 0, step
    back so that the balls touch but never overlap at the returned time."""
    ulp = np.spacing(np.maximum(np.abs(x), 1e-300))
    offsets = np.concatenate([[0.0], 2.0 ** np.arange(48)])
    trial = x[:, None] - ulp[:, None] * offsets[None, :]
    trial = np.maximum(trial, low[:, None])
    positive = evaluate(poly, trial) > 0
    first = np.argmax(positive, axis=1)
    chosen = trial[np.arange(len(x)), first]
    return np.where(positive.any(axis=1), chosen, low)
