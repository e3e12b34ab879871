"""What a fit writes: the calibrated scene file, the shots' table and the pictures.

Every file is written whole or not at all (billiards.shell.atomic).
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from billiards.fit.outcomes import describe_moved
from billiards.fit.shots import simulated_positions
from billiards.fit.table import Fit, ShotFit, physics_toml
from billiards.scene.reader import Scene, parse_scene, read_scene_tables
from billiards.shell.atomic import atomic_output

SHOTS_HEADER = (
    "id",
    "cue_ball",
    "rmse_cm",
    "rmse_4s_cm",
    "rmse_4s_weighted_cm",
    "speed",
    "direction",
    "tip_side",
    "tip_height",
    "samples",
    # The outcome (billiards.fit.outcomes), recorded and simulated: the object ball the
    # cue ball strikes first and when (s after the stroke), when it reaches the other,
    # the object balls set moving, the cue ball's cushions before the second object
    # ball and the point; then whether the whole sequence agrees.
    "first_ball_recorded",
    "first_ball_simulated",
    "first_time_recorded",
    "first_time_simulated",
    "second_time_recorded",
    "second_time_simulated",
    "moved_recorded",
    "moved_simulated",
    "cushions_recorded",
    "cushions_simulated",
    "point_recorded",
    "point_simulated",
    "outcome_agrees",
)


def shots_csv(fits: Sequence[ShotFit]) -> str:
    """One row a shot: its errors (cm) and its fitted stroke (m/s, degrees, tip / R)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(SHOTS_HEADER)
    for fit in fits:
        stroke = fit.stroke
        writer.writerow(
            [
                fit.shot.id,
                fit.shot.order[0],
                f"{fit.errors.rmse * 100:.3f}",
                f"{fit.errors.rmse_early * 100:.3f}",
                f"{fit.errors.rmse_early_weighted * 100:.3f}",
                f"{stroke.speed:.4f}",
                f"{stroke.direction:.3f}",
                f"{stroke.side:.3f}",
                f"{stroke.height:.3f}",
                fit.errors.count,
                *_outcome_cells(fit),
            ]
        )
    return out.getvalue()


def _outcome_cells(fit: ShotFit) -> list[str]:
    """The outcome's columns of SHOTS_HEADER: empty where a fit has no outcome or a part
    did not happen (no ball struck, the second never reached, cushions not read)."""
    recorded, simulated, agreement = fit.recorded, fit.simulated, fit.agreement
    if recorded is None or simulated is None or agreement is None:
        return [""] * 13

    def time(value: float | None) -> str:
        return "" if value is None else f"{value:.3f}"

    def point(value: bool | None) -> str:
        return "" if value is None else str(int(value))

    return [
        recorded.first or "",
        simulated.first or "",
        time(recorded.first_time),
        time(simulated.first_time),
        time(recorded.second_time),
        time(simulated.second_time),
        describe_moved(recorded.moved),
        describe_moved(simulated.moved),
        "" if recorded.cushions is None else str(recorded.cushions),
        "" if simulated.cushions is None else str(simulated.cushions),
        point(recorded.point),
        point(simulated.point),
        str(int(agreement.sequence)),
    ]


def table_toml(scene: Scene, scene_path: str | Path) -> str:
    """The scene file's text with its [physics] table replaced by `scene.physics` (every
    constant written out); its comments and other tables kept. Checked by reading it
    back: the result gives exactly `scene.physics`."""
    _, source = read_scene_tables(scene_path)
    from billiards.scene.reader import find_scene

    text = find_scene(scene_path).read_text(encoding="utf-8")
    physics = physics_toml(scene.physics)
    header = re.compile(r"^\s*\[physics\]\s*(#.*)?$", re.MULTILINE)
    match = header.search(text)
    if match is None:
        text = text.rstrip("\n") + "\n\n" + physics
    else:
        following = re.compile(r"^\s*\[", re.MULTILINE).search(text, match.end())
        end = following.start() if following else len(text)
        text = text[: match.start()] + physics + "\n" + text[end:]
    again = parse_scene(text, source)
    if again.physics != scene.physics:
        raise ValueError(f"{source}: its [physics] could not be rewritten (dotted keys?)")
    return text


def write_text(path: Path, text: str) -> None:
    with atomic_output(path, path.suffix) as temporary:
        temporary.write_text(text, encoding="utf-8")


def write_pictures(fit: Fit, folder: Path) -> list[Path]:
    """paths.png: recorded against simulated paths of the best, the median and the worst
    shot, on the table; errors.png: the histogram of the shots' RMSE."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ranked = sorted(fit.shots, key=lambda shot_fit: shot_fit.errors.rmse)
    chosen = [ranked[0], ranked[len(ranked) // 2], ranked[-1]] if ranked else []
    labels = ["best", "median", "worst"]
    table = fit.table.table
    figure, axes = plt.subplots(len(chosen), 1, figsize=(8, 4.3 * len(chosen)), squeeze=False)
    colours = ("#1f77b4", "#d62728", "#b8860b")
    for axis, shot_fit, label in zip(axes[:, 0], chosen, labels, strict=False):
        shot = shot_fit.shot
        times = np.linspace(0.0, shot.duration, max(int(shot.duration * 50), 2))
        simulated = simulated_positions(fit.table, shot, shot_fit.stroke, times)
        axis.add_patch(
            plt.Rectangle((0, 0), table.length, table.width, fill=True, color="#2e6b3a", alpha=0.25)
        )
        for column, ball in enumerate(shot.order):
            colour = colours[column % len(colours)]
            recorded = shot.recorded[column]
            axis.plot(recorded[:, 0], recorded[:, 1], ".", ms=2.5, color=colour)
            axis.plot(
                simulated[:, column, 0],
                simulated[:, column, 1],
                "-",
                lw=1.2,
                color=colour,
                label=f'ball "{ball}"' + (" (cue)" if column == 0 else ""),
            )
        axis.set_xlim(-0.05, table.length + 0.05)
        axis.set_ylim(-0.05, table.width + 0.05)
        axis.set_aspect("equal")
        title = (
            f"{label}: shot {shot.id}, RMSE {shot_fit.errors.rmse * 100:.1f} cm "
            f"(first 4 s {shot_fit.errors.rmse_early * 100:.1f} cm); dots recorded, lines simulated"
        )
        if shot_fit.recorded is not None and shot_fit.simulated is not None:
            title += (
                f"\nrecorded: {shot_fit.recorded.describe()}; "
                f"simulated: {shot_fit.simulated.describe()}"
            )
        axis.set_title(title, fontsize=8)
        axis.legend(fontsize=7, loc="upper right")
    figure.tight_layout()
    paths = [folder / "paths.png", folder / "errors.png"]
    with atomic_output(paths[0], ".png") as temporary:
        figure.savefig(temporary, dpi=110, format="png")
    plt.close(figure)

    figure, axis = plt.subplots(figsize=(7, 3.6))
    whole = [shot_fit.errors.rmse * 100 for shot_fit in fit.shots]
    early = [shot_fit.errors.rmse_early * 100 for shot_fit in fit.shots]
    top = max([*whole, *early, 1.0])
    bins = [float(edge) for edge in np.linspace(0, top, 26)]
    axis.hist(whole, bins=bins, alpha=0.6, label=f"whole shot (median {np.median(whole):.1f} cm)")
    axis.hist(early, bins=bins, alpha=0.6, label=f"first 4 s (median {np.median(early):.1f} cm)")
    axis.set_xlabel("position RMSE per shot, cm (all balls, every recorded sample)")
    axis.set_ylabel("shots")
    axis.legend(fontsize=8)
    figure.tight_layout()
    with atomic_output(paths[1], ".png") as temporary:
        figure.savefig(temporary, dpi=110, format="png")
    plt.close(figure)
    return paths
