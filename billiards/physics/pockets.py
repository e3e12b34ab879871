"""Pockets: where the cushions stop, the jaws that end them, and the capture lines.

The cushion noses run along x = 0, x = L, y = 0 and y = W; from the head end (x = 0)
the corner pockets are head-left (0, W), head-right (0, 0), foot-left (L, W) and
foot-right (L, 0), the side pockets side-top (L/2, W) and side-bottom (L/2, 0)
(docs/pockets.md has the figure).

- Mouths: a corner mouth of width w_c ends each nose a = w_c / sqrt 2 from the corner;
  a side mouth of width w_s ends the long noses w_s / 2 either side of L/2.
- Jaws: each nose ends in a circle of radius rho tangent to it at its end (its centre
  rho behind the nose); a ball touches a jaw when its centre is r + rho from it.
- Capture: a line through a pocket's two jaw centres; a ball whose centre crosses it
  is pocketed. It meets its jaw circles inside them, so every way out of the table
  crosses a cushion line or a jaw circle (a bounce) or a capture line (a drop).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from billiards.physics.numerics.arithmetic import at_rows, projections
from billiards.physics.numerics.arrays import BoolArray, Constant, FloatArray, IntArray

# The one rule for which tables have pockets and where, shared with the scene reader.
from billiards.rules.pocket_rule import POCKET_NAMES, pocket_places, pocket_problem
from billiards.rules.seed import CORNER_POCKET_WIDTH, JAW_RADIUS, SIDE_POCKET_WIDTH


@dataclass(frozen=True)
class PocketTable:
    """A table's six pockets, as flat arrays (pockets in POCKET_NAMES order)."""

    names: tuple[str, ...]  # (P,)
    jaws: FloatArray  # (J, 2) m, centres of the jaws' rounded ends
    jaw_pocket: IntArray  # (J,) the pocket each jaw belongs to
    jaw_radius: float  # m, rho
    radius: float  # m, the balls' r
    capture_normal: FloatArray  # (P, 2) unit, pointing into the pocket
    capture_level: FloatArray  # (P,) m: a centre with normal . p > level is pocketed
    # Where each wall's cushion line (the ball centre's, r inside the nose) exists:
    # (lo, hi) along the wall's own coordinate (y for walls 0 and 1, x for 2 and 3).
    segments: tuple[FloatArray, ...]  # 4 arrays (S, 2)
    # What the table was laid out from (billiards.record.pocket_shapes.PocketShapes draws from it).
    table_size: tuple[float, float]  # (L, W) m between the noses
    corner_width: float  # m, w_c between a corner mouth's nose ends
    side_width: float  # m, w_s

    @property
    def jaw_reach(self) -> float:
        """r + rho: the distance between a ball's centre and a jaw's it touches."""
        return self.radius + self.jaw_radius


@dataclass(frozen=True)
class PocketRows:
    """The pockets of a batch's tables: the one table's arrays where every run shares
    its layout, else a row a ball (every table has the same pockets and normals)."""

    jaws: FloatArray  # (J, 2), or (k, J, 2)
    jaw_reach: Constant  # r + rho
    capture_normal: FloatArray  # (P, 2)
    capture_level: FloatArray  # (P,), or (k, P)
    segments: tuple[FloatArray, ...]  # 4 arrays (S, 2), or (k, S, 2)

    @classmethod
    def of(cls, tables: Sequence[PocketTable], count: int) -> PocketRows:
        """The rows of R tables, `count` balls a table."""
        table = tables[0]
        if all(_layout(each) == _layout(table) for each in tables):
            return cls(
                jaws=table.jaws,
                jaw_reach=table.jaw_reach,
                capture_normal=table.capture_normal,
                capture_level=table.capture_level,
                segments=table.segments,
            )

        def rows(values: Sequence[FloatArray | float]) -> FloatArray:
            return np.repeat(np.array(values), count, axis=0)

        return cls(
            jaws=rows([each.jaws for each in tables]),
            jaw_reach=rows([each.jaw_reach for each in tables]),
            capture_normal=table.capture_normal,
            capture_level=rows([each.capture_level for each in tables]),
            segments=tuple(rows([each.segments[wall] for each in tables]) for wall in range(4)),
        )

    def at(self, balls: IntArray) -> PocketRows:
        """The rows of `balls` (the one table itself, where every run shares it)."""
        if self.jaws.ndim == 2:
            return self
        return PocketRows(
            jaws=self.jaws[balls],
            jaw_reach=at_rows(self.jaw_reach, balls),
            capture_normal=self.capture_normal,
            capture_level=self.capture_level[balls],
            segments=tuple(segments[balls] for segments in self.segments),
        )


def _layout(table: PocketTable) -> tuple[object, ...]:
    """What a table's pockets are laid out from."""
    return (table.table_size, table.radius, table.corner_width, table.side_width, table.jaw_radius)


def pocket_table(
    table_size: tuple[float, float],
    radius: float,
    corner_width: float = CORNER_POCKET_WIDTH,
    side_width: float = SIDE_POCKET_WIDTH,
    jaw_radius: float = JAW_RADIUS,
) -> PocketTable:
    """The six pockets of a table of `table_size` (L, W) between the noses; ValueError
    for geometry a ball cannot use (pocket_problem)."""
    problem = pocket_problem(table_size, radius, corner_width, side_width, jaw_radius)
    if problem is not None:
        raise ValueError(f"{problem[0]} = {problem[1]:g}: expected {problem[2]}")
    length, width = table_size
    a, rho, half = corner_width / math.sqrt(2.0), jaw_radius, side_width / 2.0
    jaws: list[tuple[float, float]] = []
    normals: list[tuple[float, float]] = []
    levels: list[float] = []
    for x, y, sx, sy in pocket_places(table_size):
        if sx:
            # Corner: one jaw on the long (y) rail, one on the short (x) rail.
            centres = ((x + sx * a, y - sy * rho), (x - sx * rho, y + sy * a))
            normal = (-sx / math.sqrt(2.0), -sy / math.sqrt(2.0))
        else:
            centres = ((x - half, y - sy * rho), (x + half, y - sy * rho))
            normal = (0.0, -sy)
        jaws.extend(centres)
        normals.append(normal)
        levels.append(normal[0] * centres[0][0] + normal[1] * centres[0][1])
    short = np.array([[a, width - a]])
    long = np.array([[a, length / 2 - half], [length / 2 + half, length - a]])
    return PocketTable(
        names=POCKET_NAMES,
        jaws=np.array(jaws),
        jaw_pocket=np.repeat(np.arange(len(normals), dtype=np.intp), 2),  # two jaws a pocket
        jaw_radius=rho,
        radius=radius,
        capture_normal=np.array(normals),
        capture_level=np.array(levels),
        segments=(short, short, long, long),
        table_size=table_size,
        corner_width=corner_width,
        side_width=side_width,
    )


def on_cushion(along: FloatArray, segments: FloatArray, margin: float = 0.0) -> BoolArray:
    """Which points, by their coordinate `along` a wall, lie where its cushion exists
    (its `segments` (S, 2), or each point's (k, S, 2), brought in by `margin`)."""
    point = along[:, None]
    inside = (point >= segments[..., 0] + margin) & (point <= segments[..., 1] - margin)
    return np.asarray(inside.any(axis=1))


def pocket_of(pockets: PocketTable, positions: FloatArray) -> IntArray:
    """The pocket whose capture line each centre (N, 2) is past, or -1."""
    past = projections(positions, pockets.capture_normal) > pockets.capture_level  # (N, P)
    return np.where(past.any(axis=1), past.argmax(axis=1), -1).astype(np.intp)
