"""The compiled sampler (billiards.physics.compiled.sampling): a run's ball centres at
given times, taken from the compiled loop's log without making its result, are the
result's own positions_at, bit for bit: in both motion models, on tables with pockets
(balls dropped) and without (centres clamped to the cushion lines), at times before the
stroke, at every contact, and after the end; in a batch as alone, on threads as serially;
and a run whose result would hold a number that is not finite gives that result, so that
its caller raises what simulate_batch raises."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from billiards.physics.compiled import runner
from billiards.physics.engine.packaging import Run, started
from billiards.physics.engine.result import SimulationResult
from billiards.physics.methods import entry
from billiards.scene.reader import Scene, default_scene_path, load_scene
from billiards.simulation import NonFiniteRun, _run_of, sample_batch, simulate_batch
from tests.physics.test_compiled import FAMILIES, family_runs, fresh_digests, seed_break_variants
from tests.test_batch import exact_form
from tests.test_scene_bounds import runaway_scene


def shipped_scenes() -> list[Scene]:
    """Every shipped scene (both models, with pockets and without), as it is, cut short
    by max_time, and cut short by max_events (its anchors then run past the last contact)."""
    scenes = []
    for path in sorted(default_scene_path().parent.glob("*.toml")):
        scene = load_scene(path)
        simulation = scene.simulation
        scenes += [
            scene,
            dataclasses.replace(scene, simulation=dataclasses.replace(simulation, max_time=0.37)),
            dataclasses.replace(scene, simulation=dataclasses.replace(simulation, max_events=5)),
        ]
    return scenes


def sample_times(result: SimulationResult, seed: int) -> np.ndarray:
    """Times before the stroke, at it, at every contact and motion-state change, between
    them and after the run's end."""
    rng = np.random.default_rng(seed)
    end = result.rest_time
    return np.concatenate(
        [
            [-0.5, -0.0, 0.0, 1e-12, end, end + 2.0],
            [event.time for event in result.events],
            [transition.time for transition in result.transitions],
            np.sort(rng.uniform(0.0, 1.2 * end + 0.1, 64)),
        ]
    )


def results_of(items: list[Run]) -> list[SimulationResult]:
    results = []
    for result in entry.run_batch(items):
        assert isinstance(result, SimulationResult), result
        results.append(result)
    return results


def assert_sampled_as_positions_at(items: list[Run], times: list[np.ndarray]) -> None:
    """entry.sample_batch gives each run's samples (not its result: the sampler ran) and
    they are its result's positions_at, byte for byte."""
    results = results_of(items)
    for item, outcome, result, at in zip(
        items, entry.sample_batch(items, times), results, times, strict=True
    ):
        assert isinstance(outcome, np.ndarray), (item[0].model, outcome)
        assert exact_form(outcome) == exact_form(result.positions_at(at))


@pytest.mark.parametrize("method", ["event", "exact"])
def test_every_shipped_scene_sampled_is_its_positions_at_bit_for_bit(method: str) -> None:
    scenes = shipped_scenes()
    items = [_run_of(scene, method, None) for scene in scenes]
    assert {setup.model for setup, *_ in items} == {"rolling", "spin"}
    assert any(setup.pockets is not None for setup, *_ in items)
    times = [sample_times(result, seed) for seed, result in enumerate(results_of(items))]
    # Alone, and all together (both models in one batch).
    for item, at in zip(items, times, strict=True):
        assert_sampled_as_positions_at([item], [at])
    assert_sampled_as_positions_at(items, times)


def test_balls_dropped_and_pressed_in_the_hard_cases_sample_as_positions_at() -> None:
    dropped = 0
    for family in ("pocket_rack", "jaw_shot", "pressed", "frozen"):
        items = family_runs(FAMILIES[family], range(3))
        results = results_of(items)
        assert_sampled_as_positions_at(items, [sample_times(result, 7) for result in results])
        dropped += sum(len(result.pocketed) for result in results)
    assert dropped > 0


def test_a_run_sampled_in_a_batch_is_sampled_as_alone_and_on_threads_as_serially() -> None:
    items = list(seed_break_variants(12))
    times = [np.linspace(-0.1, 6.0, 40 + index) for index in range(len(items))]
    alone = [runner.sample_compiled([item], [at])[0] for item, at in zip(items, times, strict=True)]
    assert exact_form(runner.sample_compiled(items, times)) == exact_form(alone)
    assert exact_form(runner.sample_compiled(items, times, threads=True)) == exact_form(alone)


def test_a_log_that_overflows_is_sampled_from_its_second_run(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    items = list(seed_break_variants(3))
    times = [np.linspace(0.0, 5.0, 30)] * 3
    wanted = runner.sample_compiled(items, times)
    monkeypatch.setattr(runner, "_LOG_ROOM", 2)  # every run overflows, twice
    monkeypatch.setattr(runner, "_LOG_BYTES", 0)  # (else the byte budget gives room)
    assert exact_form(runner.sample_compiled(items, times)) == exact_form(wanted)


def starts_of(item: Run, count: int, seed: int) -> tuple[np.ndarray, np.ndarray | None]:
    """`count` random starts of the run's balls: velocities (R, N, 2), and spins (R, N, 3)
    in the spin model (None in the rolling)."""
    rng = np.random.default_rng(seed)
    balls = len(item[0].positions)
    velocities = rng.uniform(-2.0, 2.0, (count, balls, 2))
    spins = rng.uniform(-40.0, 40.0, (count, balls, 3)) if item[0].model == "spin" else None
    return velocities, spins


@pytest.mark.parametrize("method", ["event", "exact", "naive"])
def test_one_run_started_many_ways_is_sampled_as_each_started_setup(
    method: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """entry.sample_starts (one setup packed once, each start set in place: the fitter's
    runs) gives, bit for bit, what sample_batch gives for each setup so started, in both
    models, also where every log overflows."""
    for name in ("three_cushion", "break"):
        item = _run_of(load_scene(name), method, 1 / 200 if method == "naive" else None)
        velocities, spins = starts_of(item, 6, seed=len(name))
        times = np.linspace(-0.1, 4.0, 33)
        each = [started(item, velocities[k], None if spins is None else spins[k]) for k in range(6)]
        wanted = list(entry.sample_batch(each, [times] * 6))
        assert exact_form(entry.sample_starts(item, velocities, spins, times)) == exact_form(wanted)
        # Started other ways as many times: the packing kept from the first call is the
        # setup's, each call's starts its own.
        others, other_spins = starts_of(item, 6, seed=len(name) + 1)
        each = [
            started(item, others[k], None if other_spins is None else other_spins[k])
            for k in range(6)
        ]
        assert exact_form(entry.sample_starts(item, others, other_spins, times)) == exact_form(
            list(entry.sample_batch(each, [times] * 6))
        )
        if method != "naive":
            assert all(isinstance(outcome, np.ndarray) for outcome in wanted)
            with monkeypatch.context() as patch:
                patch.setattr(runner, "_LOG_ROOM", 2)
                patch.setattr(runner, "_LOG_BYTES", 0)
                again = runner.sample_starts(item, velocities, spins, times)
            assert exact_form(again) == exact_form(wanted)


def test_a_run_that_is_not_finite_raises_what_simulate_batch_raises() -> None:
    scene = load_scene()
    scenes = [scene, runaway_scene(), scene]
    times = [np.linspace(0.0, 3.0, 7)] * 3
    with np.errstate(all="ignore"):
        outcomes = list(sample_batch(scenes, times))
        results = list(simulate_batch(scenes))
    assert isinstance(outcomes[1], NonFiniteRun) and isinstance(results[1], NonFiniteRun)
    assert str(outcomes[1]) == str(results[1])
    for index in (0, 2):
        result = results[index]
        assert isinstance(result, SimulationResult)
        assert exact_form(outcomes[index]) == exact_form(result.positions_at(times[index]))


def test_runs_the_compiled_loop_does_not_take_are_sampled_from_their_results() -> None:
    scene = load_scene("three_cushion")
    scenes = [scene, scene]
    times = [np.linspace(0.0, 2.0, 9)] * 2
    naive = list(sample_batch(scenes, times, method="naive", dt=1 / 200))
    results = list(simulate_batch(scenes, method="naive", dt=1 / 200))
    for outcome, result, at in zip(naive, results, times, strict=True):
        assert isinstance(result, SimulationResult)
        assert exact_form(outcome) == exact_form(result.positions_at(at))
    bad = list(sample_batch(scenes[:1], times[:1], method="warp"))
    assert isinstance(bad[0], ValueError)


# A fresh process compiles the sampler alone (an empty cache: numba cannot show the code of
# a cached kernel) on a log written by hand, and counts the fused multiply-adds in it.
FMA_COUNT = """
import re
import numpy as np
from billiards.physics.compiled import runner, sampling
from billiards.scene.reader import load_scene
from billiards.simulation import _run_of
setup, ids, method, dt = _run_of(load_scene("three_cushion"), "event", None)
runs = runner._packed([setup], [method], [dt])
logs = runner._logs(1, 4, len(ids), 1)
logs.filled[0, 1] = len(ids)
logs.segment_ball[0, : len(ids)] = np.arange(len(ids))
logs.segment_rows[0, : len(ids)] = 0.0
logs.segment_rows[0, : len(ids), 1:3] = setup.positions
out = np.empty(2 * len(ids) * 3)
sampling.sample_many(runs, logs, np.array([1.0]), np.array([0.0, 0.5, 2.0]),
    np.array([0, 3]), out, np.array([0, len(out)]), np.zeros(1, dtype=np.bool_))
listings = list(sampling.sample_many.inspect_asm().values())
fused = re.compile(r"\\bv?f(n)?m(add|sub)", re.IGNORECASE)
print("listings", len(listings))
print("fma", sum(len(fused.findall(text)) for text in listings))
"""


def test_the_sampler_compiles_no_fused_multiply_add(tmp_path: Path) -> None:
    assert fresh_digests(tmp_path, FMA_COUNT) == {"listings": "1", "fma": "0"}


def test_flying_runs_sample_as_positions_at_bit_for_bit() -> None:
    """Runs with balls in the air (issue 45: the jump shot, the hopping break, seeded
    jumps among balls, a ball flying high over a pocket and off the table) sampled
    densely through their flights, landings, 3D contacts and departures: the compiled
    sampler's centres are their results' positions_at, bit for bit, alone and in one
    batch, and through sample_batch from the scenes."""
    from billiards.physics.spin.motion import FLYING
    from billiards.physics.spin.result import SpinMotion
    from tests.physics.test_flight import corner_setup, jump_family

    scenes = [load_scene(name) for name in ("jump_shot", "hop_break")]
    items = [_run_of(scene, "event", None) for scene in scenes]
    setups = [jump_family(case) for case in range(4)] + [corner_setup(0.25, 6.0, 1.5)]
    for setup in setups:
        ids = tuple(f"b{n}" for n in range(len(setup.positions)))
        items.append((setup, ids, "event", 1 / 240))
    results = results_of(items)
    for result in results:
        assert isinstance(result.motion, SpinMotion)
        assert (result.motion.state == FLYING).any()
    assert results[-1].events[-1].pocket is None  # it left the table
    times = [
        np.concatenate([sample_times(result, seed), np.linspace(0.0, 0.6, 601)])
        for seed, result in enumerate(results)
    ]
    for item, at in zip(items, times, strict=True):
        assert_sampled_as_positions_at([item], [at])
    assert_sampled_as_positions_at(items, times)
    for scene, at, result in zip(scenes, times[:2], results[:2], strict=True):
        (outcome,) = sample_batch([scene], [at])
        assert exact_form(outcome) == exact_form(result.positions_at(at))
