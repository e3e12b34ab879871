"""The table seen from above: its dimensions, the cushion noses, where each cushion
runs and how its ends are cut back into the jaws, and each pocket's cut through the bed
and the rail (billiards.record.pocket_shapes gives the holes, mouths and jaws)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from billiards.record.pocket_shapes import PocketShapes
from billiards.stage.holed_surfaces import HOLE_SEGMENTS

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class TableShape:
    """Dimensions of the built table, in metres (cloth at z = 0)."""

    length: float
    width: float
    cushion_width: float = 0.05  # nose to the rail
    nose_height: float = (
        0.036  # about 0.63 ball diameters: the nose meets the ball above its centre
    )
    rail_width: float = 0.11
    rail_top: float = 0.042
    rail_bottom: float = -0.12
    apron_bottom: float = -0.30
    floor: float = -0.79  # the cloth stands 79 cm above the floor
    liner_depth: float = 0.11  # m: the dark cup under each hole (above the apron's top)
    # m: the radius of the cloth's roll over a hole's edge into its liner (the cloth is
    # cut back this far round the hole; billiards.stage.pocket_mesh fills it)
    pocket_lip: float = 0.006

    @property
    def outer(self) -> float:
        """From a cushion nose to the rail's outer edge."""
        return self.cushion_width + self.rail_width

    def sights(self) -> list[tuple[float, float, bool]]:
        """(x, y, along_x) of the diamond sights, at the middle of the rail tops."""
        mid = self.cushion_width + self.rail_width / 2
        out = []
        for i in (1, 2, 3, 5, 6, 7):
            x = self.length * i / 8
            out += [(x, -mid, True), (x, self.width + mid, True)]
        for j in (1, 2, 3):
            y = self.width * j / 4
            out += [(-mid, y, False), (self.length + mid, y, False)]
        return out


# Behind the nose, a cushion's end is cut back along its jaw: towards a corner pocket
# at 45 degrees (the face is then tangent to the corner hole), away from a side pocket
# by this many metres per metre (the side pocket's opening widens into the rail).
CORNER_JAW_SLOPE = 1.0
SIDE_JAW_SLOPE = -0.35


@dataclass(frozen=True)
class PocketCut:
    """One pocket as built: the hole through the bed (a dark liner below it), its edge
    on the physics' capture line (PocketShapes.edge_radii), and the
    larger cut through the rail around it, whose wall runs from one cushion's back end
    to the other's (billiards.record.pocket_shapes.PocketShapes gives the hole and the mouths)."""

    hole: tuple[float, float, float]  # x, y, radius of the hole in the bed
    rail: tuple[float, float, float]  # x, y, radius of the cut through the rail


def _wall_of(point: FloatArray, shape: TableShape) -> int | None:
    """Which nose line a mouth point lies on: 0 (x = 0), 1 (x = L), 2 (y = 0),
    3 (y = W)."""
    x, y = float(point[0]), float(point[1])
    for wall, distance in enumerate((x, x - shape.length, y, y - shape.width)):
        if abs(distance) < 1e-6:
            return wall
    return None


class NoseLine(NamedTuple):
    """A wall's cushion nose: from `origin` along `along` for `length` m, `outward`
    pointing off the table."""

    origin: tuple[float, float]
    along: tuple[float, float]
    outward: tuple[float, float]
    length: float


def nose_lines(shape: TableShape) -> list[NoseLine]:
    """The four nose lines, walls 0 (x = 0), 1 (x = L), 2 (y = 0) and 3 (y = W)."""
    length, width = shape.length, shape.width
    return [
        NoseLine((0.0, 0.0), (0.0, 1.0), (-1.0, 0.0), width),
        NoseLine((length, 0.0), (0.0, 1.0), (1.0, 0.0), width),
        NoseLine((0.0, 0.0), (1.0, 0.0), (0.0, -1.0), length),
        NoseLine((0.0, width), (1.0, 0.0), (0.0, 1.0), length),
    ]


@dataclass(frozen=True)
class CushionRun:
    """One cushion along a wall: from `span[0]` to `span[1]` along the nose line, its
    ends cut back by `jaw_slopes` (metres along per metre behind the nose, towards the
    end's pocket; negative leans away from it)."""

    wall: int
    span: tuple[float, float]
    jaw_slopes: tuple[float, float]
    jaw_radius: float = 0.0  # m: the rounding of each end's nose into its face (0: sharp)


def cushion_runs(shape: TableShape, pockets: PocketShapes | None) -> list[CushionRun]:
    """The cushions: one whole cushion per wall without pockets (mitred at the corners),
    else one between each two pocket mouths on a wall."""
    walls = nose_lines(shape)
    if pockets is None:
        return [
            CushionRun(wall, (0.0, line.length), (CORNER_JAW_SLOPE, CORNER_JAW_SLOPE))
            for wall, line in enumerate(walls)
        ]
    ends: list[list[tuple[float, float]]] = [[] for _ in walls]
    for mouth in pockets.mouths:
        on = [_wall_of(point, shape) for point in mouth]
        side = on[0] == on[1]  # a side pocket's two mouths are on one wall
        for point, wall in zip(mouth, on, strict=True):
            if wall is None:
                raise ValueError(f"pocket mouth {tuple(point)} is on no cushion's nose line")
            origin, along = walls[wall].origin, walls[wall].along
            s = (point[0] - origin[0]) * along[0] + (point[1] - origin[1]) * along[1]
            ends[wall].append((float(s), SIDE_JAW_SLOPE if side else CORNER_JAW_SLOPE))
    runs = []
    for wall, points in enumerate(ends):
        points.sort()
        for start, stop in zip(points[::2], points[1::2], strict=True):
            runs.append(
                CushionRun(wall, (start[0], stop[0]), (start[1], stop[1]), pockets.jaw_radius)
            )
    return runs


class JawEnd(NamedTuple):
    """One end of a cushion in its own frame: u along the nose towards the end's
    pocket (0 at the mouth), depth behind the nose. The end is cut back along a face
    at `slope` (u per depth), and the nose rounds into that face about the jaw's
    centre (u, depth) = (0, radius): billiards.physics.pockets' jaw circle."""

    mouth: FloatArray  # (2,) x, y of the mouth (where the nose line ends)
    u: FloatArray  # (2,) unit, along the nose towards the pocket
    depth: FloatArray  # (2,) unit, behind the nose (off the table)
    slope: float
    radius: float

    @property
    def turn(self) -> float:
        """Radians the rounding turns through, from facing the table to facing the
        pocket along the face."""
        return math.atan2(1.0, self.slope)

    def normal(self, angle: float) -> FloatArray:
        """(u, depth) of the rounding's outward normal `angle` rad into its turn."""
        return np.array((math.sin(angle), -math.cos(angle)))

    def point(self, depth: float, angle: float) -> FloatArray:
        """(u, depth) of the end's outline for the profile's point `depth` behind the
        nose, `angle` into the rounding: on a circle of the jaw's radius tangent to the
        nose (at this depth) and to the face, whose centre slides along the face."""
        face = np.array((self.slope, 1.0)) / math.hypot(self.slope, 1.0)
        centre = np.array((0.0, self.radius)) + depth / face[1] * face
        return centre + self.radius * self.normal(angle)

    def place(self, local: FloatArray) -> FloatArray:
        """x, y of local (u, depth) points (..., 2)."""
        return self.mouth + local[..., :1] * self.u + local[..., 1:] * self.depth


def jaw_ends(shape: TableShape, run: CushionRun) -> tuple[JawEnd, JawEnd]:
    """A cushion's two ends (at span[0] and span[1])."""
    line = nose_lines(shape)[run.wall]
    origin, along, outward = np.array(line.origin), np.array(line.along), np.array(line.outward)
    first = JawEnd(
        mouth=origin + run.span[0] * along,
        u=-along,
        depth=outward,
        slope=run.jaw_slopes[0],
        radius=run.jaw_radius,
    )
    second = JawEnd(
        mouth=origin + run.span[1] * along,
        u=along,
        depth=outward,
        slope=run.jaw_slopes[1],
        radius=run.jaw_radius,
    )
    return first, second


def cushion_back_ends(shape: TableShape, run: CushionRun) -> tuple[FloatArray, FloatArray]:
    """Where a cushion's two end faces meet the rail (cushion_width behind the nose)."""
    cw = shape.cushion_width
    ends = []
    for end in jaw_ends(shape, run):
        turn = end.turn
        # The face's line, tangent to the rounding, at the rail's depth.
        u = (end.radius * (1 - math.cos(turn)) + cw * math.cos(turn)) / math.sin(turn)
        ends.append(end.place(np.array((u, cw))))
    return ends[0], ends[1]


def pocket_cuts(shape: TableShape, pockets: PocketShapes) -> list[PocketCut]:
    """Each pocket's hole, and the rail cut that opens the rail from one cushion's back
    end to the other's, around the hole: for a corner, the circle through both back
    ends and the rail's inner corner; for a side pocket, centred on the hole."""
    backs = [end for run in cushion_runs(shape, pockets) for end in cushion_back_ends(shape, run)]
    cw = shape.cushion_width
    low, high = np.array((-cw, -cw)), np.array((shape.length + cw, shape.width + cw))
    angles = np.linspace(0.0, 2 * math.pi, HOLE_SEGMENTS, endpoint=False)
    ring = np.column_stack((np.cos(angles), np.sin(angles)))
    cuts = []
    edges = pockets.edge_radii()
    for (x, y, _), radius, mouth in zip(pockets.holes, edges, pockets.mouths, strict=True):
        hole = np.array((x, y))
        # The two back ends nearest to this hole are its cushions'.
        near = sorted(backs, key=lambda end: float(np.linalg.norm(end - hole)))[:2]
        if _wall_of(mouth[0], shape) != _wall_of(mouth[1], shape):  # a corner pocket
            # The rail's inner corner behind it.
            inner_corner = np.where(hole < 0.5 * (low + high), low, high)
            # The circle through both back ends and the rail's inner corner: its centre
            # hole + t u on the diagonal, |hole + t u - corner| = |hole + t u - back|.
            d = float(np.linalg.norm(inner_corner - hole))
            u = (inner_corner - hole) / d
            b = near[0] - hole
            t = (d * d - float(b @ b)) / (2.0 * (d - float(b @ u)))
            # (t < 0: the back ends lie beyond the corner; a circle about the hole
            # through them covers it.)
            centre = hole + max(t, 0.0) * u
        else:
            centre = hole
        reach = max(float(np.linalg.norm(end - centre)) for end in near)
        # It must also open the rail wherever the hole reaches under it.
        points = hole + radius * ring
        under = np.any((points < low) | (points > high), axis=1)
        if under.any():
            reach = max(reach, float(np.max(np.linalg.norm(points[under] - centre, axis=1))))
        cuts.append(
            PocketCut(
                (float(x), float(y), float(radius)), (float(centre[0]), float(centre[1]), reach)
            )
        )
    return cuts
