"""One recorded shot against the simulation: its scene, a stroke's error, the stroke fit.

A shot's scene is the table scene's (its table, balls' size, [physics] and
[simulation]) with the recording's balls: the cue ball (the first to move) first, then
the others in the recording's order, each at its first recorded position and at rest,
named by the recording's ids. Only the cue ball's stroke is unknown: its speed, its
direction and its cue-tip offset (side, height, fractions of R: the spin model's
`tip`, billiards.physics.spin.motion.tip_spin).

The error of a stroke is the RMSE over every recorded sample of every ball: the
distance between the recorded centre and the simulated one at that sample's time, the
shot's clock starting when the cue ball is struck (`Shot.start`).
"""

from __future__ import annotations

import contextlib
import functools
import math
from collections import OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Literal, get_args

import numpy as np
import numpy.typing as npt

from billiards.fit.recordings import MOVED, FloatArray, Recording
from billiards.physics.engine.packaging import Run, started
from billiards.physics.spin.motion import tip_spin
from billiards.scene.reader import Ball, Scene
from billiards.simulation import prepare_runs, sample_runs, sample_starts

IntArray = npt.NDArray[np.intp]

# The first-4-s error's window (issue 31), s after the stroke.
EARLY = 4.0
# tailuge/billiards' weighted first-4-s score (dist/fit/rmse.js and its results pages):
# each sample within EARLY s weighs 1 / (1 + t), the cue ball's 1.5 times that.
CUE_WEIGHT = 1.5
# A run that fails (never expected) scores this, in m: worse than any miss.
FAILED = 10.0
# What a stroke fit matches: the whole shot, or (as tailuge/billiards fits and scores
# its strokes) the first EARLY s, weighted (Shot.weights).
Window = Literal["shot", "4s"]
WINDOWS: tuple[Window, ...] = get_args(Window)
# The cue-tip offset stays inside this fraction of the ball's radius (a miscue beyond).
TIP_LIMIT = 0.8


@dataclass(frozen=True)
class Stroke:
    """The cue ball's start: speed (m/s), direction (degrees from +x, counter-clockwise)
    and the cue tip's offset from the centre (side, height) / R."""

    speed: float
    direction: float
    side: float = 0.0
    height: float = 0.0

    def vector(self) -> tuple[float, float, float, float]:
        return (self.speed, self.direction, self.side, self.height)

    @classmethod
    def of(cls, values: Sequence[float] | FloatArray) -> Stroke:
        speed, direction, side, height = (float(value) for value in values)
        reach = math.hypot(side, height)
        if reach > TIP_LIMIT:  # on the ball: the search's box reaches past its edge
            side, height = side * TIP_LIMIT / reach, height * TIP_LIMIT / reach
        return cls(speed, direction, side, height)


@dataclass(frozen=True)
class Shot:
    """A recording made ready to score against simulations of one table."""

    recording: Recording
    order: tuple[str, ...]  # recorded ball ids: the scene's balls, the cue ball first
    start: float  # s of the recording's clock when the cue ball is struck
    times: FloatArray  # (T,) every sample's time after the stroke (>= 0), each once
    samples: tuple[IntArray, ...]  # per ball (scene order): its samples' rows of times
    recorded: tuple[FloatArray, ...]  # per ball: its recorded centres (S, 2)
    early: tuple[npt.NDArray[np.bool_], ...]  # per ball: samples within EARLY of the stroke
    # per ball: each sample's weight in tailuge's first-4-s score (CUE_WEIGHT / (1 + t)
    # for the cue ball, 1 / (1 + t) for the others; 0 after EARLY)
    weights: tuple[FloatArray, ...]
    guess: Stroke  # the stroke its first samples show

    @property
    def id(self) -> str:
        return self.recording.id

    @property
    def duration(self) -> float:
        return float(self.times[-1])

    @functools.cached_property
    def flat(self) -> FlatSamples:
        """Every ball's samples one after another (FlatSamples)."""
        return FlatSamples(
            rows=np.concatenate(self.samples),
            columns=np.concatenate(
                [
                    np.full(len(rows), column, dtype=np.intp)
                    for column, rows in enumerate(self.samples)
                ]
            ),
            bounds=tuple(np.cumsum([0, *(len(rows) for rows in self.samples)]).tolist()),
            recorded=np.concatenate(self.recorded),
            early=np.concatenate(self.early),
            weights=np.concatenate(self.weights),
        )

    def simulated(self, positions: FloatArray) -> FloatArray:
        """Many runs' positions (R, T, N, 2) at the shot's samples, every ball's one after
        another (R, S, 2; FlatSamples' order): one gather, not one a ball."""
        runs, _, balls, _ = positions.shape
        places = self.flat.rows * balls + self.flat.columns
        return np.take(positions.reshape(runs, -1, 2), places, axis=1)  # C-ordered, fast


@dataclass(frozen=True)
class FlatSamples:
    """A shot's samples of every ball one after another (the cue ball's, then the
    others' in scene order), for the errors of many runs at once."""

    rows: IntArray  # (S,) each sample's row of Shot.times
    columns: IntArray  # (S,) its ball's column (scene order)
    bounds: tuple[int, ...]  # ball k's samples are [bounds[k], bounds[k + 1])
    recorded: FloatArray  # (S, 2) the recorded centres
    early: npt.NDArray[np.bool_]  # (S,) within EARLY of the stroke
    weights: FloatArray  # (S,) the weight in tailuge's first-4-s score


def prepare(recording: Recording) -> Shot:
    """The shot's clock, sample rows and first guess at the stroke."""
    cue = recording.cue_ball
    order = (cue, *(ball for ball in recording.balls if ball != cue))
    track = recording.balls[cue]
    start, guess = _stroke_start(track.t, track.xy)
    stroke_times = [np.maximum(recording.balls[ball].t - start, 0.0) for ball in order]
    times, rows = np.unique(np.concatenate(stroke_times), return_inverse=True)
    bounds = np.cumsum([0, *(len(t) for t in stroke_times)])
    samples = tuple(
        np.asarray(rows[bounds[i] : bounds[i + 1]], dtype=np.intp) for i in range(len(order))
    )
    return Shot(
        recording=recording,
        order=order,
        start=start,
        times=times,
        samples=samples,
        recorded=tuple(recording.balls[ball].xy for ball in order),
        early=tuple(t <= EARLY for t in stroke_times),
        weights=tuple(
            np.where(t <= EARLY, (CUE_WEIGHT if index == 0 else 1.0) / (1.0 + t), 0.0)
            for index, t in enumerate(stroke_times)
        ),
        guess=guess,
    )


def _stroke_start(t: FloatArray, xy: FloatArray) -> tuple[float, Stroke]:
    """When the cue ball was struck, and its speed and direction then, from its first
    samples after it moved: their velocity, extrapolated back to where it stood (never
    before the sample at which it last stood there)."""
    moved = np.hypot(*(xy - xy[0]).T) > MOVED
    first = int(np.argmax(moved)) if moved.any() else 0
    if first == 0:  # it never moves (or moved before the recording began)
        return float(t[0]), Stroke(0.5, 0.0)
    later = min(first + 3, len(t) - 1)
    step = xy[later] - xy[first]
    span = t[later] - t[first]
    if later == first or span <= 0:
        step, span = xy[first] - xy[0], t[first] - t[0]
    speed = float(np.hypot(*step) / span) if span > 0 else 1.0
    direction = math.degrees(math.atan2(step[1], step[0]))
    travelled = float(np.hypot(*(xy[first] - xy[0])))
    start = max(float(t[first - 1]), float(t[first]) - travelled / max(speed, 1e-3))
    # The ball slows while it slides: its speed at the stroke is a little more.
    return start, Stroke(speed * 1.03, direction)


def shot_scene(table: Scene, shot: Shot, stroke: Stroke, *, slack: float = 0.5) -> Scene:
    """The table scene with the shot's balls, the cue ball struck with `stroke`; run
    until the last sample (and `slack` s more)."""
    velocity = cue_velocity(stroke)
    mass = table.balls[0].mass if table.balls else Ball("", (0.0, 0.0)).mass
    recorded = tuple((float(centres[0, 0]), float(centres[0, 1])) for centres in shot.recorded)
    size = (table.table.length, table.table.width)
    positions = _apart(recorded, table.radius, size)
    balls = []
    for index, (ball, position) in enumerate(zip(shot.order, positions, strict=True)):
        if index == 0:
            tip = (stroke.side, stroke.height)
            balls.append(Ball(ball, position, velocity=velocity, mass=mass, tip=tip))
        else:
            balls.append(Ball(ball, position, mass=mass))
    simulation = replace(table.simulation, max_time=shot.duration + slack)
    return replace(table, balls=tuple(balls), simulation=simulation)


def cue_velocity(stroke: Stroke) -> tuple[float, float]:
    """The cue ball's velocity (m/s) the stroke gives it."""
    radians = math.radians(stroke.direction)
    return (stroke.speed * math.cos(radians), stroke.speed * math.sin(radians))


@dataclass(frozen=True)
class ShotRun:
    """A shot's run on a table, made once: its scene's (shot_scene) run, which a stroke
    changes only in the cue ball's velocity and spin, set as the scene's setup sets them
    (billiards.simulation.setup_from_scene: tip_spin over every ball's velocity and tip).
    A stroke fit runs its shot some 800 times; a scene and a setup each cost more than
    the compiled run."""

    table: Scene
    shot: Shot
    run: Run | Exception  # the shot's run struck with its guess; or why it makes none

    @classmethod
    def of(cls, table: Scene, shot: Shot) -> ShotRun:
        scenes = [shot_scene(table, shot, shot.guess)]
        return cls(table, shot, next(iter(prepare_runs(scenes))))

    def struck(self, stroke: Stroke) -> Run | Exception:
        """The run with the cue ball (the first) struck with `stroke`."""
        if isinstance(self.run, Exception):
            return self.run
        velocities, spins = self.starts([stroke])
        return started(self.run, velocities[0], None if spins is None else spins[0])

    def starts(self, strokes: Sequence[Stroke]) -> tuple[FloatArray, FloatArray | None]:
        """The balls' velocities (R, N, 2) and spins (R, N, 3; None in the rolling model)
        with the cue ball struck with each stroke (the run must be made)."""
        assert not isinstance(self.run, Exception)
        setup = self.run[0]
        velocities = np.repeat(setup.velocities[None], len(strokes), axis=0)
        velocities[:, 0] = [cue_velocity(stroke) for stroke in strokes]
        if setup.model != "spin":
            return velocities, None
        tips = np.zeros(velocities.shape)  # the other balls' are None: (0, 0)
        tips[:, 0] = [(stroke.side, stroke.height) for stroke in strokes]
        spins = tip_spin(velocities.reshape(-1, 2), tips.reshape(-1, 2), setup.radius)
        return velocities, spins.reshape(len(strokes), -1, 3)

    def sample(self, strokes: Sequence[Stroke]) -> list[FloatArray | Exception]:
        """The balls' centres at the shot's times (T, N, 2) struck with each stroke, or
        the exception its run raised."""
        if isinstance(self.run, Exception):
            return [self.run] * len(strokes)
        velocities, spins = self.starts(strokes)
        return sample_starts(self.run, velocities, spins, self.shot.times, self.table.source)


# The shots' runs kept (shot_run), by the ids of the table and the shot they hold.
_SHOT_RUNS: OrderedDict[tuple[int, int], ShotRun] = OrderedDict()
SHOT_RUNS_KEPT = 256  # a calibration trial's shots (Budget.trial_shots) and more


def shot_run(table: Scene, shot: Shot) -> ShotRun:
    """The shot's ShotRun on the table, made at its first use and kept: an entry holds
    its table and shot, so while it is kept no other object can take their ids."""
    key = (id(table), id(shot))
    found = _SHOT_RUNS.get(key)
    if found is not None:
        _SHOT_RUNS.move_to_end(key)
        return found
    made = _SHOT_RUNS[key] = ShotRun.of(table, shot)
    if len(_SHOT_RUNS) > SHOT_RUNS_KEPT:
        _SHOT_RUNS.popitem(last=False)
    return made


# A stroke fit asks for the same shot's balls some 800 times: kept, they cost nothing.
@functools.lru_cache(maxsize=1024)
def _apart(
    centres: tuple[tuple[float, float], ...], radius: float, size: tuple[float, float]
) -> tuple[tuple[float, float], ...]:
    """The balls' centres inside the cushions and not overlapping: recorded centres are
    rounded to about 1 mm, so two frozen balls may overlap by that, or a ball on the
    cushion sit past it."""
    high = (size[0] - radius, size[1] - radius)
    positions = np.clip(np.array(centres), radius, high)
    for _ in range(3):
        for i in range(len(positions)):
            for j in range(i + 1, len(positions)):
                gap = positions[j] - positions[i]
                distance = float(np.hypot(*gap))
                if distance < 2 * radius * (1 + 1e-9):
                    direction = gap / distance if distance > 0 else np.array([1.0, 0.0])
                    push = (2 * radius * (1 + 1e-6) - distance) / 2
                    positions[i] -= direction * push
                    positions[j] += direction * push
        positions = np.clip(positions, radius, high)
    return tuple((float(x), float(y)) for x, y in positions)


@dataclass(frozen=True)
class Errors:
    """A simulated shot against its recording: squared-distance sums and sample counts,
    over the whole shot and over its first EARLY s, and the first EARLY s's sums
    weighted as tailuge/billiards weighs them (CUE_WEIGHT, 1 / (1 + t))."""

    squares: float
    count: int
    early_squares: float
    early_count: int
    weighted_squares: float = 0.0
    weights: float = 0.0

    @property
    def rmse(self) -> float:
        return math.sqrt(self.squares / self.count)

    @property
    def rmse_early(self) -> float:
        return math.sqrt(self.early_squares / self.early_count) if self.early_count else 0.0

    @property
    def rmse_early_weighted(self) -> float:
        return math.sqrt(self.weighted_squares / self.weights) if self.weights else 0.0

    def loss(self, budget: Budget) -> float:
        """What the stroke search minimises. Window "shot": the mean square distance
        with the first EARLY s's samples counted 1 + early_weight times (a shot's end is
        chaotic: its start says more about the stroke). Window "4s": tailuge/billiards'
        weighted mean over the first EARLY s alone (rmse_early_weighted squared)."""
        if budget.window == "4s":
            return self.weighted_squares / self.weights if self.weights else 0.0
        return (self.squares + budget.early_weight * self.early_squares) / (
            self.count + budget.early_weight * self.early_count
        )


def shot_errors(shot: Shot, positions: FloatArray) -> Errors:
    """The errors of simulated positions (T, N, 2) at the shot's times (the counts are
    the shot's samples, as failed's)."""
    return runs_errors(shot, positions[None])[0]


def runs_errors(shot: Shot, positions: FloatArray) -> list[Errors]:
    """shot_errors of many runs' positions (R, T, N, 2) at once. Each run's sums are
    those of its own samples alone: numpy sums each row of a C-ordered (R, S) array as it
    sums the row by itself (pairwise), so the squares are made C-ordered first (numpy's
    indexing hands them over with the samples outermost)."""
    runs = len(positions)
    squares, early, weighted = np.zeros(runs), np.zeros(runs), np.zeros(runs)
    weights = 0.0
    distance = shot.simulated(positions) - shot.flat.recorded
    every_square = distance[..., 0] * distance[..., 0] + distance[..., 1] * distance[..., 1]
    bounds = shot.flat.bounds
    for column, (within, weight) in enumerate(zip(shot.early, shot.weights, strict=True)):
        square = np.ascontiguousarray(every_square[:, bounds[column] : bounds[column + 1]])
        squares += square.sum(axis=1)
        inside = np.ascontiguousarray(square[:, within])
        early += inside.sum(axis=1)
        weight = weight[within]
        weighted += (weight * inside).sum(axis=1)
        weights += float(weight.sum())
    count = sum(len(rows) for rows in shot.samples)
    early_count = sum(int(within.sum()) for within in shot.early)
    return [
        Errors(
            squares=run_squares,
            count=count,
            early_squares=run_early,
            early_count=early_count,
            weighted_squares=run_weighted,
            weights=weights,
        )
        for run_squares, run_early, run_weighted in zip(
            squares.tolist(), early.tolist(), weighted.tolist(), strict=True
        )
    ]


def failed(shot: Shot) -> Errors:
    count = sum(len(rows) for rows in shot.samples)
    early = sum(int(within.sum()) for within in shot.early)
    return Errors(
        squares=FAILED**2 * count,
        count=count,
        early_squares=FAILED**2 * early,
        early_count=early,
        weighted_squares=FAILED**2,
        weights=1.0,
    )


def simulate_strokes(
    table: Scene, jobs: Sequence[tuple[Shot, Stroke]]
) -> tuple[list[Errors], list[FloatArray | None]]:
    """Each (shot, stroke)'s errors and simulated positions at its times (None for a
    failed run; sample_strokes), each shot's runs scored at once."""
    positions = sample_strokes(table, jobs)
    found: dict[int, Errors] = {}
    for indices in _shots_runs(jobs):
        ran = [index for index in indices if positions[index] is not None]
        if ran:
            stacked = np.stack([positions[index] for index in ran])  # type: ignore[misc]
            found.update(zip(ran, runs_errors(jobs[ran[0]][0], stacked), strict=True))
    errors = [found.get(index) or failed(shot) for index, (shot, _) in enumerate(jobs)]
    return errors, positions


def sample_strokes(table: Scene, jobs: Sequence[tuple[Shot, Stroke]]) -> list[FloatArray | None]:
    """Each (shot, stroke)'s simulated positions at its shot's times (None for a failed
    run), every shot's runs a batch (they share the table's constants): only the samples
    are made, not the runs' results, and each shot's run is made once (shot_run), a
    stroke setting only the cue ball's start."""
    positions: list[FloatArray | None] = [None] * len(jobs)
    for indices in _shots_runs(jobs):
        shot = jobs[indices[0]][0]
        sampled = shot_run(table, shot).sample([jobs[index][1] for index in indices])
        for index, at in zip(indices, sampled, strict=True):
            positions[index] = None if isinstance(at, Exception) else at
    return positions


def _shots_runs(jobs: Sequence[tuple[Shot, Stroke]]) -> list[list[int]]:
    """The jobs' indices, shot by shot (in the order of each shot's first job)."""
    by_shot: dict[int, list[int]] = {}
    for index, (shot, _) in enumerate(jobs):
        by_shot.setdefault(id(shot), []).append(index)
    return list(by_shot.values())


def simulated_positions(table: Scene, shot: Shot, stroke: Stroke, times: FloatArray) -> FloatArray:
    """The shot's balls at `times` after the stroke (T, N, 2), for pictures."""
    run = shot_run(table, shot).struck(stroke)
    (positions,) = sample_runs([run], [times], [table.source])
    if isinstance(positions, Exception):
        raise positions
    return positions


# --- the stroke search ---------------------------------------------------------------------


@dataclass(frozen=True)
class Budget:
    """How hard each search tries: the stroke's global search (differential evolution:
    population per parameter, generations), its local polish (pattern-search rounds);
    the table constants' trials (Nelder-Mead's evaluations, in `passes` runs, each
    from the best so far), each trial's stroke polish rounds (from the best `starts` of
    billiards.fit.table.kinematic_starts) and the shots it fits."""

    population: int = 5
    generations: int = 6
    polish: int = 6
    evaluations: int = 60
    passes: int = 2
    # A trial fits its strokes from the first frames' estimate (billiards.fit.table.
    # kinematic_starts), not from strokes already fitted: 4 rounds from there leave a
    # synthetic shot (tests/test_fit.py's first) 7 mm from its recording at some
    # constants, where 8 reach the noise (1.4 mm), and a trial's loss that jumps with
    # the polish's luck misleads the Nelder-Mead over the constants.
    trial_polish: int = 8
    trial_shots: int = 30
    starts: int = 3  # the search's best few, each polished
    seeded: int = 2  # the best few of the seeded strokes (fit_stroke's seeds), polished
    # fit_stroke takes a stroke whose outcome agrees more with the recording's over the
    # best if its loss (a mean square) is at most this many times the best's: up to
    # twice its RMSE. Held out (docs/validation.md, 2026-12-08), 1.5, 2.0 and 4.0 moved
    # the recording's balls in 88%, 89% and 91% of the shots, the medians unchanged.
    agreeing_loss: float = 4.0
    early_weight: float = 1.0  # Errors.loss
    window: Window = "shot"  # Errors.loss


# The tips (side, height) / R tried with the first samples' stroke as polish starts.
GUESS_TIPS = ((0.0, 0.0), (0.0, 0.4), (0.0, -0.4), (0.4, 0.0), (-0.4, 0.0))


def stroke_bounds(guess: Stroke) -> list[tuple[float, float]]:
    """Where the stroke is searched: near the speed and direction the first samples
    show (the cue ball slides straight until it meets something), any tip offset."""
    return [
        (0.75 * guess.speed, 1.35 * guess.speed),
        (guess.direction - 3.0, guess.direction + 3.0),
        (-TIP_LIMIT, TIP_LIMIT),
        (-TIP_LIMIT, TIP_LIMIT),
    ]


def fit_stroke(
    table: Scene,
    shot: Shot,
    budget: Budget | None = None,
    start: Stroke | None = None,
    seeds: Sequence[Stroke] = (),
    agrees: Callable[[list[Stroke]], list[int]] | None = None,
) -> tuple[Stroke, Errors]:
    """The stroke that best matches one recorded shot on this table (least
    Errors.loss): SciPy's differential evolution over speed, direction and tip, each
    generation simulated as one batch, then its best few polished (polish_strokes),
    with the best budget.seeded of `seeds` (candidates from elsewhere, such as
    billiards.fit.seeds' aimed at the recording's first contact; one batch). With
    `agrees` (how much of the recording's outcome each stroke gives, higher the more:
    billiards.fit.seeds.outcome_check), the polished strokes whose loss is within
    budget.agreeing_loss of the best are ranked by it first, their loss second."""
    from scipy.optimize import differential_evolution

    budget = budget or Budget()
    guess = start or shot.guess

    def losses(candidates: FloatArray) -> FloatArray:
        strokes = [Stroke.of(column) for column in candidates.T]
        errors, _ = simulate_strokes(table, [(shot, stroke) for stroke in strokes])
        return np.array([error.loss(budget) for error in errors])

    bounds = stroke_bounds(shot.guess)
    x0 = np.clip(np.array(guess.vector()), [b[0] for b in bounds], [b[1] for b in bounds])
    found = differential_evolution(
        losses,
        bounds,
        popsize=budget.population,
        maxiter=budget.generations,
        init="sobol",
        x0=x0,
        seed=0,
        polish=False,
        vectorized=True,
        updating="deferred",
        tol=0.0,
    )
    # The best few of the last generation, each polished (one batch for all of them):
    # the search's best may sit in a basin a little worse than a neighbour's, and a
    # narrow basin (a thin cut, a near miss) is easily stepped over.
    population = getattr(found, "population", found.x[None, :])
    energies = getattr(found, "population_energies", np.array([found.fun]))
    starts = [Stroke.of(population[k]) for k in np.argsort(energies)[: max(budget.starts, 1)]]
    # And the first samples' own speed and direction (often the best direction), with
    # a few tips.
    starts += [replace(shot.guess, side=side, height=height) for side, height in GUESS_TIPS]
    if seeds and budget.seeded > 0:
        # The best few seeds, each also with a few tips (a seed knows where to aim, not
        # the spin): the best few of those polished.
        chosen = _best_strokes(table, shot, list(seeds), budget)
        tipped = [
            replace(seed, side=side, height=height)
            for seed in chosen
            for side, height in GUESS_TIPS
        ]
        starts += _best_strokes(table, shot, chosen + tipped, budget)
    strokes, errors = polish_strokes(table, [shot] * len(starts), starts, budget.polish, budget)
    ranked = sorted(range(len(starts)), key=lambda k: errors[k].loss(budget))
    best = ranked[0]
    if agrees is not None and budget.agreeing_loss > 1.0:
        # Of the strokes that match the samples nearly as well as the best, the best of
        # those whose outcome agrees with the recording's the most.
        within = [
            k
            for k in ranked
            if errors[k].loss(budget) <= budget.agreeing_loss * errors[best].loss(budget)
        ]
        agreeing = agrees([strokes[k] for k in within])
        most = max(agreeing)
        best = next(k for k, level in zip(within, agreeing, strict=True) if level == most)
    return strokes[best], errors[best]


def _best_strokes(table: Scene, shot: Shot, strokes: list[Stroke], budget: Budget) -> list[Stroke]:
    """The budget.seeded strokes of least loss (one batch)."""
    errors, _ = simulate_strokes(table, [(shot, stroke) for stroke in strokes])
    ranked = sorted(range(len(strokes)), key=lambda k: errors[k].loss(budget))
    return [strokes[k] for k in ranked[: budget.seeded]]


# Finite-difference steps of the stroke's parameters for the polish's Jacobian: speed
# (a share of it), direction (degrees), side and height (fractions of R). The runs are
# exact to rounding, so small steps stay within one sequence of contacts; but the side's
# must be large enough that its spin outlasts the cloth until a contact (spinning
# friction stops 0.001 R of side in about 0.02 s, 0.1 R in about 2 s: a small side has
# no effect at all), so near zero the side's is a secant's step away from it.
JACOBIAN_STEPS = (1e-4, 1e-3, 0.01, 0.005)
SMALL_SIDE, SIDE_SECANT = 0.03, 0.06
# The polish's dampings (Marquardt's, relative to the normal matrix's diagonal), all
# tried each round in one batch: no state to run away when a step fails.
DAMPING_TRIES = (1e-5, 1e-3, 1e-1, 10.0)


def residuals(shot: Shot, positions: Sequence[FloatArray | None], budget: Budget) -> FloatArray:
    """Each run's (R, M) residuals, from its simulated positions (None: a failed run, every
    residual FAILED): every sample's simulated minus recorded coordinates, each scaled by
    the square root of its weight in Errors.loss (so their squares' sum is the loss
    times a constant of the shot): the first EARLY s's by sqrt(1 + early_weight); in
    window "4s" by sqrt(CUE_WEIGHT / (1 + t)), and the later ones by 0."""
    found = np.full((len(positions), 2 * sum(len(rows) for rows in shot.samples)), FAILED)
    ran = [index for index, at in enumerate(positions) if at is not None]
    if not ran:
        return found
    stacked = np.stack([positions[index] for index in ran])  # type: ignore[misc]
    flat = shot.flat
    if budget.window == "4s":
        weight = np.sqrt(flat.weights)
    else:
        weight = np.where(flat.early, math.sqrt(1.0 + budget.early_weight), 1.0)
    difference = shot.simulated(stacked) - flat.recorded
    found[ran] = (difference * weight[:, None]).reshape(len(ran), -1)
    return found


def polish_strokes(
    table: Scene,
    shots: Sequence[Shot],
    strokes: Sequence[Stroke],
    rounds: int,
    budget: Budget | None = None,
) -> tuple[list[Stroke], list[Errors]]:
    """Every shot's stroke polished by Levenberg-Marquardt on its residuals (each
    sample's position error): each round, one batch simulates every shot's stroke and
    its four finite-difference neighbours (the Jacobian), and a second batch tries a
    step for each of four dampings; a shot keeps the best if it lowers its loss. Every run of both batches has the table's constants, so the
    runs batch together. Deterministic: the same strokes in, the same out."""
    budget = budget or Budget()
    current = list(strokes)
    errors, positions = simulate_strokes(table, list(zip(shots, current, strict=True)))
    for _ in range(rounds):
        jobs: list[tuple[Shot, Stroke]] = []
        for shot, stroke in zip(shots, current, strict=True):
            base = np.array(stroke.vector())
            for axis, step in enumerate(_steps(stroke)):
                moved = base.copy()
                moved[axis] += step
                jobs.append((shot, Stroke(*moved)))
        moved_positions = sample_strokes(table, jobs)  # the Jacobian's: no errors
        tries: list[tuple[Shot, Stroke]] = []
        for index, (shot, stroke) in enumerate(zip(shots, current, strict=True)):
            runs = [positions[index], *moved_positions[4 * index : 4 * index + 4]]
            found = residuals(shot, runs, budget)  # the stroke's, then its neighbours'
            r0 = found[0].copy()
            jacobian = np.stack(
                [(found[1 + axis] - r0) / step for axis, step in enumerate(_steps(stroke))],
                axis=1,
            )
            base = np.array(stroke.vector())
            changes = _damped_steps(jacobian.T @ jacobian, jacobian.T @ r0)
            tries += [(shot, Stroke.of(base + change)) for change in changes]
        tried, tried_positions = simulate_strokes(table, tries)
        for index in range(len(shots)):
            count = len(DAMPING_TRIES)
            options = range(count * index, count * (index + 1))
            best = min(options, key=lambda k: tried[k].loss(budget))
            if tried[best].loss(budget) < errors[index].loss(budget):
                current[index] = tries[best][1]
                errors[index] = tried[best]
                positions[index] = tried_positions[best]
    return current, list(errors)


def _damped_steps(normal: FloatArray, gradient: FloatArray) -> FloatArray:
    """The step (DAMPING_TRIES, 4) for each damping: the normal equations damped by it
    on the diagonal, solved all at once (LAPACK solves each matrix of a stack as it
    solves one alone); a singular one's step is none."""
    dampings = np.array(DAMPING_TRIES)[:, None, None] * np.diag(np.diag(normal) + 1e-12)
    damped = normal + dampings
    try:
        return np.asarray(np.linalg.solve(damped, -gradient), dtype=np.float64)
    except np.linalg.LinAlgError:  # which one: each alone
        changes = np.zeros((len(DAMPING_TRIES), 4))
        for index, matrix in enumerate(damped):
            with contextlib.suppress(np.linalg.LinAlgError):
                changes[index] = np.linalg.solve(matrix, -gradient)
        return changes


def _steps(stroke: Stroke) -> list[float]:
    speed, direction, side, height = JACOBIAN_STEPS
    if abs(stroke.side) < SMALL_SIDE:
        side = SIDE_SECANT if stroke.side >= 0 else -SIDE_SECANT
    return [speed * stroke.speed, direction, side, height]
