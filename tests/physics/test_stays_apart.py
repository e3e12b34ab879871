"""The pair times' quick rejection (billiards.physics.compiled.rolling_times.stays_apart):
where it says a pair stays apart, the pair's relative path d + w t + k t^2 truly keeps
farther than the reach on the whole window (sampled densely, and by the separation
quartic's own root search); and it does tell the plain cases apart (parting pairs,
pairs passing wide), while never a pair that meets."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.compiled.rolling_times import stays_apart
from billiards.physics.numerics.roots import first_downward_root
from billiards.physics.rolling.contact_times import separation_quartic

REACH = 2 * 0.028575  # two pool-ball radii


def closest(gap: np.ndarray, closing: np.ndarray, curve: np.ndarray, length: float) -> float:
    """The least |d + w t + k t^2| over [0, length], sampled at 20,001 times."""
    times = np.linspace(0.0, length, 20_001)[:, None]
    path = gap + closing * times + curve * times**2
    return float(np.min(np.hypot(path[:, 0], path[:, 1])))


def root(gap: np.ndarray, closing: np.ndarray, curve: np.ndarray, length: float) -> float:
    """The separation quartic's first root in [0, length] (inf if none), as the numpy
    pair times find it (the compiled ones are its bits)."""
    relative = np.array([[gap, closing, curve]])
    quartic, _ = separation_quartic(relative, REACH * REACH)
    touching = np.array([REACH * REACH * 1e-12])
    return float(first_downward_root(quartic, np.array([length]), touching)[0])


@pytest.mark.parametrize("seed", range(4))
def test_a_pair_told_apart_never_comes_within_reach(seed: int) -> None:
    rng = np.random.default_rng(seed)
    told = 0
    for _ in range(1_500):
        gap = rng.uniform(-0.6, 0.6, 2)
        if np.hypot(*gap) <= REACH:
            continue
        closing = rng.uniform(-3.0, 3.0, 2)
        curve = rng.uniform(-1.0, 1.0, 2) * rng.choice([0.0, 0.1, 1.0])
        length = float(rng.uniform(0.0, 1.0))
        if stays_apart(tuple(gap), tuple(closing), tuple(curve), REACH, length):
            told += 1
            assert closest(gap, closing, curve, length) > REACH
            assert root(gap, closing, curve, length) == np.inf
    assert told > 300  # the test asks a real share of pairs


def test_the_plain_cases() -> None:
    far, parting = (0.5, 0.0), (1.0, 0.0)
    assert stays_apart(far, parting, (0.0, 0.0), REACH, 10.0)  # parting along the gap
    assert stays_apart(far, (-1.0, 0.0), (0.0, 0.0), REACH, 0.1)  # closing, not in time
    assert stays_apart(far, (-1.0, 3.0), (0.0, 0.0), REACH, 10.0)  # passing wide
    assert not stays_apart(far, (-1.0, 0.0), (0.0, 0.0), REACH, 1.0)  # head on, in time
    # Passing wide of it on a line, but curving back into it (the across axis's k term).
    assert not stays_apart((0.0, 0.2), (1.0, 0.0), (0.0, -0.5), REACH, 1.0)
    assert not stays_apart((REACH, 0.0), parting, (0.0, 0.0), REACH, 1.0)  # touching now
