"""A run by its method, through the engine that serves it: the physics' one entry.

- `event` and `exact` runs the compiled loop supports (compiled.runner.supports) go
  through it, all in one call;
- the other exact runs through the numpy engine (engine.stepper), a batch per shape;
- `naive` runs, the seed's stepped method, one at a time (methods.naive).

Every run's result is what it gives alone, whichever way it went.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from functools import partial

from billiards.physics.compiled import runner as compiled
from billiards.physics.engine.packaging import Run, result_of, started
from billiards.physics.engine.result import SampledMotion, SimulationResult, keep_final_positions
from billiards.physics.engine.setup import Setup
from billiards.physics.engine.stepper import run_engine
from billiards.physics.laws import CUSHION_LAWS
from billiards.physics.numerics.arrays import FloatArray

METHODS = ("exact", "event", "naive")


def run(setup: Setup, ball_ids: tuple[str, ...], method: str, dt: float) -> SimulationResult:
    """Simulate a setup to rest (or max_time) by `method`, stepping by `dt` where it steps."""
    result = next(run_batch([(setup, ball_ids, method, dt)]))
    if isinstance(result, Exception):
        raise result
    return result


def run_batch(
    runs: Iterable[Run], *, threads: bool = False
) -> Iterator[SimulationResult | Exception]:
    """Each run's result, in order, exactly what it gives alone, or the exception it
    raised (a failing run fails alone). threads: the compiled loop's runs spread over
    threads, the loop's spans side by side (the same bits)."""
    items = list(runs)
    results: list[SimulationResult | Exception | None] = [None] * len(items)
    fast: list[int] = []  # the compiled loop's
    engine: list[int] = []  # the numpy engine's
    for index, (setup, ball_ids, method, dt) in enumerate(items):
        try:
            _check(setup, method, dt)
            if method == "naive":
                results[index] = _naive(setup, ball_ids, dt)
            elif compiled.supports(setup, method):
                fast.append(index)
            else:
                engine.append(index)
        except Exception as error:  # the run's outcome, not the batch's
            results[index] = error
    for indices, finish in ((fast, partial(_compiled, threads=threads)), (engine, run_engine)):
        if indices:
            done = finish([items[index] for index in indices])
            for index, finished in zip(indices, done, strict=True):
                results[index] = finished
    for outcome in results:
        assert outcome is not None
        yield outcome


def sample_batch(
    runs: Iterable[Run], times: Sequence[FloatArray], *, threads: bool = False
) -> Iterator[FloatArray | SimulationResult | Exception]:
    """Each run's ball centres at its `times` (T, N, 2), bit for bit its result's
    positions_at(times), where the compiled loop runs it and every number its result
    would hold is finite: sampled from the loop's log without making the result (most of
    a fitter's cost, when only the samples are wanted). Else, in its place, what
    run_batch gives for it (its result, or the exception it raised), for the caller to
    check and sample."""
    items = list(runs)
    outcomes: list[FloatArray | SimulationResult | Exception | None] = [None] * len(items)
    fast = [index for index, item in enumerate(items) if _samplable(item)]
    if fast:
        sampled: Sequence[FloatArray | SimulationResult | None]
        try:
            sampled = compiled.sample_compiled(
                [items[index] for index in fast], [times[index] for index in fast], threads
            )
        except Exception:  # run_batch runs them again, each failing alone
            sampled = [None] * len(fast)
        for index, sample in zip(fast, sampled, strict=True):
            outcomes[index] = sample
    rest = [index for index, outcome in enumerate(outcomes) if outcome is None]
    done = run_batch([items[index] for index in rest], threads=threads)
    for index, finished in zip(rest, done, strict=True):
        outcomes[index] = finished
    for outcome in outcomes:
        assert outcome is not None
        yield outcome


def sample_starts(
    item: Run,
    velocities: FloatArray,
    spins: FloatArray | None,
    times: FloatArray,
    *,
    threads: bool = False,
) -> list[FloatArray | SimulationResult | Exception]:
    """sample_batch of the run `item` started len(velocities) ways, each with its balls'
    velocities (R, N, 2) and spins (R, N, 3; None: the setup's own), all at `times`, as
    sample_batch gives for the setups so changed: where the compiled loop runs it, without
    making a setup each (compiled.runner.sample_starts)."""
    if _samplable(item):
        try:
            return list(compiled.sample_starts(item, velocities, spins, times, threads))
        except Exception:  # sample_batch runs them again, each failing alone
            pass
    runs = [
        started(item, velocities[index], None if spins is None else spins[index])
        for index in range(len(velocities))
    ]
    return list(sample_batch(runs, [times] * len(runs), threads=threads))


def _samplable(item: Run) -> bool:
    """Whether run_batch would send the run to the compiled loop."""
    setup, _, method, dt = item
    try:
        _check(setup, method, dt)
        return method != "naive" and compiled.supports(setup, method)
    except Exception:  # run_batch gives the run its exception
        return False


def _compiled(items: list[Run], threads: bool) -> list[SimulationResult | Exception]:
    """The compiled loop's results; should it raise, each run again alone, so that a
    failing run fails alone (as in the numpy engine's batches)."""
    try:
        done = compiled.run_compiled(items, threads=threads)
    except Exception as error:
        if len(items) == 1:
            return [error]
        return [outcome for item in items for outcome in _compiled([item], threads=False)]
    keep_final_positions(done)
    return list(done)


def _check(setup: Setup, method: str, dt: float) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    if not dt > 0:
        raise ValueError(f"dt must be positive, got {dt!r}")
    if setup.cushion_law not in CUSHION_LAWS:
        raise ValueError(f"unknown cushion law {setup.cushion_law!r}")
    if setup.drives is not None and (method == "naive" or not compiled.supports(setup, method)):
        raise ValueError(
            f"a ball that leaves the cloth runs in the compiled loop only (the spin model, "
            f"'event' or 'exact', a finite max_time), not by {method!r} here"
        )
    if setup.drives is not None and not setup.gravity > 0:
        raise ValueError(f"a ball that leaves the cloth needs gravity > 0, got {setup.gravity!r}")


def _naive(setup: Setup, ball_ids: tuple[str, ...], dt: float) -> SimulationResult:
    from billiards.physics.methods.naive import run_naive  # the seed's stepped method, on request

    times, positions, velocities, spins, contacts, complete = run_naive(setup, dt)
    motion = SampledMotion(times=times, positions=positions, velocities=velocities, spins=spins)
    item = (setup, ball_ids, "naive", dt)
    return result_of(item, contacts, float(times[-1]), len(times) - 1, motion, complete)
