"""The model against recorded three-cushion shots: 5-fold cross-validation (issue 31).

    python scripts/validation_tracks.py [TRACKS] [--models han2005] [--folds 5] \
        [--workers 2] [--out DIR] [--quiet]

TRACKS: the recordings (train.json, or its folder); without it, the file that
BILLIARDS_RECORDINGS names, else ../shared/data/carom_tracks/train.json beside the
repository (billiards.fit.recordings.recordings_path); none there is one line, exit 2.

For each model (a cushion law on the three_cushion scene) and each fold: calibrate the
table's constants on the other folds' shots (billiards.fit.calibrate), then fit only the
strokes of the fold's shots on that table (billiards.fit.score) and keep their errors.
Prints, per model, the median over all shots (each scored by the fold that never saw
it) of the whole-shot and first-4-s RMSE, the share of shots whose outcome agrees with
the recording's (billiards.fit.outcomes: the first object ball, the balls set moving, the
point; each shot that differs listed), each fold's own median and their spread over
the folds (min, max, interquartile range: billiards.fit.cross_validation.fold_spread),
the CPU time of one shot's stroke fit and of each fold's calibration, and the machine's
load; --out writes every shot's row
(cv_shots.csv: scripts/accuracy_report.py --real reads it) and every fold's constants
and CPU (cv_folds.csv). docs/validation.md, Recorded shots, shows a run.
"""

from __future__ import annotations

import argparse
import csv
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any, cast

import numpy as np
from tqdm import tqdm

from billiards.fit import Budget, read_recordings
from billiards.fit.cross_validation import (
    FoldJob,
    FoldOutcome,
    fold_jobs,
    fold_spread,
    run_fold,
)
from billiards.fit.output import shots_csv, table_toml, write_pictures, write_text
from billiards.fit.recordings import RecordingError, recordings_path
from billiards.fit.shots import WINDOWS, Window

# Issue 44's targets: the whole shot's median, the first 4 s weighted with 4-s strokes
# (window 4s), the outcome agreement (the first object ball and the balls set moving).
TARGETS = {"whole": 11.5, "whole_aim": 8.0, "early": 4.5, "early_aim": 3.5, "outcome": 90}


def write_histogram(rows: list[dict[str, Any]], path: Path) -> None:
    """The held-out shots' RMSE (whole shot and first 4 s; with window 4s, its weighted
    first 4 s), per model, as a histogram."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axis = plt.subplots(figsize=(7, 3.6))
    top = max(max(float(r["rmse_cm"]) for r in rows), 1.0)
    bins = [float(edge) for edge in np.linspace(0, top, 31)]
    for model in sorted({r["model"] for r in rows}):
        mine = [r for r in rows if r["model"] == model and r["window"] == "shot"]
        whole = [float(r["rmse_cm"]) for r in mine]
        early = [float(r["rmse_4s_cm"]) for r in mine]
        weighted = [
            float(r["rmse_4s_weighted_cm"])
            for r in rows
            if r["model"] == model and r["window"] == "4s"
        ]
        if weighted:
            axis.hist(
                weighted,
                bins=bins,
                alpha=0.6,
                label=f"{model}, first 4 s weighted, strokes fitted to it "
                f"(median {np.median(weighted):.1f} cm)",
            )
        if not mine:
            continue
        axis.hist(
            whole,
            bins=bins,
            alpha=0.6,
            label=f"{model}, whole shot (median {np.median(whole):.1f} cm)",
        )
        axis.hist(
            early,
            bins=bins,
            alpha=0.6,
            label=f"{model}, first 4 s (median {np.median(early):.1f} cm)",
        )
    axis.set_xlabel("held-out position RMSE per shot, cm (all balls, every recorded sample)")
    axis.set_ylabel("shots")
    axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "tracks",
        nargs="?",
        help="train.json or its folder (default: $BILLIARDS_RECORDINGS, else "
        "../shared/data/carom_tracks beside the repository)",
    )
    parser.add_argument("--scene", default="three_cushion")
    parser.add_argument("--models", default="han2005", help="cushion laws, comma-separated")
    parser.add_argument("--folds", type=int, default=5)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--generations", type=int, default=Budget.generations)
    parser.add_argument("--evaluations", type=int, default=Budget.evaluations)
    parser.add_argument("--trial-shots", type=int, default=Budget.trial_shots)
    parser.add_argument("--passes", type=int, default=Budget.passes)
    parser.add_argument(
        "--calibrate-all",
        action="store_true",
        help="also calibrate each model on every shot, into --out/MODEL (as billiards-fit)",
    )
    parser.add_argument("--limit", type=int, help="only the first N shots (a quick look)")
    parser.add_argument("--every", type=int, default=1, help="only every N-th shot (a quick look)")
    parser.add_argument(
        "--fixed",
        action="store_true",
        help="no calibration: fit only the strokes, with the scene's (or the law's) constants",
    )
    parser.add_argument(
        "--windows",
        default="shot",
        help="what the held-out strokes are fitted to, comma-separated: shot (the whole "
        "shot) and/or 4s (the first 4 s, weighted as tailuge/billiards weighs them)",
    )
    parser.add_argument("--out", help="folder for cv_shots.csv")
    parser.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    windows = args.windows.split(",")
    if not set(windows) <= set(WINDOWS):
        parser.error(f"--windows: {args.windows!r}; expected some of {', '.join(WINDOWS)}")
    try:
        recordings = read_recordings(recordings_path(args.tracks))[: args.limit : args.every]
    except RecordingError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    budget = Budget(
        generations=args.generations,
        evaluations=args.evaluations,
        trial_shots=args.trial_shots,
        passes=args.passes,
    )
    base = FoldJob(
        model="",
        fold=0,
        scene=args.scene,
        budget=budget,
        fixed=args.fixed,
        windows=cast(tuple[Window, ...], tuple(windows)),  # checked above
        train=[],
        test=[],
    )
    models = args.models.split(",")
    jobs = fold_jobs(recordings, args.folds, models, base)
    if args.out and args.calibrate_all and not args.fixed:  # each model on every shot
        jobs += [
            FoldJob(
                **{**vars(jobs[0]), "model": model, "fold": -1, "train": recordings, "test": []}
            )
            for model in models
        ]
    load_before = os.getloadavg()
    wall = time.perf_counter()
    with (
        ProcessPoolExecutor(max_workers=args.workers) as pool,
        tqdm(total=len(jobs), unit="fold", disable=args.quiet, file=sys.stderr) as progress,
    ):
        running = [pool.submit(run_fold, job) for job in jobs]
        for done in as_completed(running):
            done.result()
            progress.update()
        outcomes = [done.result() for done in running]
    wall = time.perf_counter() - wall
    load_after = os.getloadavg()
    cv_jobs = [job for job in jobs if job.fold >= 0]
    words = sys.argv[1:] if argv is None else argv
    print(f"$ python scripts/validation_tracks.py {' '.join(words)}")
    print(
        f"{len(recordings)} shots, {args.folds} folds ("
        f"{'no calibration: --fixed' if args.fixed else f'{len(cv_jobs)} calibrations'}"
        f"{', and one on every shot a model' if len(jobs) > len(cv_jobs) else ''}), {args.workers} workers, "
        f"{os.cpu_count()} cores; load average {load_before[0]:.1f} before, "
        f"{load_after[0]:.1f} after; wall {wall / 60:.1f} min"
    )
    print_report(models, windows, jobs, outcomes)
    if args.out:
        write_folder(Path(args.out), args.scene, jobs, outcomes)
    return 0


def print_report(
    models: list[str], windows: list[str], jobs: list[FoldJob], outcomes: list[FoldOutcome]
) -> None:
    """Per law and window the held-out medians and CPU; the folds' constants; the worst shots."""
    rows = [row for outcome in outcomes for row in outcome.rows]
    print()
    print(
        f"{'model':<14} {'window':>6} {'median RMSE':>12} {'median 4 s':>11} "
        f"{'weighted 4 s':>13} {'worst':>8} {'first ball':>11} {'same moved':>11} "
        f"{'point':>6} {'stroke fit':>11} {'calibration':>12} {'5-fold CPU':>11}"
    )
    print(
        f"{'':<14} {'':>6} {'cm':>12} {'cm':>11} {'cm':>13} {'cm':>8} {'agrees':>11} "
        f"{'agrees':>11} {'agrees':>6} {'CPU s/shot':>11} {'CPU s/fold':>12} {'min':>11}"
    )
    for model in models:
        calibration = [
            outcome.calibration_cpu_s
            for outcome, job in zip(outcomes, jobs, strict=True)
            if job.model == model and job.fold >= 0
        ]
        for window in windows:
            mine = [row for row in rows if row["model"] == model and row["window"] == window]
            total = (sum(calibration) + sum(row["stroke_cpu_s"] for row in mine)) / 60
            print(
                f"{model:<14} {window:>6} {np.median([r['rmse_cm'] for r in mine]):12.2f} "
                f"{np.median([r['rmse_4s_cm'] for r in mine]):11.2f} "
                f"{np.median([r['rmse_4s_weighted_cm'] for r in mine]):13.2f} "
                f"{max(r['rmse_cm'] for r in mine):8.1f} "
                f"{_share(mine, 'first_agrees'):>11} {_share(mine, 'moved_agrees'):>11} "
                f"{_share(mine, 'point_agrees'):>6} "
                f"{np.mean([r['stroke_cpu_s'] for r in mine]):11.2f} "
                f"{np.mean(calibration):12.0f} {total:11.1f}"
            )
    print_fold_spread(models, windows, rows)
    print()
    print(
        f"targets: median whole shot < {TARGETS['whole']} cm (aim {TARGETS['whole_aim']}), "
        f"first 4 s weighted, its strokes fitted to it (window 4s) < {TARGETS['early']} cm "
        f"(aim {TARGETS['early_aim']}); the first object ball and the balls set moving "
        f"agreeing in at least {TARGETS['outcome']}% of the shots; a stroke fit <= 0.05 s "
        "CPU; the 5 folds <= 5 min on 2 cores"
    )
    print()
    print("fitted constants by fold:")
    for outcome, job in zip(outcomes, jobs, strict=True):
        if job.fold < 0:
            continue
        constants = ", ".join(f"{k} {v:.4g}" for k, v in outcome.constants.items())
        print(f"  {job.model} fold {job.fold}: {constants}")
    print_outcomes(rows, windows[0])
    worst = sorted(
        (row for row in rows if row["window"] == windows[0]), key=lambda row: -row["rmse_cm"]
    )[:8]
    print()
    print(
        "worst held-out shots: "
        + ", ".join(
            f"{row['id']} ({row['model']}, {row['rmse_cm']:.1f} cm, 4 s {row['rmse_4s_cm']:.1f})"
            for row in worst
        )
    )


FIGURES = {
    "rmse_cm": "whole shot",
    "rmse_4s_cm": "first 4 s",
    "rmse_4s_weighted_cm": "first 4 s weighted",
}


def print_fold_spread(models: list[str], windows: list[str], rows: list[dict[str, Any]]) -> None:
    """Per law and window, each fold's own held-out median of each figure, and their
    spread over the folds (min, max, interquartile range): how much the median over
    every shot owes to the split."""
    print()
    print("per fold: each fold's median over its held-out shots, cm (fold 0, 1, ...):")
    for model in models:
        for window in windows:
            for column, name in FIGURES.items():
                spread = fold_spread(rows, model, window, column)
                if spread.medians:
                    print(f"  {model} {window}, {name}: {spread.line()}")


def _share(rows: list[dict[str, Any]], column: str) -> str:
    """The share of rows with a 1 in the column (of those with a value), as a percentage."""
    values = [int(row[column]) for row in rows if row[column] != ""]
    return f"{100 * sum(values) / len(values):.0f}%" if values else "-"


def print_outcomes(rows: list[dict[str, Any]], window: str) -> None:
    """Each held-out shot whose outcome differs from the recording's: both outcomes."""
    print()
    print(
        "outcome (billiards.fit.outcomes): the share of held-out shots whose fitted stroke "
        "strikes the recording's first object ball, sets the same object balls moving, and "
        "scores the point or not as the recording does; the shots that differ:"
    )
    for row in rows:
        if row["window"] == window and not row["outcome_agrees"]:
            print(
                f"  {row['id']} ({row['model']}, {row['rmse_cm']:.1f} cm): recorded "
                f"{row['outcome_recorded']}; simulated {row['outcome_simulated']}"
            )


def write_folder(
    folder: Path, scene: str, jobs: list[FoldJob], outcomes: list[FoldOutcome]
) -> None:
    """cv_shots.csv, cv_folds.csv, cv_errors.png; each law's calibration on every shot."""
    rows = [row for outcome in outcomes for row in outcome.rows]
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / "cv_shots.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    with open(folder / "cv_folds.csv", "w", newline="") as handle:
        fold_rows = [
            {
                "model": job.model,
                "fold": job.fold,
                "calibration_cpu_s": f"{outcome.calibration_cpu_s:.1f}",
                "stroke_fits_cpu_s": f"{sum(r['stroke_cpu_s'] for r in outcome.rows):.1f}",
                **{name: f"{value:.6g}" for name, value in outcome.constants.items()},
            }
            for outcome, job in zip(outcomes, jobs, strict=True)
        ]
        names = list(dict.fromkeys(key for row in fold_rows for key in row))
        writer = csv.DictWriter(handle, fieldnames=names)
        writer.writeheader()
        writer.writerows(fold_rows)
    write_histogram(rows, folder / "cv_errors.png")
    for outcome, job in zip(outcomes, jobs, strict=True):
        if job.fold < 0 and outcome.fit is not None:  # as billiards-fit writes it
            model_folder = folder / job.model
            model_folder.mkdir(exist_ok=True)
            write_text(model_folder / "table.toml", table_toml(outcome.fit.table, scene))
            write_text(model_folder / "shots.csv", shots_csv(outcome.fit.shots))
            write_pictures(outcome.fit, model_folder)


if __name__ == "__main__":
    sys.exit(main())
