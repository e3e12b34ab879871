"""Many runs at once (issue 19): each run of a batch gives exactly, bit for bit, the
result its scene gives alone, whatever the batch's size, its other runs, their order
or the method; a failing run fails alone.

Results are compared whole (every field of the SimulationResult, arrays as bytes,
floats as their bits), and the shipped scenes also against their pins
(tests/test_fingerprints.py). A sample runs by default; `-m hard` runs the rest.
"""

from __future__ import annotations

import dataclasses
import random
import struct
from collections import Counter
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
import pytest

from billiards.physics.engine import batch, stepper
from billiards.physics.engine.events import Event, events_named
from billiards.physics.engine.packaging import Run
from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.methods import entry as methods
from billiards.physics.pockets import pocket_table
from billiards.scene.reader import Scene, SceneError, default_scene_path, load_scene
from billiards.simulation import setup_from_scene, simulate_batch, simulate_scene
from billiards.sweep.variations import load_scene_data
from tests import hard_checks
from tests.physics import test_hard_cases, test_pocket_hard_cases, test_spin_hard_cases
from tests.test_fingerprints import PINS, fingerprint

SHIPPED = tuple(sorted(path.stem for path in default_scene_path().parent.glob("*.toml")))
BREAKS = ("break", "hard_break", "spin_break", "pool_break")  # cut short in mixed batches
hard = pytest.mark.hard


def exact_form(value: Any) -> Any:
    """A value as exact, comparable data: arrays as bytes, floats as their bits (so
    nan equals nan and -0.0 differs from 0.0), dataclasses field by field."""
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, float | np.floating):
        return struct.pack("<d", float(value))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = dataclasses.fields(value)
        return (type(value).__name__, *(exact_form(getattr(value, f.name)) for f in fields))
    if isinstance(value, tuple | list):
        return tuple(exact_form(item) for item in value)
    return value


def assert_same(outcome: SimulationResult | Exception, alone: SimulationResult) -> None:
    assert isinstance(outcome, SimulationResult), f"the run failed in the batch: {outcome}"
    assert exact_form(outcome) == exact_form(alone)
    # The final positions the batch found for all its runs at once (result.
    # keep_final_positions) are each run's own positions_at at its rest time.
    own = outcome.positions_at(np.array([outcome.rest_time]))[0]
    assert exact_form(outcome.final_positions) == exact_form(own)
    assert exact_form(alone.final_positions) == exact_form(own)


def shipped(name: str) -> Scene:
    return load_scene(default_scene_path().parent / f"{name}.toml")


@cache
def alone(scene: Scene, method: str | None, dt: float | None) -> SimulationResult:
    return simulate_scene(scene, method=method, dt=dt)


# --- every shipped scene -----------------------------------------------------------------


@pytest.mark.parametrize(
    ("method", "dt"),
    [
        ("event", None),
        ("exact", 1 / 1000),
        pytest.param("exact", None, marks=hard),
        pytest.param("exact", 1 / 30, marks=hard),
        pytest.param("naive", None, marks=hard),
    ],
)
def test_every_shipped_scene_in_one_batch_gives_its_pinned_result(
    method: str, dt: float | None
) -> None:
    """Each run of the batch of all shipped scenes hashes to its pin (the pins are
    those of the scene run alone), and equals its run alone where it has none (naive
    on hard_break); naive runs one at a time inside the batch, and a scene whose balls
    fly (jump_shot, hop_break) is the SceneError it is alone (the compiled loop's only)."""
    scenes = [shipped(name) for name in SHIPPED]
    results = list(simulate_batch(scenes, method, dt))
    for name, scene, outcome in zip(SHIPPED, scenes, results, strict=True):
        if method == "naive" and setup_from_scene(scene).drives is not None:
            assert isinstance(outcome, SceneError) and "method 'naive'" in str(outcome), name
            continue
        assert isinstance(outcome, SimulationResult), f"{name}: {outcome}"
        if (name, method, dt) in PINS:
            assert fingerprint(outcome) == PINS[name, method, dt], name
        else:
            assert_same(outcome, simulate_scene(scene, method=method, dt=dt))


# --- seeded random batches of mixed scenes -----------------------------------------------


@cache
def scene_pool() -> tuple[tuple[str, Any], ...]:
    """Each shipped scene's tables (the breaks cut at 0.05 s, so a batch stays cheap):
    both models, pockets on (pocket_shot, pool_break) and off."""
    pool = []
    for name in SHIPPED:
        data = load_scene_data(name)
        if name in BREAKS:
            data = dataclasses.replace(data, data=data.with_values([("simulation.max_time", 0.05)]))
        pool.append((name, data))
    return tuple(pool)


def mixed_scenes(seed: int, size: int) -> list[Scene]:
    """`size` scenes drawn from the pool, each with its first ball nudged in x and y by
    up to a micrometre (a nudge that makes a bad scene leaves it as it is)."""
    rng = np.random.default_rng([19, seed])
    pool = scene_pool()
    scenes = []
    for _ in range(size):
        _, data = pool[int(rng.integers(len(pool)))]
        ball = data.scene.ball_ids[0]
        x, y = data.scene.balls[0].position
        values = [
            (f"ball.{ball}.position.x", x + float(rng.uniform(-1e-6, 1e-6))),
            (f"ball.{ball}.position.y", y + float(rng.uniform(-1e-6, 1e-6))),
        ]
        try:
            scenes.append(data.build(data.with_values(values)))
        except SceneError:
            scenes.append(data.scene)
    return scenes


METHODS = [("event", None), ("exact", 1 / 240)]


@pytest.mark.parametrize("size", [1, 2, 7, pytest.param(64, marks=hard)])
@pytest.mark.parametrize(("method", "dt"), METHODS)
def test_a_mixed_batch_gives_each_run_its_result_alone(
    size: int, method: str, dt: float | None
) -> None:
    scenes = mixed_scenes(size, size)
    for scene, outcome in zip(scenes, simulate_batch(scenes, method, dt), strict=True):
        assert_same(outcome, alone(scene, method, dt))


@pytest.mark.parametrize(("method", "dt"), METHODS)
def test_a_shuffled_batch_gives_the_same_results(method: str, dt: float | None) -> None:
    """The same 16 runs in three orders, taken from a generator: every run's result is
    the one it gives alone."""
    scenes = mixed_scenes(16, 16)
    orders = [list(range(16)), list(range(15, -1, -1))]
    orders.append(random.Random(19).sample(range(16), 16))
    for order in orders:
        results = simulate_batch((scenes[n] for n in order), method, dt)
        for n, outcome in zip(order, results, strict=True):
            assert_same(outcome, alone(scenes[n], method, dt))


@hard
@pytest.mark.parametrize("seed", range(8))
def test_many_mixed_batches_give_each_run_its_result_alone(seed: int) -> None:
    scenes = mixed_scenes(1000 + seed, 64)
    dt = (1 / 30, 1 / 240, 1 / 1000, 1e-5)[seed % 4]
    for method, step in (("event", None), ("exact", dt)):
        for scene, outcome in zip(scenes, simulate_batch(scenes, method, step), strict=True):
            assert_same(outcome, alone(scene, method, step))


# --- failures stay per run ---------------------------------------------------------------


def broken(scene: Scene, **physics: Any) -> Scene:
    return dataclasses.replace(scene, physics=dataclasses.replace(scene.physics, **physics))


def test_a_failing_run_fails_alone_and_leaves_its_neighbours_unchanged() -> None:
    good = mixed_scenes(5, 4)
    warp = dataclasses.replace(
        good[0], simulation=dataclasses.replace(good[0].simulation, method="warp")
    )  # fails in the stepper
    cushion = broken(shipped("draw_shot"), cushion_model="warp")  # fails in its calendar
    scenes = [good[0], warp, good[1], good[2], cushion, good[3]]
    outcomes = list(simulate_batch(scenes))
    assert isinstance(outcomes[1], ValueError)
    assert "unknown method 'warp'" in str(outcomes[1])
    assert isinstance(outcomes[4], ValueError)
    assert "unknown cushion law 'warp'" in str(outcomes[4])
    for n, scene in ((0, good[0]), (2, good[1]), (3, good[2]), (5, good[3])):
        assert_same(outcomes[n], alone(scene, None, None))


def test_a_bad_method_fails_every_run_with_its_reason() -> None:
    outcomes = list(simulate_batch(mixed_scenes(6, 3), method="warp"))
    assert all(isinstance(outcome, ValueError) for outcome in outcomes)
    assert all("unknown method 'warp'" in str(outcome) for outcome in outcomes)


def test_a_generator_of_scenes_is_taken_lazily() -> None:
    """simulate_batch takes a generator and yields as it goes: the first result comes
    before the input is exhausted."""
    taken = []

    def scenes() -> Any:
        for scene in mixed_scenes(7, 3):
            taken.append(scene)
            yield scene

    results = simulate_batch(scenes())
    assert taken == []  # nothing is run before the first result is asked for
    next(results)
    assert len(taken) == 3  # one take (up to BATCH_SIZE scenes)


# --- the hard-case families through the batch path ---------------------------------------

Check = Callable[[SimulationResult, Setup], None]


def rolling_check(result: SimulationResult, setup: Setup) -> None:
    hard_checks.check_sound(result, setup)
    test_hard_cases.assert_no_pair_meets_twice_without_cause(result)


def spin_check(result: SimulationResult, setup: Setup) -> None:
    hard_checks.check_no_nan(result)
    times = hard_checks.sample_times(result)
    if setup.pockets is None:
        hard_checks.check_inside_cushions(result, times)
        hard_checks.check_no_overlap(result, times)
    else:
        hard_checks.check_on_pocket_table(result, times)
        hard_checks.check_no_pocketed_overlap(result, times)
        hard_checks.check_pocketed(result)
    hard_checks.check_spin_energy_never_rises(result, times)
    hard_checks.check_contacts_conserve_momentum(result, setup.restitution)


pockets = test_pocket_hard_cases
spins = test_spin_hard_cases
# family -> (its size under -m hard, the case's setup, the invariants of its tests)
FAMILIES: dict[str, tuple[int, Callable[[int], Setup], Check]] = {
    "rack": (1000, test_hard_cases.rack_case, rolling_check),
    "scene": (200, test_hard_cases.scene_case, rolling_check),
    "pressed": (300, test_hard_cases.pressed_case, rolling_check),
    "cluster": (240, test_hard_cases.cluster_case, rolling_check),
    "line": (120, test_hard_cases.line_case, rolling_check),
    "frozen": (60, test_hard_cases.frozen_case, rolling_check),
    "pocket_rack": (
        400,
        lambda i: pockets.on_the_table(test_hard_cases.rack_case(i)),
        hard_checks.check_pocket_sound,
    ),
    "pocket_scene": (
        200,
        lambda i: pockets.on_the_table(test_hard_cases.scene_case(i)),
        hard_checks.check_pocket_sound,
    ),
    "jaw_shot": (400, pockets.jaw_shot_case, hard_checks.check_pocket_sound),
    "strike": (60, spins.strike, spin_check),
    "english": (40, spins.english, spin_check),
    "spin_frozen": (12, spins.frozen, spin_check),
    "pocket_strike": (60, lambda i: spins.with_pockets(spins.strike(i)), spin_check),
    "pocket_english": (60, lambda i: spins.with_pockets(spins.english(i)), spin_check),
}
SAMPLE = 1  # cases of each family by default
BATCH = 40  # cases per batch under -m hard


def family_cases(hard_run: bool) -> list[tuple[str, int]]:
    rng = np.random.default_rng(20261202)
    cases: list[tuple[str, int]] = []
    for family, (size, _, _) in FAMILIES.items():
        chosen = range(size) if hard_run else rng.choice(size, SAMPLE, replace=False)
        cases.extend((family, int(index)) for index in chosen)
    return cases


def assert_families_through_the_batch(cases: list[tuple[str, int]], method: str) -> None:
    """The cases as one batch of setups (methods.run_batch): each equals its run alone
    and keeps every invariant its family's tests assert."""
    setups = [FAMILIES[family][1](index) for family, index in cases]
    runs = [
        (setup, tuple(f"b{n}" for n in range(len(setup.positions))), method, 1 / 240)
        for setup in setups
    ]
    outcomes = methods.run_batch(runs)
    for (family, index), setup, outcome in zip(cases, setups, outcomes, strict=True):
        assert isinstance(outcome, SimulationResult), f"{family}[{index}]: {outcome}"
        reference = hard_checks.run(setup, method)
        assert exact_form(outcome) == exact_form(reference), f"{family}[{index}]"
        assert outcome.complete, f"{family}[{index}] did not come to rest"
        FAMILIES[family][2](outcome, setup)


@pytest.mark.parametrize("method", ["event", pytest.param("exact", marks=hard)])
def test_a_sample_of_the_hard_case_families_through_one_batch(method: str) -> None:
    assert_families_through_the_batch(family_cases(False), method)


@hard
@pytest.mark.parametrize("chunk", range(3152 // BATCH + 1))
def test_the_hard_case_families_through_batches(chunk: int) -> None:
    cases = family_cases(True)[chunk * BATCH : (chunk + 1) * BATCH]
    if cases:
        assert_families_through_the_batch(cases, "event")


# --- sweeps: many runs of one shape, resolved together -----------------------------------


def swept(name: str, runs: int, *keys: tuple[str, float, float]) -> list[Scene]:
    """`runs` copies of a shipped scene with each key drawn from N(mean, sd), as a sweep
    draws them (seed 19)."""
    data = load_scene_data(name)
    rng = np.random.default_rng(19)
    return [
        data.build(data.with_values([(key, float(rng.normal(mean, sd))) for key, mean, sd in keys]))
        for _ in range(runs)
    ]


SWEEPS = {
    "break": ("break", 24, ("ball.cue.position.y", 0.5325, 0.001)),
    "spin_break": ("spin_break", 12, ("ball.cue.tip.side", 0.0, 0.02)),
    "pool_break": ("pool_break", 6, ("ball.cue.position.y", 0.5, 0.001)),
}


@pytest.fixture
def numpy_engine(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every run through the numpy engine (these tests look inside its batches; the
    compiled loop's runs are held to it in tests/physics/test_compiled.py)."""
    monkeypatch.setattr(methods.compiled, "supports", lambda setup, method: False)


@pytest.mark.long
@pytest.mark.parametrize("sweep", SWEEPS)
@pytest.mark.parametrize(("method", "dt"), METHODS)
@pytest.mark.usefixtures("numpy_engine")
def test_a_sweep_of_one_scene_gives_each_run_its_result_alone(
    monkeypatch: pytest.MonkeyPatch, sweep: str, method: str, dt: float | None
) -> None:
    name, runs, key = SWEEPS[sweep]
    scenes = swept(name, runs, key)
    together = []
    resolve_pairs = stepper.resolve_pairs

    def counted(calendars: Any, wanted: np.ndarray) -> np.ndarray:
        left = resolve_pairs(calendars, wanted)
        together.append(len(wanted) - len(left))
        return left

    monkeypatch.setattr(stepper, "resolve_pairs", counted)
    for scene, outcome in zip(scenes, simulate_batch(scenes, method, dt), strict=True):
        assert_same(outcome, alone(scene, method, dt))
    assert sum(together) > runs  # the runs' plain contacts were resolved together


@pytest.mark.usefixtures("numpy_engine")
def test_a_run_failing_midway_in_a_shared_batch_fails_alone(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A run of a sweep that raises part way (here: at its first anchoring after 0.2 s,
    whether its event was resolved with the other runs' or on its own) fails alone: its
    outcome is the error, and every other run of the batch is its result alone."""
    from billiards.physics.engine import batch as batch_module

    scenes = swept("break", 8, ("ball.cue.position.y", 0.5325, 0.001))
    data = load_scene_data("break")
    values = [("ball.cue.position.y", 0.5326), ("ball.1.mass", 0.171)]  # the marked run
    marked = data.build(data.with_values(values))
    scenes.insert(3, marked)
    queue, queue_rows = batch_module.Batch.queue, batch_module.Batch.queue_rows

    def marked_after(self: batch_module.Batch, runs: list[int], times: list[float]) -> None:
        for run, time in zip(runs, times, strict=True):
            if time > 0.2 and self.setups[run].masses[1] == 0.171:
                raise RuntimeError("the marked run fails")

    def failing(
        self: batch_module.Batch, run: int, balls: Any, time: float, *rest: Any, **named: Any
    ) -> None:
        marked_after(self, [run], [time])
        queue(self, run, balls, time, *rest, **named)

    def failing_rows(
        self: batch_module.Batch, runs: Any, balls: Any, times: Any, *rest: Any
    ) -> None:
        marked_after(self, runs.tolist(), times.tolist())
        queue_rows(self, runs, balls, times, *rest)

    monkeypatch.setattr(batch_module.Batch, "queue", failing)
    monkeypatch.setattr(batch_module.Batch, "queue_rows", failing_rows)
    outcomes = list(simulate_batch(scenes))
    assert isinstance(outcomes[3], RuntimeError)
    for n, scene in enumerate(scenes):
        if n != 3:
            assert_same(outcomes[n], alone(scene, None, None))


def test_jaw_and_capture_events_among_batched_cushions() -> None:
    """Spin runs with pockets (pocket_english 28-59, several of each shape): a run whose
    event is a jaw or a capture line while others meet cushions is left to its calendar
    (it once raised an IndexError in the batched cushions, and, the last run of its pass,
    that error became its result instead of a rerun alone)."""
    assert_families_through_the_batch([("pocket_english", n) for n in range(28, 60)], "event")


# --- runs that differ in their constants and ball counts (issue 35) ----------------------


def varied(setup: Setup, rng: np.random.Generator) -> Setup:
    """`setup` with every constant a law or a motion model reads drawn anew (within a
    few percent, so the scene stays valid: a smaller ball and a larger table keep every
    gap open), and maybe its last balls taken away (at least two stay)."""

    def scaled(value: float, low: float = 0.9, high: float = 1.1) -> float:
        return value * float(rng.uniform(low, high))

    keep = max(2, len(setup.positions) - int(rng.integers(0, 4)))
    radius = scaled(setup.radius, 0.97, 1.0)
    length, width = setup.table_size
    table_size = (scaled(length, 1.0, 1.03), scaled(width, 1.0, 1.03))
    pockets = setup.pockets
    if pockets is not None:
        pockets = pocket_table(
            table_size,
            radius,
            scaled(pockets.corner_width, 0.97, 1.03),
            scaled(pockets.side_width, 0.97, 1.03),
            scaled(pockets.jaw_radius),
        )
    return dataclasses.replace(
        setup,
        positions=setup.positions[:keep],
        velocities=setup.velocities[:keep],
        masses=setup.masses[:keep] * rng.uniform(0.95, 1.05, keep),
        spins=None if setup.spins is None else setup.spins[:keep],
        radius=radius,
        table_size=table_size,
        decel=scaled(setup.decel),
        restitution=float(rng.uniform(0.9, 1.0)),
        retention=float(rng.uniform(0.6, 0.9)),
        max_time=min(scaled(setup.max_time), 1.0),  # short: the default suite stays quick
        slide_decel=scaled(setup.slide_decel),
        spin_decel=scaled(setup.spin_decel),
        cushion_restitution=scaled(setup.cushion_restitution, 0.9, 1.0),
        cushion_friction=scaled(setup.cushion_friction),
        cushion_height=scaled(setup.cushion_height, 0.99, 1.01),
        sliding_friction=scaled(setup.sliding_friction),
        cushion_restitution_speed=scaled(setup.cushion_restitution_speed),
        ball_friction=tuple(scaled(value) for value in setup.ball_friction),  # type: ignore[arg-type]
        pockets=pockets,
    )


@cache
def family_setups() -> dict[tuple[str, str, str, bool], list[Setup]]:
    """The shipped scenes' setups (breaks cut short) by what may split a batch: the
    model, the ball and cushion laws, and pockets or none; the spin model's every law
    pair, with pockets and without, from the spin scenes re-lawed."""
    families: dict[tuple[str, str, str, bool], list[Setup]] = {}
    for _, data in scene_pool():
        setup = setup_from_scene(data.scene)
        if setup.drives is not None:  # a jump (issue 45): the compiled loop's only
            continue
        laws = [(setup.ball_law, setup.cushion_law)]
        if setup.model == "spin":
            laws = [(ball, cushion) for ball in BALL_LAWS for cushion in CUSHION_LAWS]
        for ball_law, cushion_law in laws:
            relawed = dataclasses.replace(setup, ball_law=ball_law, cushion_law=cushion_law)
            key = (setup.model, ball_law, cushion_law, setup.pockets is not None)
            families.setdefault(key, []).append(relawed)
    return families


def varied_runs(family: tuple[str, str, str, bool], seed: int, size: int) -> list[Run]:
    rng = np.random.default_rng([35, seed])
    setups = family_setups()[family]
    runs = []
    for _ in range(size):
        setup = varied(setups[int(rng.integers(len(setups)))], rng)
        ids = tuple(f"b{n}" for n in range(len(setup.positions)))
        runs.append((setup, ids, "event" if rng.integers(2) else "exact", 1 / 240))
    return runs


def assert_each_as_alone(runs: list[Run], monkeypatch: pytest.MonkeyPatch) -> None:
    """Each run's result in the batch is its result alone, by the numpy engine (which
    made one batch of each shape: none failed over to its runs alone) and by the
    compiled loop where it supports the run."""
    made: list[int] = []

    class Counted(stepper.Batch):
        def __init__(self, setups: Any) -> None:
            made.append(len(setups))
            super().__init__(setups)

    monkeypatch.setattr(stepper, "Batch", Counted)
    monkeypatch.setattr(methods.compiled, "supports", lambda setup, method: False)
    outcomes = list(methods.run_batch(runs))
    alone = [methods.run(*item) for item in runs]
    monkeypatch.undo()
    shapes = Counter(batch.shape_of(setup) for setup, *_ in runs)
    assert sorted(made[: len(shapes)]) == sorted(shapes.values())
    for outcome, own in zip(outcomes, alone, strict=True):
        assert_same(outcome, own)
    for item, outcome in zip(runs, methods.run_batch(runs), strict=True):
        assert_same(outcome, methods.run(*item))


def families() -> list[tuple[str, str, str, bool]]:
    return sorted(family_setups())


@pytest.mark.long
@pytest.mark.parametrize("size", [1, 2, 7, pytest.param(64, marks=hard)])
def test_a_batch_mixing_constants_and_ball_counts_gives_each_run_its_result_alone(
    size: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every family (both models, pockets on and off, every ball and cushion law),
    its runs' constants and ball counts all drawn per run."""
    for index, family in enumerate(families()):
        assert_each_as_alone(varied_runs(family, 100 * size + index, size), monkeypatch)


def test_a_shuffled_batch_mixing_constants_gives_the_same_results(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    runs = varied_runs(("rolling", "frictionless", "mirror", False), 7, 12)
    runs += varied_runs(("spin", "frictional", "han2005", True), 8, 4)
    random.Random(35).shuffle(runs)
    assert_each_as_alone(runs, monkeypatch)


@hard
@pytest.mark.parametrize("seed", range(4))
def test_many_batches_mixing_constants_give_each_run_its_result_alone(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    runs = [item for family in families() for item in varied_runs(family, 900 + seed, 16)]
    random.Random(seed).shuffle(runs)
    assert_each_as_alone(runs, monkeypatch)


def passes(runs: list[Run], monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The batches the numpy engine makes of `runs` (the compiled loop refused): how
    many runs each, and how many passes (selections of every unfinished run's next
    event) they took in all."""
    sizes: list[int] = []
    selections = [0]

    class Counted(stepper.Batch):
        def __init__(self, setups: Any) -> None:
            sizes.append(len(setups))
            super().__init__(setups)

        def select(self, runs: Any) -> None:
            selections[0] += 1
            super().select(runs)

    monkeypatch.setattr(stepper, "Batch", Counted)
    monkeypatch.setattr(methods.compiled, "supports", lambda setup, method: False)
    list(methods.run_batch(runs))
    monkeypatch.undo()
    return [*sizes, selections[0]]


CONSTANTS: dict[str, Any] = {
    "radius": 0.028,
    "table_size": (2.2, 1.1),
    "decel": 0.08,
    "restitution": 0.93,
    "retention": 0.7,
    "max_time": 9.0,
    "max_events": 900,
    "slide_decel": 2.2,
    "spin_decel": 9.0,
    "cushion_restitution": 0.8,
    "cushion_friction": 0.3,
    "cushion_height": 0.037,
    "sliding_friction": 0.25,
    "cushion_restitution_speed": 2.0,
    "ball_friction": (0.01, 0.1, 1.2),
    "pockets": pocket_table((2.2, 1.1), 0.0286, 0.12, 0.13, 0.009),
}


@pytest.mark.parametrize("name", [*CONSTANTS, "ball count"])
def test_runs_differing_only_in_a_constant_share_every_pass(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Two runs of the pool break, one with a constant changed (or two balls fewer):
    one batch of both, whose passes are as many as the longer run's alone, not the sum."""
    setup = setup_from_scene(shipped("pool_break"))
    setup = dataclasses.replace(setup, max_time=0.2)
    if name == "ball count":
        other = dataclasses.replace(
            setup,
            positions=setup.positions[:-2],
            velocities=setup.velocities[:-2],
            masses=setup.masses[:-2],
            spins=None if setup.spins is None else setup.spins[:-2],
        )
    else:
        other = dataclasses.replace(setup, **{name: CONSTANTS[name]})
    runs = [
        (each, tuple(f"b{n}" for n in range(len(each.positions))), "event", 1 / 240)
        for each in (setup, other)
    ]
    *together, both = passes(runs, monkeypatch)
    first, second = (passes([item], monkeypatch)[-1] for item in runs)
    assert together == [2]
    assert both == max(first, second) < first + second
    assert_each_as_alone(runs, monkeypatch)


def test_events_built_in_bulk_are_the_events_their_class_builds() -> None:
    """stepper packages a run's contacts by events.events_named (each event's fields set
    at once): every event equals, field for field and in its attributes, Event(...)."""
    ids = ("cue", "one", "two")
    contacts = [
        (0.25, "ball", (0, 2), 1.5, None),
        (0.5, "cushion", (1,), 0.75, "left_corner"),
        (0.5, "pocket", (2,), 0.5, "left_corner"),
        (1.0, "ball", (0, 2), 0.125, None),
    ]
    built = events_named(contacts, ids)
    expected = tuple(
        Event(time, kind, tuple(ids[ball] for ball in balls), speed, pocket)
        for time, kind, balls, speed, pocket in contacts
    )
    assert [vars(event) for event in built] == [vars(event) for event in expected]
    assert exact_form(built) == exact_form(expected)
    assert built == expected and hash(built) == hash(expected)
    with pytest.raises(dataclasses.FrozenInstanceError):
        built[0].time = 1.0  # type: ignore[misc]
