"""Runs: what run i of a sweep simulates, and the row it returns.

A plan maps a run's index to its inputs and scene, and nothing else (no state, no
clock), so any worker computes any batch of runs and gets the same rows. A run whose
scene or simulation fails returns a row saying why in one line; the sweep goes on.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from itertools import groupby

import numpy as np

from billiards.physics.engine.result import SimulationResult
from billiards.physics.numerics.arrays import FloatArray
from billiards.scene.reader import Scene
from billiards.shell.cli import first_line
from billiards.simulation import simulate_batch
from billiards.sweep import draws
from billiards.sweep.variations import MAX_RUNS, SceneData, Variations, VaryError

NUDGE_METHODS = ("exact", "event", "naive")
NUDGES_PER_DECADE = 4


@dataclass(frozen=True)
class RunRow:
    """One run's result: its inputs, and what the simulation ended with."""

    run: int
    inputs: tuple[float | str, ...]  # the plan's input columns, in order
    failed: str | None  # why the run failed (one line), or None
    rest_time: float  # s (nan if failed)
    ball_contacts: int
    cushion_contacts: int
    stopped_by: str | None  # "max_time" / "max_events" if cut short
    positions: FloatArray  # (N, 2) m at rest, in the scene's ball order (nan if failed)
    contacts: np.ndarray  # (N,) contacts each ball took part in
    pockets: tuple[str, ...] = ()  # (N,) the pocket each ball dropped into, or ""


@dataclass(frozen=True)
class VaryPlan:
    """`--vary`: run i sets each key to its grid point or its (seed, i) draw."""

    scene_data: SceneData
    variations: Variations
    runs: int
    method: str | None = None

    @property
    def input_names(self) -> tuple[str, ...]:
        return tuple(item.key for item in self.variations.items)

    def run_input(
        self, run: int
    ) -> tuple[tuple[float | str, ...], list[tuple[str, float]], str | None]:
        values = self.variations.values(run)
        return tuple(value for _, value in values), values, self.method


@dataclass(frozen=True)
class NudgePlan:
    """`--nudge`: for each method, the scene itself (nudge 0) and then copies with the
    cue ball moved along +y by each nudge; run i is (method i // k, nudge i % k)."""

    scene_data: SceneData
    ball: str  # the ball moved: the cue ball, or the scene's first
    nudges: tuple[float, ...]  # m, 0 first
    methods: tuple[str, ...] = NUDGE_METHODS

    @property
    def runs(self) -> int:
        return len(self.methods) * len(self.nudges)

    @property
    def input_names(self) -> tuple[str, ...]:
        return ("method", "nudge")

    def run_input(
        self, run: int
    ) -> tuple[tuple[float | str, ...], list[tuple[str, float]], str | None]:
        method, index = divmod(run, len(self.nudges))
        y = next(ball for ball in self.scene_data.scene.balls if ball.id == self.ball).position[1]
        nudged = y + self.nudges[index]
        # The distance actually moved: y + 1e-15 rounds to a whole number of ulps of y.
        return (self.methods[method], nudged - y), [(self.key, nudged)], self.methods[method]

    @property
    def key(self) -> str:
        return f"ball.{self.ball}.position.y"


# What run i of a sweep simulates: a pure function of i (run_input).
Plan = VaryPlan | NudgePlan


def nudge_plan(scene_data: SceneData, text: str, methods: tuple[str, ...]) -> NudgePlan:
    """`--nudge lo:hi` (4 per decade) or `lo:hi:n` -> a NudgePlan; VaryError if bad."""
    expected = "expected lo:hi or lo:hi:n with 0 < lo < hi (m), e.g. 1e-15:1e-3"
    parts = text.split(":")
    try:
        low, high = float(parts[0]), float(parts[1])
        count = int(parts[2]) if len(parts) == 3 else None
    except (ValueError, IndexError):
        raise VaryError(f"--nudge {text}: {expected}") from None
    if len(parts) > 3 or not (0 < low < high < math.inf) or (count is not None and count < 2):
        raise VaryError(f"--nudge {text}: {expected}")
    most = MAX_RUNS // len(methods) - 1  # each method also runs the scene unnudged
    if count is not None and count > most:
        raise VaryError(
            f"--nudge {text}: {count:,} nudges: expected at most {most:,} (a sweep runs at "
            f"most {MAX_RUNS:,}: {len(methods)} methods x (1 + nudges))"
        )
    if count is None:
        count = max(2, round(NUDGES_PER_DECADE * draws.log(high / low) / draws.log(10.0)) + 1)
    ids = scene_data.scene.ball_ids
    ball = "cue" if "cue" in ids else ids[0]
    nudges = (0.0, *draws.geometric_points(low, high, count))
    return NudgePlan(scene_data, ball, nudges, methods)


def run_rows(plan: Plan, runs: range, threads: bool = False) -> list[RunRow]:
    """The rows of `runs`, in order: their scenes are built one by one (a scene that
    fails to build fails its run alone) and simulated together through
    simulate_batch (on threads if asked), one call per stretch of runs sharing
    a method (a nudge plan's runs change method every len(nudges) runs)."""
    built = [_build(plan, run) for run in runs]
    outcomes: list[SimulationResult | Scene | Exception] = [scene for _, scene, _ in built]
    ready = [n for n, outcome in enumerate(outcomes) if isinstance(outcome, Scene)]
    for method, group in groupby(ready, key=lambda n: built[n][2]):
        chosen = list(group)
        scenes = [scene for n in chosen if isinstance(scene := outcomes[n], Scene)]
        for n, outcome in zip(
            chosen, simulate_batch(scenes, method=method, threads=threads), strict=True
        ):
            outcomes[n] = outcome
    return [_row(plan, run, built[n][0], outcomes[n]) for n, run in enumerate(runs)]


def _build(plan: Plan, run: int) -> tuple[tuple[float | str, ...], Scene | Exception, str | None]:
    """Run `run`'s inputs, its scene (or why it could not be built) and its method."""
    inputs, values, method = plan.run_input(run)
    scene_data = plan.scene_data
    try:
        return inputs, scene_data.build(scene_data.with_values(values)), method
    except Exception as error:  # a failed run is a row, not a crashed sweep
        return inputs, error, method


def _row(
    plan: Plan,
    run: int,
    inputs: tuple[float | str, ...],
    outcome: SimulationResult | Scene | Exception,
) -> RunRow:
    count = len(plan.scene_data.scene.balls)
    if not isinstance(outcome, SimulationResult):
        assert isinstance(outcome, Exception)  # every built scene has its outcome
        return RunRow(
            run=run,
            inputs=inputs,
            failed=first_line(outcome),
            rest_time=math.nan,
            ball_contacts=0,
            cushion_contacts=0,
            stopped_by=None,
            positions=np.full((count, 2), math.nan),
            contacts=np.zeros(count, dtype=np.int64),
        )
    result = outcome
    ball_contacts = sum(1 for event in result.events if event.kind == "ball")
    index = {ball_id: n for n, ball_id in enumerate(result.ball_ids)}
    contacts = np.zeros(count, dtype=np.int64)
    for event in result.events:
        if event.kind == "pocket":
            continue  # a drop is no contact
        for ball_id in event.balls:
            contacts[index[ball_id]] += 1
    dropped = {drop.ball: drop.pocket for drop in result.pocketed}
    return RunRow(
        run=run,
        inputs=inputs,
        failed=None,
        rest_time=float(result.rest_time),
        ball_contacts=ball_contacts,
        cushion_contacts=sum(1 for event in result.events if event.kind == "cushion"),
        stopped_by=result.stopped_by,
        positions=np.asarray(result.final_positions, dtype=np.float64),
        contacts=contacts,
        pockets=tuple(dropped.get(ball_id, "") for ball_id in result.ball_ids),
    )


@dataclass(frozen=True)
class Batch:
    """A batch's rows, and the seconds its worker spent on them (for sizing batches)."""

    start: int
    rows: list[RunRow]
    seconds: float


def run_batch(plan: Plan, start: int, stop: int, threads: bool = False) -> Batch:
    """Runs start..stop-1: the unit of work a worker gets, simulated as one batch
    (threads: on the process's threads, for a process that has the machine to itself)."""
    began = time.perf_counter()
    rows = run_rows(plan, range(start, stop), threads)
    return Batch(start, rows, time.perf_counter() - began)
