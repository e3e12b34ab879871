"""Each pocket's inside, as numpy triangles: the cloth rolling over the hole's edge
into a leather lip, and a liner with depth that darkens as it goes down.

The table (billiards.stage.table.build_table) cuts the cloth back by the lip's
radius round each hole; this fills the hole. A dropping ball sinks past the lip, which
hides its lower part, into the liner, darker as it goes down, as the lamp's light
does not reach there (shaders/ball.frag darkens the ball to match).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import numpy.typing as npt

from billiards.record.pocket_shapes import PocketShapes
from billiards.stage.holed_surfaces import HOLE_SEGMENTS
from billiards.stage.materials import CLOTH_GREEN, POCKET_HOLE, POCKET_LEATHER, Material, linear_rgb
from billiards.stage.meshes import Mesh, disc
from billiards.stage.table import bed_rects
from billiards.stage.table_plan import TableShape, pocket_cuts

FloatArray = npt.NDArray[np.float64]

LIP_STEPS = 6  # steps of the lip's quarter turn
LINER_RINGS = 8  # rings down the liner, for its darkening
# The liner's leather: a dark brown where the lamp reaches its top, black below.
LINER_LEATHER = Material(linear_rgb("#1c120c"), specular=0.0)  # matt, as the shelf
LINER_DARK_BELOW = 0.06  # m under the cloth: black from here down


# A ring: (radius, z, its normal's (outward, up) parts, and its colour, one (3,) or per
# point round it (HOLE_SEGMENTS + 1, 3)).
Ring = tuple[float, float, FloatArray, FloatArray]
AROUND = np.stack(
    [
        np.cos(np.linspace(0.0, 2 * math.pi, HOLE_SEGMENTS + 1)),
        np.sin(np.linspace(0.0, 2 * math.pi, HOLE_SEGMENTS + 1)),
    ],
    axis=1,
)  # as circle_points: the lip meets the cloth's cut exactly


def _band(mesh: Mesh, centre: FloatArray, upper: Ring, lower: Ring, material: Material) -> None:
    """A ring band round `centre` between two rings, smooth-shaded."""
    count = len(AROUND)
    rings = []
    for radius, z, (outward, up), colour in (upper, lower):
        points = np.column_stack([centre + radius * AROUND, np.full(count, z)])
        normals = np.column_stack([outward * AROUND, np.full(count, up)])
        rings.append((points, normals, np.broadcast_to(colour, (count, 3))))
    (p0, n0, c0), (p1, n1, c1) = rings
    order = [(p0[:-1], n0[:-1], c0[:-1]), (p1[:-1], n1[:-1], c1[:-1]), (p1[1:], n1[1:], c1[1:])]
    order += [(p0[:-1], n0[:-1], c0[:-1]), (p1[1:], n1[1:], c1[1:]), (p0[1:], n0[1:], c0[1:])]
    positions = np.stack([p for p, _, _ in order], axis=1).reshape(-1, 3)
    normals = np.stack([n for _, n, _ in order], axis=1).reshape(-1, 3)
    colours = np.stack([c for _, _, c in order], axis=1).reshape(-1, 3)
    mesh.add(positions, normals, material)
    mesh.colours[-len(positions) :] = colours


def build_pocket_liners(shape: TableShape, pockets: PocketShapes) -> Mesh:
    """The lip and liner of every pocket's hole (TableShape.pocket_lip round it)."""
    mesh = Mesh()
    lip = shape.pocket_lip
    leather = np.array(LINER_LEATHER.colour)
    black = np.array(POCKET_HOLE.colour)
    x0, y0, x1, y1 = bed_rects(shape)[0]  # the cloth's; beyond it, the leather shelf
    for cut in pocket_cuts(shape, pockets):
        x, y, radius = cut.hole
        centre = np.array((x, y))
        # The lip: a quarter turn from the bed (radius + lip, z 0, facing up) down to
        # the liner's wall (radius, z -lip, facing the axis): the cloth (or the shelf's
        # leather beyond it) rolls over its top, the liner's leather shows below.
        edge = centre + (radius + lip) * AROUND
        on_cloth = (edge[:, 0] > x0) & (edge[:, 0] < x1) & (edge[:, 1] > y0) & (edge[:, 1] < y1)
        bed = np.where(on_cloth[:, None], CLOTH_GREEN.colour, POCKET_LEATHER.colour)
        # (beyond the cloth the lip stays the shelf's dark leather all the way round)
        under = np.where(on_cloth[:, None], leather, POCKET_LEATHER.colour)
        for step in range(LIP_STEPS):
            rings: list[Ring] = []
            for k in (step, step + 1):
                turn = 0.5 * math.pi * k / LIP_STEPS
                kept = (1 - k / LIP_STEPS) ** 2  # of the bed's colour
                rings.append(
                    (
                        radius + lip * (1 - math.sin(turn)),
                        -lip * (1 - math.cos(turn)),
                        np.array((-math.sin(turn), math.cos(turn))),
                        bed * kept + under * (1 - kept),
                    )
                )
            _band(mesh, centre, rings[0], rings[1], LINER_LEATHER)
        # The liner's wall, from under the lip to its bottom, darkening as it goes down.
        depths = np.linspace(lip, shape.liner_depth, LINER_RINGS + 1)
        for top, bottom in itertools.pairwise(depths):
            rings = []
            for depth in (top, bottom):
                dark = min(max((depth - lip) / (LINER_DARK_BELOW - lip), 0.0), 1.0)
                colour = leather * (1 - dark) + black * dark
                rings.append((radius, -depth, np.array((-1.0, 0.0)), colour))
            _band(mesh, centre, rings[0], rings[1], LINER_LEATHER)
        disc(mesh, (x, y, -shape.liner_depth), radius, POCKET_HOLE, segments=HOLE_SEGMENTS)
    return mesh
