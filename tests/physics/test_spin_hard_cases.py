"""The spin model's hard cases: random strikes into racks (touching or not, any tip),
english into cushions, frozen racks. Each run must keep every invariant: no overlap or
cushion crossing beyond rounding, translational plus rotational energy never rising,
`exact` equal to `event` bit for bit, and every ball at rest in the end.

A seeded sample of each family runs by default; `pytest -m hard` runs them all.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods.entry import run
from billiards.physics.pockets import pocket_of, pocket_table
from billiards.physics.spin.motion import tip_spin
from billiards.rules.seed import RADIUS
from billiards.scene.reader import rack_positions
from tests.hard_checks import (
    check_inside_cushions,
    check_no_nan,
    check_no_overlap,
    check_no_pocketed_overlap,
    check_on_pocket_table,
    check_pocketed,
    fingerprint,
    kinetic_energy,
    sample_times,
)

FAMILIES = {"strike": 60, "english": 40, "frozen": 12, "pocket_strike": 60, "pocket_english": 60}
SAMPLE = {"strike": 8, "english": 6, "frozen": 2, "pocket_strike": 3, "pocket_english": 5}
SAMPLE_SEED = 20261122
TABLE = (2.13, 1.065)


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """Full family under `-m hard` (each case marked hard), else a seeded sample."""
    for family, size in FAMILIES.items():
        if f"{family}_case" not in metafunc.fixturenames:
            continue
        markexpr = metafunc.config.option.markexpr or ""
        if "hard" in markexpr and "not hard" not in markexpr:
            params = [pytest.param(i, marks=pytest.mark.hard) for i in range(size)]
        else:
            chosen = np.random.default_rng(SAMPLE_SEED).choice(size, SAMPLE[family], replace=False)
            params = [pytest.param(int(i)) for i in sorted(chosen)]
        metafunc.parametrize(f"{family}_case", params, ids=str)


def strike(index: int) -> Setup:
    """A cue ball from anywhere behind the head string, at 0.5..12 m/s, any tip, aimed
    within 0.3 rad of the apex of a rack whose gap is 0, 0.1 or 1 mm."""
    rng = np.random.default_rng([SAMPLE_SEED, 1, index])
    gap = float(rng.choice([0.0, 1e-4, 1e-3]))
    cue = np.array([0.5325 + rng.uniform(-0.2, 0.2), 0.5325 + rng.uniform(-0.3, 0.3)])
    positions = [cue.tolist(), *[list(p) for p in rack_positions((1.5975, 0.5325), RADIUS, gap)]]
    aim = np.array([1.5975, 0.5325]) - cue
    angle = math.atan2(aim[1], aim[0]) + rng.uniform(-0.3, 0.3)
    velocities = np.zeros((16, 2))
    velocities[0] = rng.uniform(0.5, 12.0) * np.array([math.cos(angle), math.sin(angle)])
    tips = np.zeros((16, 2))
    side, height = rng.uniform(-0.6, 0.6, 2)
    tips[0] = (side, height)
    return Setup.of(
        positions,
        velocities,
        model="spin",
        spins=tip_spin(velocities, tips, RADIUS),
        restitution=float(rng.choice([1.0, 0.95, 0.8])),
    )


def english(index: int) -> Setup:
    """A ball with strong side spin (and any top or draw) into a cushion at any angle,
    a second ball near its path; some start touching the cushion; every other case
    with Han 2005 cushions."""
    rng = np.random.default_rng([SAMPLE_SEED, 2, index])
    start = np.array([rng.uniform(0.2, 1.9), rng.uniform(0.1, 0.95)])
    if index % 4 == 0:
        start[1] = RADIUS  # on the cushion line
    angle = rng.uniform(-math.pi, math.pi)
    speed = rng.uniform(0.3, 6.0)
    velocity = speed * np.array([math.cos(angle), math.sin(angle)])
    spin = tip_spin(
        velocity[None], np.array([[rng.uniform(-0.8, 0.8), rng.uniform(-0.5, 0.5)]]), RADIUS
    )
    other = start + velocity / speed * rng.uniform(3 * RADIUS, 0.5)
    other = np.clip(other, RADIUS, np.array(TABLE) - RADIUS)
    if np.linalg.norm(other - start) < 2 * RADIUS:
        other = np.array([TABLE[0] - RADIUS - 0.01, TABLE[1] / 2])
    return Setup.of(
        [start.tolist(), other.tolist()],
        [velocity.tolist(), [0.0, 0.0]],
        model="spin",
        spins=[spin[0].tolist(), [0.0, 0.0, 0.0]],
        restitution=float(rng.choice([1.0, 0.9])),
        retention=float(rng.choice([0.75, 1.0, 0.3])),
        cushion_law="han2005" if index % 2 else "mirror",
    )


def frozen(index: int) -> Setup:
    """A frozen rack (gap 0) broken head-on at 2..14 m/s with stun, draw or follow."""
    rng = np.random.default_rng([SAMPLE_SEED, 3, index])
    positions = [
        [0.5325, 0.5325],
        *[list(p) for p in rack_positions((1.5975, 0.5325), RADIUS, 0.0)],
    ]
    velocities = np.zeros((16, 2))
    velocities[0] = (rng.uniform(2.0, 14.0), 0.0)
    tips = np.zeros((16, 2))
    tips[0] = (0.0, rng.uniform(-0.6, 0.6))
    return Setup.of(
        positions,
        velocities,
        model="spin",
        spins=tip_spin(velocities, tips, RADIUS),
        restitution=float(rng.choice([1.0, 0.95])),
    )


def check_spin_invariants(setup: Setup) -> None:
    ids = tuple(str(i) for i in range(len(setup.positions)))
    result = run(setup, ids, "event", 1 / 240)
    check_no_nan(result)
    assert result.complete, "the run did not come to rest"
    times = sample_times(result)
    check_no_overlap(result, times)
    check_inside_cushions(result, times)
    check_energy_never_rises(result, times)
    stepped = run(setup, ids, "exact", 1 / 240)
    assert fingerprint(stepped) == fingerprint(result), "exact differs from event"
    assert stepped.transitions == result.transitions


def check_energy_never_rises(result: SimulationResult, times: np.ndarray) -> None:
    # Just before and at every anchor, and on the grid between.
    every = np.unique(np.concatenate([times, np.nextafter(times, -np.inf)]))
    velocities = result.velocities_at(every)
    spins = result.spins_at(every)
    energy = np.array(
        [
            kinetic_energy(result.masses, v, w, RADIUS)
            for v, w in zip(velocities, spins, strict=True)
        ]
    )
    rise = float(np.diff(energy).max(initial=0.0))
    assert rise <= 1e-12 * energy[0] + 1e-300, f"energy rose by {rise:.3g} J"


def test_random_spin_strike_keeps_every_invariant(strike_case: int) -> None:
    check_spin_invariants(strike(strike_case))


def test_english_into_a_cushion_keeps_every_invariant(english_case: int) -> None:
    check_spin_invariants(english(english_case))


def test_frozen_rack_spin_break_keeps_every_invariant(frozen_case: int) -> None:
    check_spin_invariants(frozen(frozen_case))


# --- with pockets: the same geometry as the rolling model ------------------------------

POCKETS = pocket_table(TABLE, RADIUS)


def with_pockets(setup: Setup) -> Setup:
    keep = pocket_of(POCKETS, setup.positions) < 0
    assert setup.spins is not None
    return replace(
        setup,
        positions=setup.positions[keep],
        velocities=setup.velocities[keep],
        masses=setup.masses[keep],
        spins=setup.spins[keep],
        pockets=POCKETS,
    )


def check_spin_pocket_invariants(setup: Setup) -> None:
    ids = tuple(str(i) for i in range(len(setup.positions)))
    result = run(setup, ids, "event", 1 / 240)
    check_no_nan(result)
    assert result.complete, "the run did not come to rest"
    times = sample_times(result)
    check_on_pocket_table(result, times)
    check_no_pocketed_overlap(result, times)
    check_energy_never_rises(result, times)
    check_pocketed(result)
    stepped = run(setup, ids, "exact", 1 / 240)
    assert fingerprint(stepped) == fingerprint(result), "exact differs from event"


def test_random_spin_strike_with_pockets_keeps_every_invariant(pocket_strike_case: int) -> None:
    check_spin_pocket_invariants(with_pockets(strike(pocket_strike_case)))


def test_english_near_pockets_keeps_every_invariant(pocket_english_case: int) -> None:
    """english(): side spin into cushions anywhere, so into mouths and jaws too."""
    check_spin_pocket_invariants(with_pockets(english(pocket_english_case)))
