"""The bridge from a scene to the physics: a scene's numbers become a Setup, and run.

It sits above both the scene reader and the physics, which know nothing of each other.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import replace
from itertools import islice

import numpy as np

from billiards.physics.engine.packaging import Run
from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods.entry import run, run_batch
from billiards.physics.methods.entry import sample_batch as sample_setups
from billiards.physics.methods.entry import sample_starts as sample_setup_starts
from billiards.physics.numerics.arrays import FloatArray
from billiards.physics.pockets import PocketTable, pocket_table
from billiards.scene.reader import Scene, SceneError
from billiards.shell.cli import first_line


def setup_from_scene(scene: Scene) -> Setup:
    physics = scene.physics
    if physics.model != "spin":
        return _rolling_setup(scene)
    # Imported here: a rolling run loads none of the spin model.
    from billiards.physics.spin.motion import tip_spin

    velocities = np.array([ball.velocity for ball in scene.balls], dtype=np.float64)
    tips = np.array([ball.tip or (0.0, 0.0) for ball in scene.balls], dtype=np.float64)
    spins = tip_spin(velocities, tips, scene.radius)
    for index, ball in enumerate(scene.balls):
        if ball.spin is not None:
            spins[index] = ball.spin
    return replace(
        _rolling_setup(scene),
        model="spin",
        spins=spins,
        slide_decel=physics.sliding_friction * physics.gravity,
        spin_decel=5 * physics.spinning_friction * physics.gravity / (2 * scene.radius),
        cushion_law=physics.cushion_model,
        cushion_restitution=physics.cushion_restitution,
        cushion_friction=physics.cushion_friction,
        cushion_height=physics.cushion_height,
        sliding_friction=physics.sliding_friction,
        cushion_restitution_speed=physics.cushion_restitution_speed,
        ball_law=physics.ball_model,
        ball_friction=(physics.ball_friction_a, physics.ball_friction_b, physics.ball_friction_c),
        drives=_drives(scene),
        gravity=physics.gravity,
        table_restitution=physics.table_restitution,
    )


def _drives(scene: Scene) -> np.ndarray | None:
    """How fast each struck ball is driven into the bed (Setup.drives), for a scene with
    a stroke that jumps (billiards.scene.stroke.jumps: the bed would throw the ball a
    radius or more up) or with `physics.airborne = true` (balls may fly: every elevated
    stroke's drive goes to the bed, and contacts may lift balls); None for any other,
    whose elevated strokes stay on the cloth as they always have (the vertical part
    left out: its runs keep their bits)."""
    from billiards.scene.stroke import jumps, strike

    drives = [
        0.0 if ball.stroke is None else strike(ball.stroke, ball.mass, scene.radius).drive_down
        for ball in scene.balls
    ]
    physics = scene.physics
    restitution = physics.table_restitution
    if not physics.airborne and not any(
        jumps(drive, physics.gravity, scene.radius, restitution) for drive in drives
    ):
        return None
    return np.array(drives, dtype=np.float64)


def _rolling_setup(scene: Scene) -> Setup:
    return Setup(
        positions=np.array([ball.position for ball in scene.balls], dtype=np.float64),
        velocities=np.array([ball.velocity for ball in scene.balls], dtype=np.float64),
        masses=np.array([ball.mass for ball in scene.balls], dtype=np.float64),
        radius=scene.radius,
        table_size=(scene.table.length, scene.table.width),
        decel=scene.physics.rolling_friction * scene.physics.gravity,
        restitution=scene.physics.ball_restitution,
        retention=scene.table.cushion_retention,
        max_time=scene.simulation.max_time,
        max_events=scene.simulation.max_events,
        pockets=_pockets(scene),
    )


def _pockets(scene: Scene) -> PocketTable | None:
    table = scene.table
    if not table.pockets:
        return None
    return pocket_table(
        (table.length, table.width),
        scene.radius,
        table.corner_pocket_width,
        table.side_pocket_width,
        table.jaw_radius,
    )


class NonFiniteRun(ArithmeticError):
    """A run that produced a number that is not finite (inf or nan). The scene reader's
    bounds (docs/scene_bounds.md) keep every scene it accepts from this; a command that
    meets it says so in one line and exits 1, never printing the number."""


def simulate_scene(
    scene: Scene, method: str | None = None, dt: float | None = None
) -> SimulationResult:
    """Simulate a scene to rest (or max_time). method and dt default to the scene's.
    NonFiniteRun if the result holds a number that is not finite, or its arithmetic
    failed (a division by zero, an overflow)."""
    try:
        result = run(*_run_of(scene, method, dt))
    except ArithmeticError as error:
        if isinstance(error, NonFiniteRun):
            raise
        raise NonFiniteRun(
            f"{scene.source}: the run's arithmetic failed ({first_line(error)}); "
            "expected a scene within docs/scene_bounds.md"
        ) from error
    return finite(result, scene.source)


def finite(result: SimulationResult, source: str) -> SimulationResult:
    """The result, if every number it holds is finite (its rest time, final positions,
    events and the motion's anchors or samples); else NonFiniteRun naming the first."""
    numbers: list[tuple[str, object]] = [
        ("the rest time", result.rest_time),
        ("the final positions", result.final_positions),
        ("the contact times", [event.time for event in result.events]),
        ("the impact speeds", [event.impact_speed for event in result.events]),
    ]
    numbers += [
        (f"the motion's {field.name}", getattr(result.motion, field.name))
        for field in dataclasses.fields(result.motion)
    ]
    arrays = [np.asarray(value) for _, value in numbers]
    floats = [array.reshape(-1) for array in arrays if array.dtype.kind == "f"]
    if np.isfinite(np.concatenate(floats)).all():
        return result  # all at once (a batch asks every run); else the first, named:
    for (what, _), array in zip(numbers, arrays, strict=True):
        if array.dtype.kind == "f" and not np.isfinite(array).all():
            raise NonFiniteRun(
                f"{source}: the run produced a number that is not finite ({what}); "
                "expected a scene within docs/scene_bounds.md"
            )
    return result


def _run_of(scene: Scene, method: str | None, dt: float | None) -> Run:
    """What a scene's run takes: its setup, ball ids, method and dt. A scene with a
    stroke that jumps by `naive` is a SceneError (a ball in the air is the compiled
    loop's, by `event` or `exact`)."""
    setup = setup_from_scene(scene)
    chosen = method or scene.simulation.method
    if setup.drives is not None and chosen == "naive":
        raise SceneError(
            f"{scene.source}: method 'naive': expected 'event' or 'exact' for a stroke "
            f"that jumps or physics.airborne (a ball in the air is simulated by those only)"
        )
    return (setup, scene.ball_ids, chosen, dt if dt is not None else scene.simulation.dt)


# How many scenes simulate_batch takes from its input at a time: it holds at most this
# many runs' setups at once (a few kB each), whatever the number of runs.
BATCH_SIZE = 256


def simulate_batch(
    scenes: Iterable[Scene],
    method: str | None = None,
    dt: float | None = None,
    *,
    threads: bool = False,
) -> Iterator[SimulationResult | Exception]:
    """Simulate many scenes; yields, in the scenes' order, each one's result, exactly
    (bit for bit) what `simulate_scene(scene, method, dt)` gives for it alone, or the
    exception its run raised: a failing run fails alone, its neighbours unaffected.

    An iterator, not a list: it takes the scenes BATCH_SIZE at a time from `scenes`
    (which may be a generator) and yields a take's results once its runs have ended,
    so memory is bounded by the take, not the number of runs (`list(...)` for a list).
    The batch goes to billiards.physics.methods.entry.run_batch, which simulates the runs
    that share a shape together, pass by pass (billiards.physics.engine.batch); `naive` runs
    one at a time. threads: the runs the compiled loop supports spread over numba's
    threads (the same bits; for one process that has the machine to itself).
    """
    iterator = iter(scenes)
    while taken := list(islice(iterator, BATCH_SIZE)):
        prepared = [_prepared(scene, method, dt) for scene in taken]
        yield from simulate_runs(prepared, [scene.source for scene in taken], threads=threads)
        del taken, prepared  # before the next take: one batch held at a time


def simulate_runs(
    prepared: Sequence[Run | Exception], sources: Sequence[str], *, threads: bool = False
) -> Iterator[SimulationResult | Exception]:
    """simulate_batch of runs already made from their scenes (an exception in place of a
    scene that makes none, yielded as it is), each named by its scene's source."""
    runs = [item for item in prepared if not isinstance(item, Exception)]
    results = run_batch(runs, threads=threads)
    for item, source in zip(prepared, sources, strict=True):
        yield item if isinstance(item, Exception) else _finite_or_error(next(results), source)


def sample_batch(
    scenes: Iterable[Scene],
    times: Iterable[FloatArray],
    method: str | None = None,
    dt: float | None = None,
    *,
    threads: bool = False,
) -> Iterator[FloatArray | Exception]:
    """Each scene's ball centres (T, N, 2) at its times (one array a scene): exactly (bit
    for bit) what simulate_batch's result for it gives by `positions_at(times)`, or the
    exception simulate_batch yields in its place. The compiled loop's runs are sampled
    from their logs (methods.entry.sample_batch): their results, most of the cost of a
    fitter's run, are never made."""
    pairs = iter(zip(scenes, times, strict=True))
    while taken := list(islice(pairs, BATCH_SIZE)):
        prepared = [_prepared(scene, method, dt) for scene, _ in taken]
        yield from sample_runs(
            prepared, [at for _, at in taken], [scene.source for scene, _ in taken], threads=threads
        )
        del taken, prepared


def sample_runs(
    prepared: Sequence[Run | Exception],
    times: Sequence[FloatArray],
    sources: Sequence[str],
    *,
    threads: bool = False,
) -> Iterator[FloatArray | Exception]:
    """sample_batch of runs already made from their scenes (an exception in place of a
    scene that makes none, yielded as it is), each named by its scene's source: a caller
    that runs one scene many times over with a few numbers changed (billiards.fit.shots)
    makes its runs without a scene each."""
    runs, run_times = [], []
    for item, at in zip(prepared, times, strict=True):
        if not isinstance(item, Exception):
            runs.append(item)
            run_times.append(np.atleast_1d(np.asarray(at, dtype=np.float64)))
    outcomes = sample_setups(runs, run_times, threads=threads)
    for item, at, source in zip(prepared, times, sources, strict=True):
        if isinstance(item, Exception):
            yield item
            continue
        yield _positions(next(outcomes), at, source)


def sample_starts(
    prepared: Run,
    velocities: FloatArray,
    spins: FloatArray | None,
    times: FloatArray,
    source: str,
) -> list[FloatArray | Exception]:
    """sample_runs of one run started len(velocities) ways, each with its balls'
    velocities (R, N, 2) and spins (R, N, 3; None: the setup's own, as for a rolling
    run) in place of its setup's, all at `times`: what sample_runs gives for the runs so
    changed, without making a setup each (methods.entry.sample_starts)."""
    at = np.atleast_1d(np.asarray(times, dtype=np.float64))
    outcomes = sample_setup_starts(prepared, velocities, spins, at)
    return [_positions(outcome, times, source) for outcome in outcomes]


def _positions(
    outcome: FloatArray | SimulationResult | Exception, at: FloatArray, source: str
) -> FloatArray | Exception:
    """A run's samples at `at` from what methods.entry.sample_batch gives for it: its
    samples, its result (checked finite, then sampled) or its exception."""
    if isinstance(outcome, SimulationResult):
        checked = _finite_or_error(outcome, source)
        return checked if isinstance(checked, Exception) else checked.positions_at(at)
    return outcome


def _finite_or_error(
    outcome: SimulationResult | Exception, source: str
) -> SimulationResult | Exception:
    if isinstance(outcome, Exception):
        return outcome
    try:
        return finite(outcome, source)
    except NonFiniteRun as error:  # the run's outcome, as simulate_scene would raise it
        return error


def prepare_runs(
    scenes: Iterable[Scene], method: str | None = None, dt: float | None = None
) -> Iterator[Run | Exception]:
    """Each scene's run (what simulate_runs and sample_runs take), or why it makes none."""
    return (_prepared(scene, method, dt) for scene in scenes)


def _prepared(scene: Scene, method: str | None, dt: float | None) -> Run | Exception:
    """The scene's run, or why the scene makes none."""
    try:
        return _run_of(scene, method, dt)
    except Exception as error:  # the run's outcome, not the batch's
        return error
