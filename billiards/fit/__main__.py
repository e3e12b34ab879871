"""`python -m billiards.fit {calibrate,score} [TRACKS] --scene SCENE -o DIR`

calibrate: fit the table's constants and every shot's stroke to recorded shots; writes
DIR/table.toml (the scene with the fitted [physics]), DIR/shots.csv and the pictures.
score: keep the scene's constants, fit only the strokes; writes DIR/shots.csv and the
pictures. TRACKS is the recordings file (or its folder, holding train.json); without
it, the file BILLIARDS_RECORDINGS names, else ../shared/data/carom_tracks/train.json
beside the repository (billiards.fit.recordings.recordings_path). docs/validation.md
says what the errors include.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from billiards.fit.recordings import (
    FORMATS,
    RECORDINGS_ENV,
    RecordingError,
    check_on_table,
    read_recordings,
    recordings_path,
)
from billiards.fit.shots import WINDOWS, Budget
from billiards.fit.table import (
    Fit,
    FitError,
    calibrate,
    calibration_steps,
    fitted_constants,
    score,
)
from billiards.physics.compiled import notice
from billiards.scene.reader import SceneError, load_scene
from billiards.shell import cli


def build_parser() -> argparse.ArgumentParser:
    parser = cli.OneLineParser(
        prog="python -m billiards.fit",
        description="Fit the model to recorded shots: the table's constants and each stroke.",
    )
    count = cli.whole_number(1, "a whole number >= 1")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, what in (
        ("calibrate", "fit the table's constants and every stroke; writes table.toml too"),
        ("score", "keep the scene's constants; fit every stroke"),
    ):
        command = commands.add_parser(name, help=what, description=what)
        command.error = parser.error  # type: ignore[method-assign]
        command.add_argument(
            "tracks",
            metavar="TRACKS",
            nargs="?",
            help=f"recordings: .json or .csv, or a folder holding train.json (default: "
            f"${RECORDINGS_ENV}, else ../shared/data/carom_tracks beside the repository)",
        )
        command.add_argument(
            "--scene", default="three_cushion", help="the table scene (default: three_cushion)"
        )
        command.add_argument("-o", "--output", required=True, metavar="DIR", help="output folder")
        command.add_argument("--format", choices=FORMATS, default="auto", help="recordings format")
        command.add_argument("--shots", help="only these shot ids, comma-separated")
        command.add_argument(
            "--generations",
            type=count,
            default=Budget.generations,
            help=f"stroke search generations (default {Budget.generations})",
        )
        if name == "calibrate":  # score keeps the scene's constants: nothing to try
            command.add_argument(
                "--evaluations",
                type=count,
                default=Budget.evaluations,
                help=f"trials of the table's constants (default {Budget.evaluations})",
            )
        command.add_argument(
            "--window",
            choices=WINDOWS,
            default=Budget.window,
            help="what each stroke fit matches: the whole shot (default), or the first 4 s "
            "weighted as tailuge/billiards weighs them",
        )
        command.add_argument("--no-pictures", action="store_true", help="write no pictures")
        cli.add_quiet_argument(command, "no progress on stderr")
        command.add_argument("--force", action="store_true", help="replace existing outputs")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # Deferred: a fit spends its time in SciPy, whose compiled parts cannot pass a
    # signal's exception on; it checks for one after every shot and before it writes.
    return cli.run_guarded(lambda: _run(argv), deferred=True)


def _run(argv: Sequence[str] | None) -> int:
    args = build_parser().parse_args(cli.command_words(argv))
    notice.announce = not args.quiet
    folder = Path(args.output)
    names = ["shots.csv"]
    if args.command == "calibrate":
        names.insert(0, "table.toml")
    if not args.no_pictures:
        names += ["paths.png", "errors.png"]
    with cli.failing_on(SceneError, RecordingError, FitError, one_line=True):
        scene = load_scene(args.scene)
        fitted_constants(scene)
        tracks = str(recordings_path(args.tracks))
        recordings = read_recordings(tracks, args.format, balls=len(scene.balls) or 3)
        check_on_table(recordings, (scene.table.length, scene.table.width), scene.radius, tracks)
        if args.shots:
            wanted = [part.strip() for part in args.shots.split(",")]
            known = {recording.id for recording in recordings}
            unknown = [shot for shot in wanted if shot not in known]
            if unknown:
                raise RecordingError(f"--shots: no shot {unknown[0]} in {tracks}")
            recordings = [recording for recording in recordings if recording.id in wanted]
        problem = cli.files_problem(folder, names, force=args.force)
        if problem:
            raise FitError(problem)
    evaluations = getattr(args, "evaluations", Budget.evaluations)  # calibrate's alone
    budget = Budget(generations=args.generations, evaluations=evaluations, window=args.window)

    from tqdm import tqdm

    from billiards.fit.output import shots_csv, table_toml, write_pictures, write_text

    total = (
        calibration_steps(len(recordings), budget)
        if args.command == "calibrate"
        else len(recordings)
    )
    with tqdm(total=total, unit="fit", disable=args.quiet, file=sys.stderr) as progress:

        def step(done: int = 1) -> None:
            cli.raise_if_stopped()
            progress.update(done)

        if args.command == "calibrate":
            fit = calibrate(recordings, scene, budget, step)
        else:
            fit = score(recordings, scene, budget, step)
    cli.raise_if_stopped()
    with cli.failing_on(OSError, status=cli.EXIT_FAILED, one_line=True):
        folder.mkdir(exist_ok=True)  # only now: an interrupted fit leaves nothing behind
        if args.command == "calibrate":
            write_text(folder / "table.toml", table_toml(fit.table, args.scene))
        write_text(folder / "shots.csv", shots_csv(fit.shots))
        if not args.no_pictures:
            write_pictures(fit, folder)
    if not args.quiet:
        _say_summary(fit, names, folder)
    return 0


def _say_summary(fit: Fit, names: list[str], folder: Path) -> None:
    """The shots' median RMSE and outcome agreement, and the shots whose outcome differs."""
    whole, early, weighted = fit.median_rmse()
    cli.say(
        f"{len(fit.shots)} shots: median RMSE {whole * 100:.2f} cm whole shot, "
        f"{early * 100:.2f} cm first 4 s ({weighted * 100:.2f} cm weighted); "
        f"outcome as recorded: {fit.outcome_agreement().line()}; "
        f"wrote {', '.join(names)} in {folder}"
    )
    differing = [
        f"{shot.shot.id} ({shot.agreement.differs()})"
        for shot in fit.shots
        if shot.agreement is not None and not shot.agreement.sequence
    ]
    if differing:
        cli.say(
            f"the fitted stroke's outcome differs from the recording's in {len(differing)} "
            f"shots: {', '.join(differing)} (shots.csv: the *_recorded and *_simulated columns)"
        )


if __name__ == "__main__":
    sys.exit(main())
