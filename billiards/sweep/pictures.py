"""A sweep's pictures (matplotlib, no display): where each ball came to rest over the
runs, and the chaos curve of a nudge sweep."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from billiards.ball_colors import ball_color
from billiards.physics.motion import FloatArray

CLOTH = "#24844f"
CUSHION = "#14603c"
METHOD_STYLES = {"exact": ("#1f4e9c", "o"), "event": ("#d2691e", "s"), "naive": ("#7a1f7a", "^")}


def _rgb(ball_id: str) -> tuple[float, float, float]:
    red, green, blue = ball_color(ball_id).rgb
    return (red / 255, green / 255, blue / 255)


def draw_cloud(
    path: Path,
    cloud: FloatArray,
    ball_ids: Sequence[str],
    table_size: tuple[float, float],
    title: str,
) -> None:
    """Every ball's resting places (runs x balls x 2, nan for failed runs) on the table,
    one colour per ball (a ring for a stripe)."""
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    length, width = table_size
    figure = Figure(figsize=(10, 10 * width / length + 0.9), dpi=120)
    axes = figure.subplots()
    border = 0.06
    axes.add_patch(
        Rectangle((-border, -border), length + 2 * border, width + 2 * border, color=CUSHION)
    )
    axes.add_patch(Rectangle((0, 0), length, width, color=CLOTH))
    size = float(np.clip(4000 / max(len(cloud), 1), 3, 16))  # points shrink as runs grow
    for index, ball_id in enumerate(ball_ids):
        points = cloud[:, index]
        points = points[~np.isnan(points).any(axis=1)]
        if len(points) == 0:
            continue
        colour = _rgb(ball_id)
        face: str | tuple[float, float, float] = colour
        edge: str | tuple[float, float, float] = "none"
        line = 0.0
        if ball_id == "cue":
            edge, line = "black", 0.5
        elif ball_color(ball_id).striped:  # a ring: the stripe's colour around white
            face, edge, line = "white", colour, 1.2
        axes.scatter(points[:, 0], points[:, 1], s=size, color=face, edgecolors=edge,
                     linewidths=line, alpha=0.75, label=ball_id)  # fmt: skip
    axes.set_xlim(-border, length + border)
    axes.set_ylim(-border, width + border)
    axes.set_aspect("equal")
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_title(title, fontsize=10)
    if axes.get_legend_handles_labels()[0]:
        axes.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8,
                    markerscale=8 / np.sqrt(size), frameon=False)  # fmt: skip
    figure.tight_layout()
    figure.savefig(path, format="png")


def draw_chaos(
    path: Path, curves: Mapping[str, Sequence[tuple[float, float]]], radius: float, title: str
) -> None:
    """Divergence at rest against nudge size, log-log, one line per method."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.5, 5), dpi=120)
    axes = figure.subplots()
    for method, curve in curves.items():
        # A divergence of 0 (no ball moved by one ulp) has no place on a log axis.
        points = [(d, v) for d, v in curve if v > 0 and np.isfinite(v)]
        if not points:
            continue
        colour, marker = METHOD_STYLES.get(method, ("black", "o"))
        nudges, divergences = zip(*points, strict=True)
        # exact and event often agree to the last bit: a dashed line keeps both visible.
        dashed = "--" if method == "event" else "-"
        axes.plot(nudges, divergences, dashed, marker=marker, color=colour, label=method,
                  markersize=4, markerfacecolor="none" if method == "event" else colour)  # fmt: skip
    axes.axhline(radius, color="grey", linestyle="--", linewidth=0.8)
    axes.annotate("one ball radius", (0.01, radius), xycoords=("axes fraction", "data"),
                  va="bottom", fontsize=8, color="grey")  # fmt: skip
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("nudge of the cue ball (m)")
    axes.set_ylabel("largest divergence at rest (m)")
    axes.set_title(title, fontsize=10)
    axes.grid(True, which="major", alpha=0.3)
    if axes.get_legend_handles_labels()[0]:
        axes.legend()
    figure.tight_layout()
    figure.savefig(path, format="png")
