"""The polynomial roots behind every contact time (billiards/physics/numerics/roots.py)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from billiards.physics.numerics import roots
from billiards.physics.numerics.roots import cubic_roots_within, evaluate, first_downward_root


def _real_roots(coefficients: list[float], low: float = -10.0, high: float = 10.0) -> list[float]:
    roots = cubic_roots_within(np.array([coefficients], dtype=np.float64), low, high)[0]
    return sorted(roots[np.isfinite(roots)].tolist())


def test_a_cubic_with_three_real_roots_gives_all_three() -> None:
    # (x - 1)(x - 2)(x - 3), lowest power first
    assert _real_roots([-6.0, 11.0, -6.0, 1.0]) == pytest.approx([1.0, 2.0, 3.0], abs=1e-12)


def test_a_cubic_whose_leading_terms_vanish_is_solved_as_a_quadratic_or_a_line() -> None:
    assert _real_roots([2.0, -3.0, 1.0, 0.0]) == pytest.approx([1.0, 2.0], abs=1e-15)
    assert _real_roots([-2.0, 1.0, 0.0, 0.0]) == pytest.approx([2.0], abs=1e-15)


def test_a_polynomial_without_real_roots_gives_none() -> None:
    assert _real_roots([1.0, 0.0, 1.0, 0.0]) == []  # x^2 + 1


# (t - 1)(t - 3)(t^2 + 1): positive at 0, falls through zero at t = 1, rises at t = 3.
FALLS_AT_ONE = [3.0, -4.0, 4.0, -4.0, 1.0]


def _first(coefficients: list[float], horizon: float, touching: float = 0.0) -> float:
    poly = np.array([coefficients], dtype=np.float64)
    return float(first_downward_root(poly, np.array([horizon]), np.array([touching]))[0])


def test_the_first_downward_root_is_found_to_rounding_from_the_positive_side() -> None:
    root = _first(FALLS_AT_ONE, horizon=10.0)
    assert root == pytest.approx(1.0, abs=4e-16)
    poly = np.array([FALLS_AT_ONE])
    # The balls touch but never overlap at the returned time: f >= 0 there.
    assert evaluate(poly, np.array([root]))[0] >= 0.0


def test_a_root_beyond_the_horizon_is_no_contact() -> None:
    assert _first(FALLS_AT_ONE, horizon=0.999) == np.inf


def test_a_graze_is_decided_by_the_sign_at_the_critical_point() -> None:
    # (t - 1)^2 (t^2 + 1) touches zero at t = 1 without crossing; lifted by 1e-12 it
    # never reaches zero; lowered by 1e-12 it crosses where 2 (t - 1)^2 = 1e-12, about
    # 7.07e-7 before t = 1 (t^2 + 1 = 2 there).
    graze = [1.0, -2.0, 2.0, -2.0, 1.0]
    lifted = [graze[0] + 1e-12, *graze[1:]]
    lowered = [graze[0] - 1e-12, *graze[1:]]
    assert _first(lifted, horizon=5.0) == np.inf
    root = _first(lowered, horizon=5.0)
    # to what the rounded coefficients allow (an ulp of f(0) moves the root by 4e-11)
    assert root == pytest.approx(1.0 - math.sqrt(0.5e-12), abs=1e-10)
    assert evaluate(np.array([lowered]), np.array([root]))[0] >= 0.0  # apart, not overlapping


def test_a_pair_touching_and_closing_at_the_start_contacts_at_once() -> None:
    assert _first([0.0, -1.0, 0.0, 0.0, 1.0], horizon=1.0) == 0.0
    # touching with no closing speed but curving in: also now
    assert _first([0.0, 0.0, -1.0, 0.0, 1.0], horizon=1.0) == 0.0


def test_a_pair_touching_and_parting_has_no_contact() -> None:
    assert _first([0.0, 1.0, 1.0, 0.0, 1.0], horizon=1.0) == np.inf


def test_many_pairs_are_solved_at_once_and_each_as_if_alone() -> None:
    rows = [FALLS_AT_ONE, [1.0, 1.0, 1.0, 0.0, 1.0], [0.0, -1.0, 0.0, 0.0, 1.0]]
    together = first_downward_root(np.array(rows), np.full(3, 10.0), np.zeros(3))
    alone = [_first(row, horizon=10.0) for row in rows]
    assert together.tolist() == alone


def test_newton_on_python_floats_gives_numpys_bits() -> None:
    # A few rows iterate on Python floats, many on arrays: a run alone and the same run
    # among many must find the same roots, to the bit.
    rng = np.random.default_rng(5)
    for _ in range(100):
        rows = int(rng.integers(1, 30))
        poly = rng.normal(size=(rows, int(rng.choice([4, 5])))) * 10.0 ** rng.uniform(
            -8, 8, (rows, 1)
        )
        low, high = np.zeros(rows), np.ones(rows)
        f_low, f_high = evaluate(poly, low), evaluate(poly, high)
        keep = f_low * f_high < 0
        if not keep.any():
            continue
        args = (poly[keep], low[keep], high[keep], f_low[keep], f_high[keep])
        arrays = roots._newton_arrays(*args)
        one_by_one = [
            roots._newton_one(*row) for row in zip(*(a.tolist() for a in args), strict=True)
        ]
        assert arrays.tobytes() == np.array(one_by_one).tobytes()
        assert np.all(np.abs(evaluate(args[0], arrays)) <= 1e-9 * np.abs(args[0]).max(axis=1))


def test_newtons_slow_tail_goes_on_as_python_floats_with_numpys_bits(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Twenty fast rows and one slow one (a near double root: Newton crawls, halving the
    # step): once no more than PYTHON_ROWS rows are left, they finish on Python floats.
    rng = np.random.default_rng(7)
    poly = np.vstack([rng.normal(size=(20, 4)), [[0.25 - 1e-14, -1.0, 1.0, 0.0]]])
    low = np.zeros(21)
    low[20] = 0.5  # (x - 1/2)^2 - 1e-14: its root 1e-7 past the bracket's low end
    high = np.ones(21)
    f_low, f_high = evaluate(poly, low), evaluate(poly, high)
    keep = f_low * f_high < 0
    assert keep[20] and keep.sum() > roots.PYTHON_ROWS + 1
    args = (poly[keep], low[keep], high[keep], f_low[keep], f_high[keep])
    tails = []
    steps = roots._newton_steps

    def counted(*row: Any) -> float:
        tails.append(row[-1])
        return steps(*row)

    monkeypatch.setattr(roots, "_newton_steps", counted)
    arrays = roots._newton_arrays(*args)
    assert tails and all(left < roots.NEWTON_STEPS for left in tails)  # the tail ran
    one_by_one = [roots._newton_one(*row) for row in zip(*(a.tolist() for a in args), strict=True)]
    assert arrays.tobytes() == np.array(one_by_one).tobytes()
    assert abs(arrays[-1] - (0.5 + 1e-7)) < 1e-9  # to the conditioning of a near double root
