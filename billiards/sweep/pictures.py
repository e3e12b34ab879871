"""A sweep's pictures (matplotlib, no display): where each ball came to rest over the
runs, and the chaos curve of a nudge sweep."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from billiards.physics.numerics.arrays import FloatArray
from billiards.stage.ball_colors import ball_color

CLOTH = "#e3e8e1"  # a pale cloth: every ball colour, green 6 and 14 too, shows on it
CUSHION = "#5f7f68"
METHOD_STYLES = {"exact": ("#1f4e9c", "o"), "event": ("#d2691e", "s"), "naive": ("#7a1f7a", "^")}


def _rgb(ball_id: str) -> tuple[float, float, float]:
    red, green, blue = ball_color(ball_id).rgb
    return (red / 255, green / 255, blue / 255)


SMALL_MULTIPLES = 24  # balls drawn one to a small table too, at most
COLUMNS = 4


def draw_cloud(
    path: Path,
    cloud: FloatArray,
    ball_ids: Sequence[str],
    table_size: tuple[float, float],
    title: str,
) -> None:
    """Every ball's resting places (runs x balls x 2, nan for failed runs): all balls on
    one table, one colour each (a ring for a stripe), then each ball on a small table of
    its own (a chaotic break spreads them all over, and one table hides who went where)."""
    from matplotlib.figure import Figure

    length, width = table_size
    singles = len(ball_ids) if len(ball_ids) <= SMALL_MULTIPLES else 0
    rows = -(-singles // COLUMNS)
    big = 12 * width / length
    figure = Figure(figsize=(12, big + 0.4 + rows * (3 * width / length + 0.4)), dpi=100)
    grid = figure.add_gridspec(1 + rows, COLUMNS, height_ratios=[big * 1.1] + [1.0] * rows)
    axes = figure.add_subplot(grid[0, :])
    size = float(np.clip(4000 / max(len(cloud), 1), 3, 16))  # points shrink as runs grow
    _table(axes, table_size)
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_title(title, fontsize=11)
    smalls = []
    for index, ball_id in enumerate(ball_ids[:singles]):
        small = figure.add_subplot(grid[1 + index // COLUMNS, index % COLUMNS])
        _table(small, table_size)
        small.set_title(f"ball {ball_id}", fontsize=9)
        small.set_xticks([])
        small.set_yticks([])
        smalls.append(small)
    # The layout draws the figure once to measure its labels: before the points, which
    # are most of the drawing (the axes' limits are set, so points do not move them).
    figure.tight_layout()
    for index, ball_id in enumerate(ball_ids):
        _scatter(axes, cloud[:, index], ball_id, size)
    for index, small in enumerate(smalls):
        _scatter(small, cloud[:, index], ball_ids[index], size / 2)
    # zlib's fastest level: a tenth of a second less for a file a tenth larger.
    figure.savefig(path, format="png", pil_kwargs={"compress_level": 1})


def _table(axes: Any, table_size: tuple[float, float]) -> None:
    from matplotlib.patches import Rectangle

    length, width = table_size
    border = 0.06
    axes.add_patch(
        Rectangle((-border, -border), length + 2 * border, width + 2 * border, color=CUSHION)
    )
    axes.add_patch(Rectangle((0, 0), length, width, color=CLOTH))
    axes.set_xlim(-border, length + border)
    axes.set_ylim(-border, width + border)
    axes.set_aspect("equal")


def _scatter(axes: Any, points: FloatArray, ball_id: str, size: float) -> None:
    points = points[~np.isnan(points).any(axis=1)]
    if len(points) == 0:
        return
    colour = _rgb(ball_id)
    face: str | tuple[float, float, float] = colour
    edge: str | tuple[float, float, float] = "none"
    line = 0.0
    if ball_id == "cue":
        edge, line = "black", 0.5
    elif ball_color(ball_id).striped:  # a ring: the stripe's colour around white
        face, edge, line = "white", colour, 1.0
    # A line's markers, not a scatter: one marker stamped at every point (Agg's
    # draw_markers), a fraction of a scatter's cost at thousands of points.
    axes.plot(
        points[:, 0],
        points[:, 1],
        linestyle="none",
        marker="o",
        markersize=math.sqrt(size),
        markerfacecolor=face,
        markeredgecolor=edge,
        markeredgewidth=line,
        alpha=0.75,
    )


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
        axes.plot(
            nudges,
            divergences,
            dashed,
            marker=marker,
            color=colour,
            label=method,
            markersize=4,
            markerfacecolor="none" if method == "event" else colour,
        )
    axes.axhline(radius, color="grey", linestyle="--", linewidth=0.8)
    axes.annotate(
        "one ball radius",
        (0.01, radius),
        xycoords=("axes fraction", "data"),
        va="bottom",
        fontsize=8,
        color="grey",
    )
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
