"""Runs through the compiled loop (billiards.physics.compiled.loop), from Setups to the
SimulationResults the numpy engine gives for them, field for field and bit for bit:
the setups packed into flat arrays, the loop run (on threads if asked), and each run's
log unpacked into the engine's own packaging (engine.stepper.package)."""

from __future__ import annotations

import math
import sys
import threading
from collections import OrderedDict
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from functools import cache, partial
from itertools import accumulate, pairwise
from pathlib import Path

import numpy as np

from billiards.physics.compiled import loop, notice, sampling
from billiards.physics.compiled.jit import thread_count
from billiards.physics.compiled.laws import BALL_LAW_IDS, CUSHION_LAW_IDS, CushionNumbers
from billiards.physics.compiled.roots import BERNSTEIN
from billiards.physics.compiled.state import (
    CONSTANTS,
    KIND_NAMES,
    MODEL_SPIN,
    MODELS,
    ROW_WIDTH,
    Logs,
    Runs,
)
from billiards.physics.engine.batch_log import Contact, ContactLog
from billiards.physics.engine.packaging import Run, package, started
from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.laws.cushion import CushionConstants
from billiards.physics.numerics.arrays import FloatArray
from billiards.physics.rolling.result import RollingMotion

# What compiling the loop (both models, every law, the flight) costs with an empty cache,
# measured 2026-12-08 01:20-01:49 UTC at load 1 on 2 cores: 35.2-38.6 s of CPU,
# 38.3-41.3 s wall for `simulate hard_break` (the head before, measured alternately,
# 36.5-37.2 s of CPU; it measured 30.2-30.4 the night before, on a faster-running machine).
COMPILE_SECONDS = 40
_EXACT_INTEGERS = 1 << 52  # the loop counts events in float64: exact below this
_LOG_ROOM = 256  # contacts a run's log holds at least at first
# What a call's logs may take (bytes): a few runs get room for long runs (a 200-ball
# scene logs about 10,000 contacts), many runs _LOG_ROOM each. A run that overflows its
# room runs again alone from its start, so too little room costs whole reruns (a 200-ball
# scene ran 4 times, 55% of its loop wasted); the OS maps a page only when it is written.
_LOG_BYTES = 32 << 20
_LOG_MOST = 1 << 16


def supports(setup: Setup, method: str) -> bool:
    """Whether the compiled loop runs this setup by this method: the spin model with any
    ball law and cushion law (every law is compiled: compiled.laws), the rolling model
    with the seed's (the only ones the scene reader gives it, and the only ones tested
    against the numpy engine there), pockets or none, `event` or `exact`, to a finite
    max_time; a ball that may leave the cloth (Setup.drives) in the spin model only.
    Everything else runs in the numpy engine (which refuses flight: methods.entry)."""
    seed_laws = setup.ball_law == "frictionless" and setup.cushion_law == "mirror"
    return (
        method in ("event", "exact")
        and setup.model in MODELS
        and (setup.model == "spin" or seed_laws)
        and setup.ball_law in BALL_LAW_IDS
        and setup.cushion_law in CUSHION_LAW_IDS
        and math.isfinite(setup.max_time)
        and 0 <= setup.max_events < _EXACT_INTEGERS
        and len(setup.positions) > 0
        and (setup.drives is None or setup.model == "spin")
    )


def _cushion_numbers(setup: Setup) -> tuple[float, ...]:
    """The run's cushion constants past radius and retention (state.CUSHION_RESTITUTION
    and the four columns after it)."""
    numbers = CushionNumbers.of(CushionConstants.of(setup))
    return tuple(numbers)[2:]


def run_compiled(items: Sequence[Run], threads: bool = False) -> list[SimulationResult]:
    """Each supported run's result (supports), as methods.entry.run_batch gives it;
    threads: the runs spread over jit.thread_count() threads (the same bytes). The runs of each
    motion model go through the loop together (their logs' rows differ in width)."""
    results: list[SimulationResult | None] = [None] * len(items)
    for model in MODELS:
        rows = [row for row, (setup, *_) in enumerate(items) if setup.model == model]
        if rows:
            done = _run_model([items[row] for row in rows], threads)
            for row, result in zip(rows, done, strict=True):
                results[row] = result
    return [result for result in results if result is not None]


def _run_model(items: Sequence[Run], threads: bool) -> list[SimulationResult]:
    """run_compiled for runs of one motion model, each run's result made as soon as its
    span of runs ends (on threads, while the next spans run: making results is Python,
    the loop is not)."""
    return [
        _unpacked(item, logs, row)
        for item, (_, logs, row) in zip(items, _logged(items, threads), strict=True)
    ]


def sample_compiled(
    items: Sequence[Run], times: Sequence[FloatArray], threads: bool = False
) -> list[FloatArray | SimulationResult]:
    """Each supported run's ball centres at its `times` (T, N, 2): bit for bit its
    result's positions_at(times), sampled from its log (compiled.sampling) without
    making the result, where every number that result would hold is finite; else the
    result itself (as run_compiled gives it)."""
    results: list[FloatArray | SimulationResult | None] = [None] * len(items)
    for model in MODELS:
        rows = [row for row, (setup, *_) in enumerate(items) if setup.model == model]
        if rows:
            chosen = [items[row] for row in rows]
            done = _sample_model(chosen, [times[row] for row in rows], threads)
            for row, result in zip(rows, done, strict=True):
                results[row] = result
    return [result for result in results if result is not None]


def _sample_model(
    items: Sequence[Run], times: Sequence[FloatArray], threads: bool
) -> list[FloatArray | SimulationResult]:
    """sample_compiled for runs of one motion model."""
    places = list(_logged(items, threads))
    return _sample_places(items.__getitem__, [setup for setup, *_ in items], times, places)


def sample_starts(
    item: Run,
    velocities: FloatArray,
    spins: FloatArray | None,
    times: FloatArray,
    threads: bool = False,
) -> list[FloatArray | SimulationResult]:
    """sample_compiled of the run `item` started len(velocities) ways, each with its
    balls' velocities (R, N, 2) and spins (R, N, 3; None: the setup's own, for a rolling
    run) in place of the setup's, all sampled at `times`: bit for bit what
    sample_compiled gives for the setups so changed, without making them. The setup is
    packed once and its row repeated (a fitter runs one shot's balls hundreds of times,
    only the cue ball's stroke changing; a setup and its packing cost more than its
    compiled run). The run must be one the loop supports (`supports`)."""
    setup = item[0]
    count = len(velocities)
    # The loop only reads the runs: the repeated setup is shared, the starts are the
    # call's own (copies, in C order).
    runs = _repeated_once(item, count)._replace(
        velocities=np.array(velocities, dtype=np.float64, order="C").reshape(-1, 2)
    )
    if spins is not None:
        runs = runs._replace(spins=np.array(spins, dtype=np.float64, order="C").reshape(-1, 3))
    model = MODELS.index(setup.model)
    _announce(loop.run_many)
    balls = len(setup.positions)
    logs = _logs(count, _first_room(count, balls, model), balls, model)
    for _ in _spans(runs, logs, threads):
        pass

    def item_of(index: int) -> Run:  # made only for a result to unpack (not finite)
        return started(item, velocities[index], None if spins is None else spins[index])

    limits, every_times = [setup] * count, [times] * count
    if logs.filled[:, 2].any():  # a log overflowed: that run again alone (_whole_log)
        places = [_whole_log(runs, logs, row, model) for row in range(count)]
        return _sample_places(item_of, limits, every_times, places)
    return _sampled(item_of, limits, every_times, runs, logs, list(range(count)))


# Runs packed once (_repeated_once), by the id of the run (a tuple) each holds: the run,
# and its packing repeated, by how many times.
_PACKED: OrderedDict[int, tuple[Run, dict[int, Runs]]] = OrderedDict()
PACKED_KEPT = 64
_PACKED_LOCK = threading.Lock()  # a fitter's threads may share it


def _repeated_once(item: Run, count: int) -> Runs:
    """The run packed and repeated `count` times (_repeated), made at its first use and
    kept while the run is among the last PACKED_KEPT used: sample_starts' callers start
    one run many times over, a few counts each. An entry holds its run, so while it is
    kept no other tuple can take its id."""
    with _PACKED_LOCK:
        found = _PACKED.get(id(item))
        if found is None:
            found = _PACKED[id(item)] = (item, {1: _packed([item[0]], [item[2]], [item[3]])})
            if len(_PACKED) > PACKED_KEPT:
                _PACKED.popitem(last=False)
        _PACKED.move_to_end(id(item))
        repeats = found[1]
        if count not in repeats:
            repeats[count] = _repeated(repeats[1], count)
        return repeats[count]


def _repeated(one: Runs, count: int) -> Runs:
    """A packed run (Runs of one) repeated `count` times: the Runs _packed makes of
    `count` copies of its setup."""
    balls = int(one.starts[1])
    rows = {
        name: np.repeat(getattr(one, name), count, axis=0)
        for name in ("constants", "bounds", "jaws", "capture_normal", "capture_level", "segments")
    }
    each = {
        name: np.concatenate([getattr(one, name)] * count)
        for name in ("positions", "velocities", "spins", "drives", "masses")
    }
    return one._replace(starts=np.arange(count + 1, dtype=np.int64) * balls, **rows, **each)


def _sample_places(
    item_of: Callable[[int], Run],
    limits: Sequence[Setup],
    times: Sequence[FloatArray],
    places: Sequence[tuple[Runs, Logs, int]],
) -> list[FloatArray | SimulationResult]:
    """Each run's samples (or result) from where its log is (`_logged`): each set of
    logs the loop filled (the batch's, and each overflowed run's own) sampled in one
    call. item_of(k): run k, made only for a result to unpack; limits: the setups whose
    max_time and max_events end the runs."""
    done: list[FloatArray | SimulationResult | None] = [None] * len(places)
    by_logs: dict[int, list[int]] = {}
    for row, (_, logs, _) in enumerate(places):
        by_logs.setdefault(id(logs), []).append(row)
    for rows in by_logs.values():
        runs, logs, _ = places[rows[0]]
        at = [places[row][2] for row in rows]  # their rows in `logs`
        sampled = _sampled(
            partial(_chosen, item_of, rows),
            [limits[row] for row in rows],
            [times[row] for row in rows],
            runs,
            logs,
            at,
        )
        for row, result in zip(rows, sampled, strict=True):
            done[row] = result
    return [result for result in done if result is not None]


def _chosen(item_of: Callable[[int], Run], rows: Sequence[int], index: int) -> Run:
    return item_of(rows[index])


def _sampled(
    item_of: Callable[[int], Run],
    limits: Sequence[Setup],
    times: Sequence[FloatArray],
    runs: Runs,
    logs: Logs,
    at: list[int],
) -> list[FloatArray | SimulationResult]:
    """Runs `at` of `runs` (the rest skipped), from `logs`: each one's samples, or its
    result where a number of it is not finite (item_of(k): the k-th's run, limits[k]: the
    setup whose max_time and max_events end it)."""
    count = len(runs.constants)
    rows = np.array(at, dtype=np.intp)
    contacts, events = logs.filled[rows, 0], logs.outcome[rows, 0]
    past = events > np.array([setup.max_events for setup in limits], dtype=np.int64)
    if (past & (contacts == 0)).any():  # packaging.package's own IndexError, as it raises it
        return [_unpacked(item_of(k), logs, row) for k, row in enumerate(at)]
    # packaging.ending, run by run (Python's min: the first unless the second is smaller).
    stops = logs.stop[rows]
    max_times = np.array([setup.max_time for setup in limits], dtype=np.float64)
    rest = np.where(max_times < stops, max_times, stops)
    last_contact = np.where(past, logs.contact_time[rows, np.maximum(contacts - 1, 0)], np.inf)
    rest_time = np.zeros(count)
    rest_time[rows] = np.where(past & (last_contact < rest), last_contact, rest)
    run_times = [np.zeros(0)] * count
    for sample_times, row in zip(times, at, strict=True):
        run_times[row] = sample_times
    lengths = [len(t) for t in run_times]
    sizes = (np.array(lengths) * (runs.starts[1:] - runs.starts[:-1]) * 2).tolist()
    time_starts = np.array([0, *accumulate(lengths)], dtype=np.int64)
    out_starts = np.array([0, *accumulate(sizes)], dtype=np.int64)
    out = np.empty(int(out_starts[-1]))
    finite = np.zeros(count, dtype=np.bool_)
    flat_times = np.concatenate(run_times) if count else np.zeros(0)
    sampling.sample_many(runs, logs, rest_time, flat_times, time_starts, out, out_starts, finite)
    done: list[FloatArray | SimulationResult] = []
    for k, row in enumerate(at):
        if not finite[row]:
            done.append(_unpacked(item_of(k), logs, row))
            continue
        balls = int(runs.starts[row + 1] - runs.starts[row])
        block = out[out_starts[row] : out_starts[row + 1]]
        done.append(block.reshape(len(run_times[row]), balls, 2))
    return done


def _logged(items: Sequence[Run], threads: bool) -> Iterator[tuple[Runs, Logs, int]]:
    """The loop run over runs of one motion model: where each run's log is (the runs it
    went with, their logs, its row), in order, each as soon as its span of runs has
    ended (_spans), none overflowed (_whole_log)."""
    runs = _packed(
        [setup for setup, *_ in items],
        [method for _, _, method, _ in items],
        [dt for *_, dt in items],
    )
    model = MODELS.index(items[0][0].model)
    balls = max(len(setup.positions) for setup, *_ in items)
    return _logged_runs(runs, model, balls, threads)


def _logged_runs(
    runs: Runs, model: int, balls: int, threads: bool
) -> Iterator[tuple[Runs, Logs, int]]:
    """_logged of runs already packed (of one motion model, at most `balls` balls each)."""
    _announce(loop.run_many)
    count = len(runs.constants)
    logs = _logs(count, _first_room(count, balls, model), balls, model)
    for first, stop in _spans(runs, logs, threads):
        for row in range(first, stop):
            yield _whole_log(runs, logs, row, model)


def _whole_log(runs: Runs, logs: Logs, row: int, model: int) -> tuple[Runs, Logs, int]:
    """Where run `row`'s whole log is: its row of `logs`, or, where that overflowed, a
    log of its own from running it again alone, with four times the room, until it fits."""
    place, room = (runs, logs, row), logs.contact_time.shape[1]
    while place[1].filled[place[2], 2]:
        room *= 4
        alone = _slice_runs(runs, row)
        more = _logs(1, room, int(alone.starts[1]), model)
        loop.run_many(alone, more, 0, 1)
        place = (alone, more, 0)
    return place


def _spans(runs: Runs, logs: Logs, threads: bool) -> Iterator[tuple[int, int]]:
    """Every run of `runs` through the loop, into its row of `logs`, span by span: each
    span (first, stop) given once its runs have ended. threads: the spans on
    jit.thread_count() threads (the loop holds no GIL; each run's bytes are the same on
    any thread), a few a thread so that long runs even out, the next spans running while
    the caller reads the last."""
    count = len(runs.constants)
    workers = min(thread_count(), count) if threads else 1
    if workers <= 1:
        loop.run_many(runs, logs, 0, count)
        yield 0, count
        return
    parts = 4 * workers
    edges = [count * part // parts for part in range(parts + 1)]
    spans = [(first, stop) for first, stop in pairwise(edges) if stop > first]
    with _quick_handoffs(), ThreadPoolExecutor(workers) as pool:
        running = [pool.submit(loop.run_many, runs, logs, *span) for span in spans]
        for span, done in zip(spans, running, strict=True):
            done.result()
            yield span


# While loop threads run, how long this thread may keep the GIL when one asks for it (s).
# A loop thread whose span ends needs the GIL to return and start its next span; at
# Python's default (5 ms) it waits that long while this thread makes results, idle:
# 2 threads gave 1.27x one in wall time, with this 1.49x (256 seed breaks, 2 cores).
_HANDOFF_SECONDS = 0.0002
_handoffs = threading.Lock()
_handing_off = [0, 0.0]  # calls inside _quick_handoffs, the interval before the first


@contextmanager
def _quick_handoffs() -> Iterator[None]:
    """Python's thread switch interval at most _HANDOFF_SECONDS inside, as it was after
    (the last of overlapping calls restores it)."""
    with _handoffs:
        if _handing_off[0] == 0:
            _handing_off[1] = sys.getswitchinterval()
            sys.setswitchinterval(min(_handing_off[1], _HANDOFF_SECONDS))
        _handing_off[0] += 1
    try:
        yield
    finally:
        with _handoffs:
            _handing_off[0] -= 1
            if _handing_off[0] == 0:
                sys.setswitchinterval(_handing_off[1])


def _packed(setups: Sequence[Setup], methods: Sequence[str], dts: Sequence[float]) -> Runs:
    """The setups as one Runs (state.Runs): balls end to end, constants a row a run."""
    sizes = [len(setup.positions) for setup in setups]
    starts = np.array([0, *accumulate(sizes)], dtype=np.int64)
    tables = [setup.pockets for setup in setups]
    jaws = max((len(table.jaws) for table in tables if table is not None), default=0)
    pockets = max((len(table.names) for table in tables if table is not None), default=0)
    count = len(setups)
    runs = Runs(
        starts=starts,
        positions=np.concatenate([setup.positions for setup in setups]).astype(np.float64),
        velocities=np.concatenate([setup.velocities for setup in setups]).astype(np.float64),
        spins=np.concatenate([_spins_of(setup) for setup in setups]).astype(np.float64),
        drives=np.concatenate([_drives_of(setup) for setup in setups]).astype(np.float64),
        masses=np.concatenate([setup.masses for setup in setups]).astype(np.float64),
        constants=np.zeros((count, CONSTANTS)),
        bounds=np.array([setup.bounds for setup in setups], dtype=np.float64),
        jaws=np.zeros((count, jaws, 2)),
        jaw_pocket=np.zeros(jaws, dtype=np.int64),
        capture_normal=np.zeros((count, pockets, 2)),
        capture_level=np.zeros((count, pockets)),
        segments=np.zeros((count, 4, 2, 2)),
        segment_count=np.zeros(4, dtype=np.int64),
        bernstein_whole=BERNSTEIN[0],
        bernstein_eighths=BERNSTEIN[1],
    )
    for row, (setup, method, dt) in enumerate(zip(setups, methods, dts, strict=True)):
        table = setup.pockets
        runs.constants[row] = (
            setup.radius,
            setup.decel,
            setup.restitution,
            setup.retention,
            setup.max_time,
            setup.max_events,
            method != "event",
            dt,
            0.0 if table is None else table.jaw_reach,
            table is not None,
            MODELS.index(setup.model),
            setup.slide_decel,
            setup.spin_decel,
            BALL_LAW_IDS[setup.ball_law],
            CUSHION_LAW_IDS[setup.cushion_law],
            *_cushion_numbers(setup),
            *setup.ball_friction,
            *_flight_numbers(setup),
        )
        if table is None:
            continue
        runs.jaws[row], runs.jaw_pocket[:] = table.jaws, table.jaw_pocket
        runs.capture_normal[row], runs.capture_level[row] = (
            table.capture_normal,
            table.capture_level,
        )
        for wall, segments in enumerate(table.segments):
            runs.segments[row, wall, : len(segments)] = segments
            runs.segment_count[wall] = len(segments)
    return runs


def _flight_numbers(setup: Setup) -> tuple[float, ...]:
    """state.FLIES to state.SETTLE_SPEED: whether a ball may leave the cloth, then g, the
    bed's e_t and mu_t (the cloth's sliding friction, pooltool's), and the settling
    speed sqrt(2 g h) (airborne.bounces.settle_speed's arithmetic)."""
    if setup.drives is None:
        return (0.0, 0.0, 0.0, 0.0, 0.0)
    settle = math.sqrt(2.0 * setup.gravity * setup.settle_height)
    return (1.0, setup.gravity, setup.table_restitution, setup.sliding_friction, settle)


def _drives_of(setup: Setup) -> np.ndarray:
    """How fast each ball is driven into the bed at t = 0 (N,): Setup.drives, or zeros."""
    return np.zeros(len(setup.positions)) if setup.drives is None else setup.drives


def _spins_of(setup: Setup) -> np.ndarray:
    """A setup's spins (N, 3), zero where it has none (engine.batch.Batch's start)."""
    return np.zeros((len(setup.positions), 3)) if setup.spins is None else setup.spins


def _slice_runs(runs: Runs, row: int) -> Runs:
    """Run `row` of `runs`, as Runs of its own."""
    own = slice(int(runs.starts[row]), int(runs.starts[row + 1]))
    one = slice(row, row + 1)
    return runs._replace(
        starts=np.array([0, own.stop - own.start], dtype=np.int64),
        positions=runs.positions[own],
        velocities=runs.velocities[own],
        spins=runs.spins[own],
        drives=runs.drives[own],
        masses=runs.masses[own],
        constants=runs.constants[one],
        bounds=runs.bounds[one],
        jaws=runs.jaws[one],
        capture_normal=runs.capture_normal[one],
        capture_level=runs.capture_level[one],
        segments=runs.segments[one],
    )


def _first_room(count: int, balls: int, model: int) -> int:
    """The contacts each of `count` runs' logs holds at first: what _LOG_BYTES gives each
    (_logs' arrays), at least _LOG_ROOM, at most _LOG_MOST."""
    room = _LOG_BYTES // (count * _contact_bytes(balls, model))
    return max(_LOG_ROOM, min(_LOG_MOST, room))


@cache
def _contact_bytes(balls: int, model: int) -> int:
    """What one more contact of room adds to a run's logs (_logs' arrays), in bytes."""
    per_run = sum(array.nbytes for array in _logs(1, 1, balls, model))
    return sum(array.nbytes for array in _logs(1, 2, balls, model)) - per_run


def _logs(count: int, room: int, balls: int, model: int) -> Logs:
    """Empty logs for `count` runs of a motion model: `room` contacts each, and anchors
    and motion-state changes for them all (a spin ball's contact may start up to three
    states: a slide, a roll, a spin in place, each a change and an anchor)."""
    anchors = balls + 2 * room + 16
    if model == MODEL_SPIN:
        anchors *= 4
    return Logs(
        contact_time=np.empty((count, room)),
        contact_kind=np.empty((count, room), dtype=np.int64),
        contact_balls=np.empty((count, room, 2), dtype=np.int64),
        contact_speed=np.empty((count, room)),
        contact_pocket=np.empty((count, room), dtype=np.int64),
        segment_ball=np.empty((count, anchors), dtype=np.int64),
        segment_rows=np.empty((count, anchors, ROW_WIDTH[model])),
        transition_time=np.empty((count, anchors)),
        transition_ball=np.empty((count, anchors), dtype=np.int64),
        transition_state=np.empty((count, anchors), dtype=np.int64),
        filled=np.zeros((count, 4), dtype=np.int64),
        outcome=np.zeros((count, 2), dtype=np.int64),
        stop=np.zeros(count),
    )


def _unpacked(item: Run, logs: Logs, row: int) -> SimulationResult:
    """Run `row`'s result from its log (not overflowed), packaged as the numpy engine
    packages it."""
    contacts, anchors, _, transitions = logs.filled[row].tolist()
    setup, ball_ids, _, _ = item
    log = ContactLog(
        contacts=_contacts(logs, row, contacts, setup),
        transitions=list(
            zip(
                logs.transition_time[row, :transitions].tolist(),
                logs.transition_ball[row, :transitions].tolist(),
                logs.transition_state[row, :transitions].tolist(),
                strict=True,
            )
        ),
        segment_balls=logs.segment_ball[row, :anchors].copy(),
        segment_rows=logs.segment_rows[row, :anchors].copy(),
    )
    events, steps = logs.outcome[row].tolist()
    stop = float(logs.stop[row])
    balls, rows, count = log.segment_balls, log.segment_rows, len(ball_ids)
    if setup.model == "spin":
        # The spin model's result, loaded by a spin run only (a rolling run loads none).
        from billiards.physics.spin.motion import STATE_NAMES
        from billiards.physics.spin.result import logged_spin_motion

        spinning = logged_spin_motion(setup, balls, rows, count, **_flight_of(setup, rows))
        return package(item, steps, log, stop, events, spinning, STATE_NAMES)
    rolling = RollingMotion.logged(balls, rows, setup.decel, count)
    return package(item, steps, log, stop, events, rolling, ("rolling",))


def _flight_of(setup: Setup, rows: np.ndarray) -> dict[str, object]:
    """SpinMotion's flight fields from the log's rows (their heights and vertical
    velocities, columns 9 and 10), for a run that lets a ball fly; none otherwise (its
    result is as before)."""
    if setup.drives is None:
        return {}
    return {"z0": rows[:, 9].copy(), "vz0": rows[:, 10].copy(), "gravity": setup.gravity}


def _contacts(logs: Logs, row: int, count: int, setup: Setup) -> list[Contact]:
    """A run's logged contacts as the engine logs them: (time, kind, balls, speed, pocket)."""
    names = () if setup.pockets is None else setup.pockets.names
    times = logs.contact_time[row, :count].tolist()
    kinds = logs.contact_kind[row, :count].tolist()
    balls = logs.contact_balls[row, :count].tolist()
    speeds = logs.contact_speed[row, :count].tolist()
    pockets = logs.contact_pocket[row, :count].tolist()
    return [
        (
            time_,
            KIND_NAMES[kind],
            (first, second) if second >= 0 else (first,),
            speed,
            names[pocket] if pocket >= 0 else None,
        )
        for time_, kind, (first, second), speed, pocket in zip(
            times, kinds, balls, speeds, pockets, strict=True
        )
    ]


def _announce(kernel: object) -> None:
    """Say on stderr, once, that the loop is being compiled (unless notice.announce is
    off, or numba's cache holds it already)."""
    if not notice.announce:
        return
    notice.announce = False
    try:
        index = Path(kernel._cache._cache_file._index_path)  # type: ignore[attr-defined]
    except AttributeError:  # NUMBA_DISABLE_JIT: nothing to compile
        return
    if not index.exists():
        print(
            f"billiards: compiling the physics once (about {COMPILE_SECONDS} s)...",
            file=sys.stderr,
            flush=True,
        )
