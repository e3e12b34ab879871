"""The compiled loop's spin model (billiards.physics.compiled: spin_motion, spin_times,
laws) gives the numpy engine's results, bit for bit and field for field (every event,
anchor row with its spins and motion state, transition, final position): on every
shipped spin scene, on the spin hard-case and touching-case families with their own
laws and with the mirror and frictionless ones, with the frictional law, in a batch as
alone, and on threads as serially.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from functools import cache

import numpy as np
import pytest

from billiards.physics.compiled import runner as compiled
from billiards.physics.engine.packaging import Run
from billiards.physics.engine.setup import Setup
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import _run_of
from tests.physics import test_spin_hard_cases as spin_hard
from tests.physics import test_spin_touching_cases as touching
from tests.physics.test_compiled import assert_same_results, family_runs, shipped_items
from tests.test_batch import exact_form

hard = pytest.mark.hard

SPIN_SCENES = (
    "draw_shot",
    "english_bank",
    "follow_shot",
    "masse_shot",
    "pool_break",
    "spin_break",
    "stun_shot",
    "three_cushion",
    "throw_shot",
)


def test_every_shipped_spin_scene_is_compiled_whatever_its_laws() -> None:
    spin = [item for item in shipped_items("event", None) if item[0].model == "spin"]
    assert len(spin) == len(SPIN_SCENES)
    laws = set()
    for name in SPIN_SCENES:
        item = _run_of(load_scene(default_scene_path().parent / f"{name}.toml"), None, None)
        assert compiled.supports(item[0], item[2]), name
        laws |= {item[0].cushion_law, item[0].ball_law}
    assert {"han2005", "frictional", "mirror", "frictionless"} <= laws


def mirrored(make: Callable[[int], Setup]) -> Callable[[int], Setup]:
    """A family's setups with the compiled laws: the mirror cushion, frictionless balls."""
    return lambda index: replace(make(index), cushion_law="mirror", ball_law="frictionless")


def frictional(make: Callable[[int], Setup]) -> Callable[[int], Setup]:
    """A family's setups with throw: the frictional ball law."""
    return lambda index: replace(make(index), ball_law="frictional")


def mathavan(make: Callable[[int], Setup]) -> Callable[[int], Setup]:
    """A family's setups with the integrated cushion law (its nose at 1.6 R, as a table's)."""
    return lambda index: replace(
        make(index), cushion_law="mathavan2010", cushion_height=1.6 * make(index).radius
    )


FAMILIES = {
    "strike": spin_hard.strike,
    "english": spin_hard.english,
    "english_mirrored": mirrored(spin_hard.english),
    "english_frictional": frictional(spin_hard.english),
    "english_mathavan": mathavan(spin_hard.english),
    "strike_frictional": frictional(spin_hard.strike),
    "frozen": spin_hard.frozen,
    "pocket_strike": lambda i: spin_hard.with_pockets(spin_hard.strike(i)),
    "pocket_english": lambda i: spin_hard.with_pockets(mirrored(spin_hard.english)(i)),
    "rest_cluster": touching.rest_cluster_case,
    "cushion_press": touching.cushion_press_case,
    "cushion_press_mirrored": mirrored(touching.cushion_press_case),
    "moving_pair": touching.moving_pair_case,
    "tiny": touching.tiny_case,
    "frozen_shot": touching.frozen_shot_case,
    "frozen_shot_frictional": frictional(touching.frozen_shot_case),
}
# How many cases of each family the default suite runs (the `hard` ones run the rest).
QUICK = 3
MANY = {
    "strike": 60,
    "english": 40,
    "english_mirrored": 40,
    "english_frictional": 40,
    "english_mathavan": 12,
    "strike_frictional": 60,
    "frozen": 12,
    "pocket_strike": 60,
    "pocket_english": 60,
    "rest_cluster": 120,
    "cushion_press": 80,
    "cushion_press_mirrored": 80,
    "moving_pair": 80,
    "tiny": 60,
    "frozen_shot": 100,
    "frozen_shot_frictional": 100,
}


@pytest.mark.parametrize("family", FAMILIES)
def test_the_spin_families_give_the_numpy_engines_results(family: str) -> None:
    assert_same_results(family_runs(FAMILIES[family], range(QUICK)))


@pytest.mark.parametrize("family", FAMILIES)
def test_the_spin_families_stepped_give_the_numpy_engines_results(family: str) -> None:
    runs = [
        (setup, ids, "exact", dt)
        for setup, ids, _, dt in family_runs(FAMILIES[family], range(QUICK))
    ]
    assert_same_results(runs)


@hard
@pytest.mark.parametrize("family", FAMILIES)
def test_every_spin_family_case_gives_the_numpy_engines_results(family: str) -> None:
    assert_same_results(family_runs(FAMILIES[family], range(QUICK, MANY[family])))


@cache
def spin_break_variants(count: int) -> tuple[Run, ...]:
    """The spin break with the cue ball moved sideways by up to a millimetre and its speed
    varied by 10 %, as a sweep draws them."""
    base = _run_of(load_scene(default_scene_path().parent / "spin_break.toml"), "event", None)
    rng = np.random.default_rng(43)
    runs = []
    for _ in range(count):
        setup = base[0]
        positions, velocities = setup.positions.copy(), setup.velocities.copy()
        positions[0, 1] += rng.uniform(-1e-3, 1e-3)
        velocities[0, 0] *= rng.uniform(0.9, 1.1)
        varied = replace(setup, positions=positions, velocities=velocities)
        runs.append((varied, base[1], "event", base[3]))
    return tuple(runs)


def test_spin_break_variants_give_the_numpy_engines_results_in_one_call() -> None:
    assert_same_results(list(spin_break_variants(16)))


def test_a_spin_batch_gives_each_run_its_result_alone() -> None:
    runs = list(spin_break_variants(8)) + family_runs(FAMILIES["pocket_strike"], range(2))
    together = compiled.run_compiled(runs)
    for item, result in zip(runs, together, strict=True):
        assert exact_form(result) == exact_form(compiled.run_compiled([item])[0])


def test_spin_runs_on_threads_give_the_serial_loops_results() -> None:
    runs = list(spin_break_variants(8)) + family_runs(FAMILIES["moving_pair"], range(4))
    serial = compiled.run_compiled(runs)
    threaded = compiled.run_compiled(runs, threads=True)
    assert exact_form(threaded) == exact_form(serial)


def test_rolling_and_spin_runs_in_one_call_each_give_their_own_result() -> None:
    rolling = _run_of(load_scene(default_scene_path()), "event", None)
    runs = [rolling, *spin_break_variants(2), rolling]
    together = compiled.run_compiled(runs)
    for item, result in zip(runs, together, strict=True):
        assert exact_form(result) == exact_form(compiled.run_compiled([item])[0])
