"""Speed against error: every method on closed-form cases and on breaks, how a nudge
grows in the break, and how the cost grows with the number of balls.

    python scripts/accuracy_report.py [--quick] [--out DIR] [--real CV_SHOTS] [--real-only]

Writes accuracy.md (a table per case, the command and the machine) and accuracy.png
(error against wall time, log-log, one curve per method, plus the growth of a nudge)
into --out, and prints the tables. The default folder, accuracy-report/, is untracked;
`--out docs/explanation` refreshes the copies the site shows. --quick runs fewer steps and repeats (for
trying the script, not for the committed report).

Errors are measured against closed forms computed here (the README's model section) where one exists,
and against the "event" method (the reference) on the breaks. Wall time is the
median of warm repeats; this machine is shared, so compare rows of one report.

The last section is the error against a real table: per cushion law, the median over
122 recorded shots of the cross-validated position RMSE against the CPU time of one
shot's stroke fit. It is read, not recomputed (about half an hour of CPU): from
scripts/validation_tracks.py's output, `--real` (default docs/fit_cv_shots.csv, the run
docs/validation.md shows); `--real-only` refreshes just that section of --out's report.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.physics.engine.result import AnchoredMotion, SampledMotion, SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods import entry as methods
from billiards.physics.numerics import roots
from billiards.physics.rolling import law as calendar_module
from billiards.scene.reader import rack_positions

FloatArray = npt.NDArray[np.float64]

R = 0.0286  # m
TABLE = (2.13, 1.065)  # m
DECEL = 0.01 * 9.81  # m/s^2
RETENTION = 0.75
CUE_MASS, OBJECT_MASS = 0.170, 0.165
HEAD_SPOT = (TABLE[0] / 4, TABLE[1] / 2)
FOOT_SPOT = (3 * TABLE[0] / 4, TABLE[1] / 2)

EXACT_STEPS = (1 / 30, 1 / 240, 1 / 1000, 1 / 10000)
NAIVE_STEPS = (1 / 30, 1 / 60, 1 / 120, 1 / 240, 1 / 500, 1 / 1000, 1 / 2000, 1 / 5000, 1 / 10000)
NUDGES = (1e-15, 1e-12, 1e-9, 1e-6)  # m, added to the cue ball's start y
FLOOR = 1e-17  # m: where an error of exactly 0 is drawn on the log plot


def setup_of(
    positions: npt.ArrayLike,
    velocities: npt.ArrayLike,
    masses: npt.ArrayLike,
    *,
    table_size: tuple[float, float] = TABLE,
    max_time: float = 600.0,
) -> Setup:
    """The seed's setup (Setup.of's defaults) on a table of any size, rolling long."""
    return Setup.of(positions, velocities, masses, table_size=table_size, max_time=max_time)


def simulate(setup: Setup, method: str, dt: float | None) -> SimulationResult:
    ids = tuple(f"b{index}" for index in range(len(setup.positions)))
    return methods.run(setup, ids, method, dt if dt is not None else 1 / 240)


@dataclass(frozen=True)
class Timed:
    method: str
    dt: float | None
    result: SimulationResult
    seconds: float  # median warm wall time of one run


def timed(setup: Setup, method: str, dt: float | None, budget: float) -> Timed:
    """Median wall time over repeats that fit in `budget` seconds (at least one,
    at most seven), after one untimed warm run that is also the returned result."""
    start = time.perf_counter()
    result = simulate(setup, method, dt)
    first = time.perf_counter() - start
    repeats = max(1, min(7, int(budget / max(first, 1e-6))))
    if first > budget:
        return Timed(method, dt, result, first)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        simulate(setup, method, dt)
        times.append(time.perf_counter() - start)
    return Timed(method, dt, result, statistics.median(times))


def runs(setup: Setup, quick: bool, budget: float) -> list[Timed]:
    exact_steps = EXACT_STEPS[:2] if quick else EXACT_STEPS
    naive_steps = NAIVE_STEPS[:4] if quick else NAIVE_STEPS
    out = [timed(setup, "event", None, budget)]
    out += [timed(setup, "exact", dt, budget) for dt in exact_steps]
    out += [timed(setup, "naive", dt, budget) for dt in naive_steps]
    return out


def step_label(dt: float | None) -> str:
    return "-" if dt is None else f"1/{round(1 / dt)}"


def sci(value: float) -> str:
    if value == 0:
        return "0"
    if not math.isfinite(value):
        return str(value)
    return f"{value:.1e}"


# --- closed forms (the README's model section) -----------------------------------------------------------


def roll(position: FloatArray, velocity: FloatArray) -> FloatArray:
    """Where a ball rolling freely from here stops: v^2 / (2 mu g) along v."""
    speed = float(np.hypot(*velocity))
    if speed == 0:
        return position
    return np.asarray(position + velocity / speed * speed**2 / (2 * DECEL))


def arrival(speed: float, distance: float) -> tuple[float, float]:
    """Time to roll `distance` from `speed`, and the speed then."""
    remaining = math.sqrt(speed * speed - 2 * DECEL * distance)
    return (speed - remaining) / DECEL, remaining


@dataclass(frozen=True)
class ClosedForm:
    name: str
    what: str
    setup: Setup
    final: FloatArray  # (N, 2) rest positions by the formula


def stop_case() -> ClosedForm:
    start, speed = np.array([0.4, 0.5]), 0.5
    velocity = np.array([speed * math.cos(0.3), speed * math.sin(0.3)])
    return ClosedForm(
        "stop distance",
        "one ball at 0.5 m/s, 17 degrees off the x axis: stops v^2/(2 mu g) = 1.274 m away",
        setup_of([start], [velocity], [CUE_MASS]),
        np.array([roll(start, velocity)]),
    )


def head_on_case() -> ClosedForm:
    m1, m2, v = CUE_MASS, OBJECT_MASS, 0.5
    cue, target = np.array([0.3, 0.5]), np.array([0.3 + 2 * R + 0.05, 0.5])
    _, u = arrival(v, 0.05)
    contact = target - np.array([2 * R, 0.0])
    after_cue = np.array([(m1 - m2) / (m1 + m2) * u, 0.0])
    after_target = np.array([2 * m1 / (m1 + m2) * u, 0.0])
    return ClosedForm(
        "head-on, unequal masses",
        "0.170 kg at 0.5 m/s into 0.165 kg at rest: v1' = (m1-m2)/(m1+m2) u, "
        "v2' = 2 m1/(m1+m2) u, then each rolls to rest",
        setup_of([cue, target], [(v, 0.0), (0.0, 0.0)], [m1, m2]),
        np.array([roll(contact, after_cue), roll(target, after_target)]),
    )


def cut_case() -> ClosedForm:
    v, gap, cut = 0.5, 0.1, math.radians(30)
    cue = np.array([0.4, 0.4])
    contact = cue + np.array([gap, 0.0])
    normal = np.array([math.cos(cut), math.sin(cut)])  # line of centres at contact
    target = contact + 2 * R * normal
    _, u = arrival(v, gap)
    object_velocity = u * math.cos(cut) * normal
    cue_velocity = np.array([u, 0.0]) - object_velocity
    return ClosedForm(
        "30 degree cut",
        "equal masses, elastic: the object ball leaves along the line of centres at "
        "u cos 30, the cue ball at right angles at u sin 30",
        setup_of([cue, target], [(v, 0.0), (0.0, 0.0)], [OBJECT_MASS, OBJECT_MASS]),
        np.array([roll(contact, cue_velocity), roll(target, object_velocity)]),
    )


def bank_case() -> ClosedForm:
    """Off the y = W cushion, then the x = L cushion, then to rest: mirror images, the
    speed scaled by sqrt(0.75) at each cushion, the deceleration along the path."""
    start, speed, heading = np.array([1.2, 0.5]), 0.8, math.radians(35)
    position, direction = start.copy(), np.array([math.cos(heading), math.sin(heading)])
    top, right = TABLE[1] - R, TABLE[0] - R
    for axis, line in ((1, top), (0, right)):
        distance = (line - position[axis]) / direction[axis]
        _, speed = arrival(speed, distance)
        position = position + direction * distance
        position[axis] = line
        direction[axis] = -direction[axis]
        speed *= math.sqrt(RETENTION)
    return ClosedForm(
        "bank off two cushions",
        "0.8 m/s at 35 degrees: the top cushion, the right cushion, then rest",
        setup_of([start], [speed_vector(0.8, heading)], [CUE_MASS]),
        np.array([roll(position, direction * speed)]),
    )


def speed_vector(speed: float, heading: float) -> tuple[float, float]:
    return (speed * math.cos(heading), speed * math.sin(heading))


# --- the breaks ---------------------------------------------------------------------------


def break_setup(speed: float, nudge: float = 0.0) -> Setup:
    rack = rack_positions(FOOT_SPOT, R, 0.0001)
    positions = [(HEAD_SPOT[0], HEAD_SPOT[1] + nudge), *rack]
    velocities = [(speed, 0.0)] + [(0.0, 0.0)] * len(rack)
    return setup_of(positions, velocities, [CUE_MASS] + [OBJECT_MASS] * len(rack))


def grid(*results: SimulationResult, count: int = 4000) -> FloatArray:
    end = max(result.rest_time for result in results)
    return np.linspace(0.0, end, count)


def position_error(result: SimulationResult, reference: SimulationResult) -> tuple[float, float]:
    """Largest distance of any ball from the reference over the run, and at rest."""
    times = grid(result, reference)
    difference = result.positions_at(times) - reference.positions_at(times)
    over_run = float(np.hypot(difference[..., 0], difference[..., 1]).max())
    at_rest = result.final_positions - reference.final_positions
    return over_run, float(np.hypot(at_rest[:, 0], at_rest[:, 1]).max())


def first_difference(result: SimulationResult, reference: SimulationResult) -> float:
    """When the sequence of contacts (kind and balls) first differs; inf if never."""
    for mine, theirs in zip(result.events, reference.events, strict=False):
        if (mine.kind, mine.balls) != (theirs.kind, theirs.balls):
            return min(mine.time, theirs.time)
    if len(result.events) == len(reference.events):
        return math.inf
    longer = result.events if len(result.events) > len(reference.events) else reference.events
    return longer[min(len(result.events), len(reference.events))].time


def soundness(result: SimulationResult) -> tuple[float, float, float]:
    """Deepest overlap of two balls in the method's own output (at every contact, or at
    every step for naive), deepest overlap drawn between those (a 20000-point grid of
    positions_at, what a film shows), and furthest excursion past a cushion line (m, 0
    if none)."""
    motion = result.motion
    drawn = motion.positions_at(grid(result, count=20000))
    if isinstance(motion, SampledMotion):
        own = motion.positions
    else:
        assert isinstance(motion, AnchoredMotion)
        own = motion.positions_at(np.unique(motion.t0))
    own_overlap, own_escape = _overlap_and_escape(result, own)
    drawn_overlap, drawn_escape = _overlap_and_escape(result, drawn)
    return own_overlap, drawn_overlap, max(own_escape, drawn_escape)


def _overlap_and_escape(result: SimulationResult, positions: FloatArray) -> tuple[float, float]:
    count = len(result.ball_ids)
    first, second = np.triu_indices(count, k=1)
    length, width = result.table_size
    overlap = escape = 0.0
    for chunk in range(0, len(positions), 4096):
        block = positions[chunk : chunk + 4096]
        delta = block[:, first] - block[:, second]
        gap = float(np.hypot(delta[..., 0], delta[..., 1]).min()) - 2 * R
        overlap = max(overlap, -gap)
        escape = max(
            escape,
            R - float(block[..., 0].min()),
            float(block[..., 0].max()) - (length - R),
            R - float(block[..., 1].min()),
            float(block[..., 1].max()) - (width - R),
        )
    return overlap, escape


# --- scaling ------------------------------------------------------------------------------


LARGE_TABLE = (4.0, 2.0)  # m: room for 200 balls (they cover 6 % of it)


def scattered(count: int, moving: int, seed: int) -> Setup:
    """`count` balls at random non-overlapping spots on the large table, the first
    `moving` of them rolling at 1 to 3 m/s in random directions."""
    rng = np.random.default_rng(seed)
    length, width = LARGE_TABLE
    positions: list[FloatArray] = []
    while len(positions) < count:
        candidate = rng.uniform([R, R], [length - R, width - R])
        if all(np.hypot(*(candidate - p)) >= 2 * R + 1e-6 for p in positions):
            positions.append(candidate)
    speed = rng.uniform(1.0, 3.0, count) * (np.arange(count) < moving)
    heading = rng.uniform(0, 2 * math.pi, count)
    velocities = np.stack([speed * np.cos(heading), speed * np.sin(heading)], axis=1)
    return setup_of(positions, velocities, [OBJECT_MASS] * count, table_size=LARGE_TABLE)


@dataclass
class Tally:
    """How many pairs the calendar refreshed, and for how many of them the quartic's
    critical points had to be solved (the certificate could not rule contact out)."""

    pairs: int = 0
    quartic: int = 0


def counted(setup: Setup) -> Tally:
    """Run once with the contact-time functions wrapped to count their rows."""
    tally = Tally()
    pair_contacts = calendar_module.pair_contacts
    solve = roots.cubic_roots_within

    def counting_pairs(*args: object, **kwargs: object) -> FloatArray:
        tally.pairs += len(args[1])  # type: ignore[arg-type]
        return pair_contacts(*args, **kwargs)  # type: ignore[arg-type]

    def counting_solve(coefficients: FloatArray, low: float, high: float) -> FloatArray:
        tally.quartic += len(coefficients)
        return solve(coefficients, low, high)

    calendar_module.pair_contacts = counting_pairs
    roots.cubic_roots_within = counting_solve
    try:
        simulate(setup, "event", None)
    finally:
        calendar_module.pair_contacts = pair_contacts
        roots.cubic_roots_within = solve
    return tally


@dataclass(frozen=True)
class ScalingRow:
    balls: int
    moving: int
    events: int
    seconds: float
    pairs: int
    quartic: int


def scaling_row(count: int, moving: int, budget: float) -> ScalingRow:
    setup = scattered(count, moving, seed=count * 1000 + moving)
    run = timed(setup, "event", None, budget)
    tally = counted(setup)
    return ScalingRow(
        count, moving, len(run.result.events), run.seconds, tally.pairs, tally.quartic
    )


# --- the report ---------------------------------------------------------------------------


def table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(" --- " for _ in header) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return lines


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            for line in info:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (
        f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, "
        f"Python {platform.python_version()}, numpy {np.__version__}"
    )


# The targets on recorded shots (issue 31): tailuge/billiards' held-out median, cm.
REAL_TARGET = 12.3


def real_table(path: Path) -> list[str]:
    """The section on the error against a real table, from a cross-validation's
    per-shot rows (model, window, fold, id, rmse_cm, rmse_4s_cm, rmse_4s_weighted_cm,
    stroke_cpu_s; window and the weighted column may be missing); none without the
    file."""
    if not path.is_file():
        return []
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    lines = [
        "## Against a real table",
        "",
        f"From `{path}` (scripts/validation_tracks.py, 5-fold cross-validation over the "
        "122 recorded three-cushion shots of ../shared/data/carom_tracks/train.json; "
        "docs/validation.md, Recorded shots, has the command, the load and the budget). "
        "Per cushion law: the median over shots of the position RMSE of every ball at "
        "every recorded sample, each shot scored on constants calibrated without it "
        "(a law run `--fixed`: the scene's own), against the CPU time of one shot's "
        "stroke fit (a few hundred simulations of a 9-16 s three-ball shot). Centimetres to "
        "decimetres, where the event method's error against its closed forms above is "
        "at rounding: against a real table the model, not the arithmetic, is what is off.",
        "",
    ]
    table_rows = []
    for model, window in sorted({(row["model"], row.get("window", "shot")) for row in rows}):
        mine = [
            row for row in rows if row["model"] == model and row.get("window", "shot") == window
        ]
        whole = [float(row["rmse_cm"]) for row in mine]
        early = [float(row["rmse_4s_cm"]) for row in mine]
        weighted = [
            float(row["rmse_4s_weighted_cm"]) for row in mine if row.get("rmse_4s_weighted_cm")
        ]
        cpu = [float(row["stroke_cpu_s"]) for row in mine]
        table_rows.append(
            [
                model,
                "whole shot" if window == "shot" else "first 4 s, weighted",
                str(len(mine)),
                f"{statistics.median(whole):.1f}",
                f"{statistics.median(early):.1f}",
                f"{statistics.median(weighted):.1f}" if weighted else "",
                f"{max(whole):.1f}",
                str(sum(value <= REAL_TARGET for value in whole)),
                f"{statistics.mean(cpu):.2f}",
            ]
        )
    lines += table(
        [
            "cushion law",
            "strokes fitted to",
            "shots",
            "median RMSE, whole shot (cm)",
            "median, first 4 s (cm)",
            "median, first 4 s weighted as tailuge's (cm)",
            "worst (cm)",
            f"shots <= {REAL_TARGET:g} cm",
            "stroke fit, CPU a shot (s)",
        ],
        table_rows,
    )
    return [*lines, ""]


def refresh_real_table(report: Path, real: Path) -> None:
    """Replace (or add) the real-table section of a written report, before its last
    line (the report's runtime); every other line kept."""
    lines = report.read_text(encoding="utf-8").split("\n")
    title = "## Against a real table"
    if title in lines:
        start = lines.index(title)
        end = next(
            (
                k
                for k in range(start + 1, len(lines))
                if lines[k].startswith(("## ", "Report runtime"))
            ),
            len(lines),
        )
        del lines[start:end]
    at = next((k for k, line in enumerate(lines) if line.startswith("Report runtime")), len(lines))
    lines[at:at] = real_table(real)
    report.write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(real_table(real)))


def closed_form_section(
    quick: bool,
    budget: float,
    started: float,
    plot_points: dict[str, dict[str, list[tuple[float, float]]]],
) -> list[str]:
    """Every method on the cases with a closed form: its rest error and wall time."""
    lines: list[str] = []
    lines += ["## Cases with a closed form", ""]
    for case in (stop_case(), head_on_case(), cut_case(), bank_case()):
        rows = []
        points = plot_points.setdefault(case.name, {})
        for run in runs(case.setup, quick, budget):
            error = float(np.hypot(*(run.result.final_positions - case.final).T).max())
            rows.append(
                [
                    run.method,
                    step_label(run.dt),
                    str(run.result.steps),
                    f"{run.seconds * 1e3:.2f}",
                    sci(error),
                ]
            )
            points.setdefault(run.method, []).append((run.seconds, max(error, FLOOR)))
        lines += [f"### {case.name}", "", case.what + ".", ""]
        lines += table(["method", "step (s)", "steps", "wall (ms)", "rest error (m)"], rows)
        lines += [""]
        print(f"{case.name}: done ({time.perf_counter() - started:.0f} s)", file=sys.stderr)

    return lines


def break_section(
    quick: bool,
    budget: float,
    started: float,
    plot_points: dict[str, dict[str, list[tuple[float, float]]]],
) -> list[str]:
    """Every method on two breaks against the event reference, and its soundness."""
    lines: list[str] = []
    lines += [
        "## Breaks",
        "",
        "Against the `event` reference: the largest distance of any ball from the "
        "reference over the run (4000 times) and at rest; when the sequence of contacts "
        "(kind and balls) first differs; the deepest overlap of two balls in the method's "
        "own output (its contacts, or naive's steps, which push overlaps apart) and drawn "
        "between them (positions_at on a 20000-point grid, what a film shows), and the "
        "furthest excursion past a cushion line. `exact` is the same computation as `event` "
        "split into steps, so it matches bit for bit at every step.",
        "",
    ]
    for name, speed in (("seed break, 3 m/s", 3.0), ("break at 10 m/s", 10.0)):
        setup = break_setup(speed)
        results = runs(setup, quick, budget)
        reference = results[0].result
        rows = []
        points = plot_points.setdefault(name, {})
        for run in results:
            over_run, at_rest = position_error(run.result, reference)
            differs = first_difference(run.result, reference)
            overlap, drawn, escape = soundness(run.result)
            rows.append(
                [
                    run.method,
                    step_label(run.dt),
                    str(run.result.steps),
                    str(len(run.result.events)),
                    f"{run.seconds * 1e3:.1f}",
                    sci(over_run),
                    sci(at_rest),
                    "never" if math.isinf(differs) else f"{differs:.4f}",
                    "none" if overlap <= 1e-9 else sci(overlap),
                    "none" if drawn <= 1e-9 else sci(drawn),
                    "none" if escape <= 1e-9 else sci(escape),
                ]
            )
            points.setdefault(run.method, []).append((run.seconds, max(over_run, FLOOR)))
        lines += [f"### {name}", ""]
        lines += table(
            [
                "method",
                "step (s)",
                "steps",
                "contacts",
                "wall (ms)",
                "max error over run (m)",
                "error at rest (m)",
                "contacts differ from (s)",
                "overlap at own contacts/steps (m)",
                "overlap drawn between them (m)",
                "past cushion (m)",
            ],
            rows,
        )
        lines += [""]
        print(f"{name}: done ({time.perf_counter() - started:.0f} s)", file=sys.stderr)

    return lines


def chaos_section(started: float) -> tuple[list[str], dict[str, tuple[FloatArray, FloatArray]]]:
    """How a nudge of the cue ball's start grows in the break; the growth curves."""
    lines: list[str] = []
    lines += [
        "## Why a slightly wrong method gives a different break",
        "",
        "The `event` run again with the cue ball's start moved by a nudge along y; the "
        "largest final distance of any ball from the un-nudged run, and when the "
        "contacts first differ.",
        "",
    ]
    growth: dict[str, tuple[FloatArray, FloatArray]] = {}
    rows = []
    for name, speed in (("3 m/s", 3.0), ("10 m/s", 10.0)):
        reference = simulate(break_setup(speed), "event", None)
        for nudge in NUDGES:
            nudged = simulate(break_setup(speed, nudge), "event", None)
            _, at_rest = position_error(nudged, reference)
            differs = first_difference(nudged, reference)
            rows.append(
                [
                    name,
                    sci(nudge),
                    sci(at_rest),
                    sci(at_rest / nudge),
                    "never" if math.isinf(differs) else f"{differs:.4f}",
                ]
            )
            if nudge in (1e-15, 1e-12, 1e-9):
                times = grid(nudged, reference, count=2000)
                difference = nudged.positions_at(times) - reference.positions_at(times)
                spread = np.hypot(difference[..., 0], difference[..., 1]).max(axis=1)
                growth[f"{name}, nudge {sci(nudge)} m"] = (times, np.maximum(spread, FLOOR))
    lines += table(
        ["break", "nudge (m)", "final difference (m)", "growth", "contacts differ from (s)"],
        rows,
    )
    lines += [""]
    print(f"chaos: done ({time.perf_counter() - started:.0f} s)", file=sys.stderr)

    return lines, growth


def scaling_section(quick: bool, budget: float, started: float) -> list[str]:
    """How the event method's cost grows with the balls on the table and moving."""
    lines: list[str] = []
    counts = (2, 10, 50, 200) if quick else (2, 5, 10, 20, 50, 100, 200)
    one_moving = [scaling_row(n, 1, budget) for n in counts]
    all_moving = [scaling_row(n, n, budget) for n in counts]
    moving_of_200 = [scaling_row(200, k, budget) for k in (1, 5, 20, 50, 200)]
    print(f"scaling: done ({time.perf_counter() - started:.0f} s)", file=sys.stderr)
    lines += [
        "## How cost grows with the number of balls",
        "",
        f"Event method on a {LARGE_TABLE[0]:g} x {LARGE_TABLE[1]:g} m table, balls at "
        "random spots, the moving ones at 1 to 3 m/s, run to rest. *pairs refreshed*: "
        "pair entries the calendar recomputed (each contact re-anchors its balls and "
        "refreshes only their rows); *quartics*: those whose quartic the cheap certificate "
        "could not rule out, so that its critical points were solved.",
        "",
    ]
    for title, rows_of in (
        ("One ball moving among N", one_moving),
        ("All N balls moving", all_moving),
        ("200 balls, k of them moving", moving_of_200),
    ):
        lines += [f"### {title}", ""]
        lines += table(
            [
                "balls",
                "moving",
                "contacts",
                "wall (ms)",
                "per contact (us)",
                "pairs refreshed",
                "quartics",
            ],
            [
                [
                    str(row.balls),
                    str(row.moving),
                    str(row.events),
                    f"{row.seconds * 1e3:.1f}",
                    f"{row.seconds / max(row.events, 1) * 1e6:.0f}",
                    str(row.pairs),
                    str(row.quartic),
                ]
                for row in rows_of
            ],
        )
        lines += [""]
    lines += [
        "How resting balls and far pairs stay cheap: the calendar caches every ball's next "
        "cushion time and every pair's next contact time, and a contact recomputes only "
        "the rows of the balls it re-anchors (N - 1 pairs per ball, as one vectorized "
        "numpy call); every other entry keeps its cached time. A pair whose balls both "
        "rest has no piece to solve and is skipped; a pair with one ball at rest gets a "
        "quadratic (the mover's distance to touch), never the quartic; a pair of rolling "
        "balls has its quartic f(t) = |d(t)|^2 - (2r)^2 tested by a certificate first "
        "(f >= b0 + x min q over the piece, a dozen array operations for all rows at "
        "once) and only pairs it cannot rule out have their critical points solved. "
        "What does grow with N is the vectorized row refresh and the search for the "
        "earliest entry of the N x N table, so the time per contact grows slowly with "
        "N while the number of contacts follows the number of balls moving.",
        "",
    ]
    return lines


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer steps and repeats")
    parser.add_argument(
        "--out",
        default="accuracy-report",
        help="directory for accuracy.md/.png (default: %(default)s; --out docs/explanation "
        "refreshes the tracked copies the site shows)",
    )
    parser.add_argument(
        "--real",
        default="docs/fit_cv_shots.csv",
        help="cv_shots.csv of scripts/validation_tracks.py: the error against a real table "
        "(default: %(default)s; skipped if absent)",
    )
    parser.add_argument(
        "--real-only",
        action="store_true",
        help="only refresh the real-table section of --out's accuracy.md from --real "
        "(a new cross-validation), keeping its measured sections",
    )
    args = parser.parse_args(argv)
    if args.real_only:
        refresh_real_table(Path(args.out) / "accuracy.md", Path(args.real))
        return
    budget = 0.3 if args.quick else 1.0  # s of repeats per timed run
    started = time.perf_counter()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = [
        "# Speed against error",
        "",
        "Generated by `python scripts/accuracy_report.py"
        + (" --quick" if args.quick else "")
        + "`; do not edit by hand.",
        "",
        f"Machine: {machine()}. Wall time is the median of warm repeats (one run where a "
        "run takes longer than a second); the machine is shared, so compare rows of one "
        "report, not across reports.",
        "",
        "![error against wall time](accuracy.png)",
        "",
    ]
    plot_points: dict[str, dict[str, list[tuple[float, float]]]] = {}

    lines += closed_form_section(args.quick, budget, started, plot_points)
    lines += break_section(args.quick, budget, started, plot_points)
    chaos_lines, growth = chaos_section(started)
    lines += chaos_lines
    lines += scaling_section(args.quick, budget, started)
    lines += [
        *real_table(Path(args.real)),
        f"Report runtime: {time.perf_counter() - started:.0f} s.",
        "",
    ]
    text = "\n".join(lines)
    (out / "accuracy.md").write_text(text, encoding="utf-8")
    draw(out / "accuracy.png", plot_points, growth)
    print(text)


def draw(
    path: Path,
    points: dict[str, dict[str, list[tuple[float, float]]]],
    growth: dict[str, tuple[FloatArray, FloatArray]],
) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels: list[tuple[str, Callable[[plt.Axes], None]]] = []
    styles = {"event": ("k", "*"), "exact": ("tab:blue", "o"), "naive": ("tab:red", "s")}
    for case in ("bank off two cushions", "seed break, 3 m/s", "break at 10 m/s"):

        def panel(axes: plt.Axes, case: str = case) -> None:
            for method, series in points[case].items():
                colour, marker = styles[method]
                seconds, error = zip(*sorted(series), strict=True)
                axes.loglog(
                    np.array(seconds) * 1e3, error, marker=marker, color=colour, label=method
                )
            axes.axhline(FLOOR, color="0.6", lw=0.8, ls=":")
            axes.set_xlabel("wall time per run (ms)")
            axes.set_ylabel(
                "rest position error (m)" if "bank" in case else "max position error (m)"
            )
            against = "closed form" if "bank" in case else "event reference"
            axes.set_title(f"{case}: error vs {against}", fontsize=9)
            axes.legend(fontsize=8, title=f"{FLOOR:g} = exactly 0", title_fontsize=7)

        panels.append((case, panel))

    def chaos(axes: plt.Axes) -> None:
        colours = {"1.0e-15": "tab:green", "1.0e-12": "tab:orange", "1.0e-09": "tab:purple"}
        for label, (times, spread) in growth.items():
            colour = next(c for key, c in colours.items() if key in label)
            style = "--" if label.startswith("3 m/s") else "-"
            axes.semilogy(times, spread, style, color=colour, label=label)
        axes.set_xlabel("time (s)")
        axes.set_ylabel("largest ball distance from un-nudged run (m)")
        axes.set_title("a nudge of the cue ball's start y grows (event method)", fontsize=9)
        axes.legend(fontsize=8)

    panels.append(("chaos", chaos))
    figure, grid_axes = plt.subplots(2, 2, figsize=(11, 8.5))
    for axes, (_, draw_panel) in zip(grid_axes.flat, panels, strict=True):
        draw_panel(axes)
        axes.grid(True, which="major", alpha=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


if __name__ == "__main__":
    main()
