"""The table, the room and the lamp as numpy triangle meshes (no GL here).

Frame: the physics frame. z is up, the cloth is z = 0 and the playing area is
[0, L] x [0, W] between the cushion noses. Solids are built convex (boxes, prisms,
discs) so flat normals can be pointed away from their centres; the table's top is
built from flat surfaces and walls with their own normals, so that a table with
pockets has real holes: through the cloth bed (each over a dark liner, so a ball
dropping in goes into darkness) and through the rail. The mesh data is plain arrays,
uploaded by billiards.render.gl.renderer.

Colours are linear RGB (the shaders light in linear space and encode for display).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import PocketShapes

FloatArray = npt.NDArray[np.float64]

# Surface patterns the scene shader draws procedurally (in_material.w).
# WOOD's grain runs along the rails (mitred at the corners), UPRIGHT_WOOD's up.
PLAIN, WOOD, PLANKS, CLOTH, UPRIGHT_WOOD = 0.0, 1.0, 2.0, 3.0, 4.0


def srgb_to_linear(display: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Display (sRGB) values in [0, 1] as linear light, by the exact sRGB curve."""
    c = np.asarray(display, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_rgb(hex_colour: str) -> tuple[float, float, float]:
    """A display colour ("#rrggbb") as linear RGB."""
    value = hex_colour.lstrip("#")
    r, g, b = srgb_to_linear([int(value[i : i + 2], 16) / 255.0 for i in (0, 2, 4)]).tolist()
    return (r, g, b)


@dataclass(frozen=True)
class Material:
    colour: tuple[float, float, float]  # linear RGB albedo
    specular: float = 0.0  # strength of the Blinn-Phong highlight
    shininess: float = 16.0  # Blinn-Phong exponent
    emissive: float = 0.0  # share of the colour emitted regardless of light
    pattern: float = PLAIN


CLOTH_GREEN = Material(linear_rgb("#1d7a3c"), specular=0.02, shininess=4.0, pattern=CLOTH)
CUSHION_GREEN = Material(linear_rgb("#155c2c"), specular=0.04, shininess=8.0, pattern=CLOTH)
RAIL_WOOD = Material(linear_rgb("#6b3318"), specular=0.12, shininess=60.0, pattern=WOOD)
APRON_WOOD = Material(linear_rgb("#5c2b13"), specular=0.25, shininess=40.0, pattern=WOOD)
LEG_WOOD = Material(linear_rgb("#3e1c0c"), specular=0.2, shininess=40.0, pattern=UPRIGHT_WOOD)
SIGHT_PEARL = Material(linear_rgb("#e8e0cf"), specular=0.9, shininess=160.0, emissive=0.03)
# The thin dark band an inlaid sight's pearl is set in.
SIGHT_SETTING = Material(linear_rgb("#24120a"), specular=0.3, shininess=60.0)
# A sight's half-diagonals (m) along and across the rail: a pearl diamond 16 x 8 mm,
# set flush in a band 1.5 mm wide.
SIGHT_HALF = (0.008, 0.004)
SIGHT_BAND = 0.0015
POCKET_HOLE = Material(linear_rgb("#050505"), specular=0.0)
# The pocket's leather (its shelf and the wall of the rail's cut): near black and matt,
# so a pocket reads as a dark opening from every side, not a pale cup under the lamp.
POCKET_LEATHER = Material(linear_rgb("#0b0908"), specular=0.0)
FLOOR_WOOD = Material(linear_rgb("#5a3a22"), specular=0.15, shininess=30.0, pattern=PLANKS)
WALL_PAINT = Material(linear_rgb("#7a2e2a"), specular=0.0)
WAINSCOT = Material(linear_rgb("#3b2414"), specular=0.15, shininess=20.0, pattern=WOOD)
CEILING = Material(linear_rgb("#6b625a"), specular=0.0)
LAMP_SHADE = Material(linear_rgb("#0f3d22"), specular=0.5, shininess=50.0)
LAMP_BRASS = Material(linear_rgb("#8a6a2a"), specular=0.9, shininess=80.0)
LAMP_GLOW = Material(linear_rgb("#fff3dc"), emissive=1.0)


@dataclass
class Mesh:
    """Triangles as flat vertex arrays: three consecutive vertices per triangle."""

    positions: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    normals: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    colours: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    materials: FloatArray = field(default_factory=lambda: np.zeros((0, 4)))

    def __len__(self) -> int:
        return len(self.positions)

    def add(self, positions: FloatArray, normals: FloatArray, material: Material) -> None:
        count = len(positions)
        self.positions = np.concatenate([self.positions, positions])
        self.normals = np.concatenate([self.normals, normals])
        self.colours = np.concatenate([self.colours, np.tile(material.colour, (count, 1))])
        values = (material.specular, material.shininess, material.emissive, material.pattern)
        self.materials = np.concatenate([self.materials, np.tile(values, (count, 1))])

    def extend(self, other: Mesh) -> None:
        self.positions = np.concatenate([self.positions, other.positions])
        self.normals = np.concatenate([self.normals, other.normals])
        self.colours = np.concatenate([self.colours, other.colours])
        self.materials = np.concatenate([self.materials, other.materials])

    def interleaved(self) -> npt.NDArray[np.float32]:
        """Per vertex: in_position 3f, in_normal 3f, in_color 3f, in_material 4f."""
        data = np.hstack([self.positions, self.normals, self.colours, self.materials])
        return np.ascontiguousarray(data, dtype=np.float32)

    def bounds(self) -> tuple[FloatArray, FloatArray]:
        return self.positions.min(axis=0), self.positions.max(axis=0)


def convex_solid(
    mesh: Mesh, corners: FloatArray, faces: list[list[int]], material: Material
) -> None:
    """Add a convex solid given its corners and faces (corner indices around each face).

    Faces are fanned into triangles; each gets the flat normal that points away from
    the solid's centre, so winding does not matter.
    """
    centre = corners.mean(axis=0)
    triangles = []
    for face in faces:
        for k in range(1, len(face) - 1):
            triangles.append((face[0], face[k], face[k + 1]))
    tri = corners[np.array(triangles)]  # (T, 3, 3)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    keep = lengths[:, 0] > 1e-12
    tri, normals = tri[keep], normals[keep] / lengths[keep]
    outward = np.einsum("ij,ij->i", normals, tri.mean(axis=1) - centre) >= 0
    normals[~outward] *= -1
    mesh.add(tri.reshape(-1, 3), np.repeat(normals, 3, axis=0), material)


# The unit cube's corners and its 12 triangles, wound outwards (trimesh.creation.box's,
# written out: importing trimesh costs the film 0.4 s at its start, before any frame).
CUBE_CORNERS = np.array(
    [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)], dtype=np.float64
)
CUBE_TRIANGLES = np.array(
    [[1, 3, 0], [4, 1, 0], [0, 3, 2], [2, 4, 0], [1, 7, 3], [5, 1, 4],
     [5, 7, 1], [3, 7, 2], [6, 4, 2], [2, 7, 6], [6, 5, 4], [7, 5, 6]]
)  # fmt: skip


def box(mesh: Mesh, low: tuple[float, ...], high: tuple[float, ...], material: Material) -> None:
    """An axis-aligned box from corner `low` to corner `high`, flat-shaded."""
    start = np.array(low, dtype=np.float64)
    corners = start + CUBE_CORNERS * (np.array(high, dtype=np.float64) - start)
    triangles = corners[CUBE_TRIANGLES]  # (12, 3, 3)
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    mesh.add(triangles.reshape(-1, 3), np.repeat(normals, 3, axis=0), material)


def quad(mesh: Mesh, corners: FloatArray, normal: tuple[float, float, float], m: Material) -> None:
    """A one-sided rectangle (corners in order around it) facing `normal`."""
    tri = corners[[0, 1, 2, 0, 2, 3]]
    mesh.add(tri, np.tile(normal, (6, 1)), m)


def disc(
    mesh: Mesh,
    centre: tuple[float, float, float],
    radius: float,
    material: Material,
    inner: float = 0.0,
    segments: int = 40,
) -> None:
    """A horizontal disc (or ring when inner > 0) facing up."""
    angles = np.linspace(0.0, 2 * math.pi, segments + 1)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    c = np.array(centre)
    outer_pts = c + radius * ring
    if inner > 0:
        inner_pts = c + inner * ring
        tris = []
        for k in range(segments):
            tris += [inner_pts[k], outer_pts[k], outer_pts[k + 1]]
            tris += [inner_pts[k], outer_pts[k + 1], inner_pts[k + 1]]
    else:
        tris = []
        for k in range(segments):
            tris += [c, outer_pts[k], outer_pts[k + 1]]
    positions = np.array(tris)
    mesh.add(positions, np.tile((0.0, 0.0, 1.0), (len(positions), 1)), material)


def cylinder(
    mesh: Mesh,
    bottom: tuple[float, float, float],
    height: float,
    radius_bottom: float,
    radius_top: float,
    material: Material,
    segments: int = 32,
) -> None:
    """A vertical (truncated) cone's side with smooth normals, plus its two caps."""
    # The side: a quad (two triangles) per section between the bottom and top rings.
    angles = np.linspace(0.0, 2 * math.pi, segments + 1)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    low = radius_bottom * ring
    high = radius_top * ring + np.array([0.0, 0.0, height])
    side = np.stack([low[:-1], low[1:], high[:-1], high[:-1], low[1:], high[1:]], axis=1).reshape(
        -1, 3, 3
    )
    triangles = side + np.array(bottom)  # (T, 3, 3)
    # Smooth normals in closed form: outward from the axis, tilted by the side's slope.
    outward = triangles[..., :2] - np.array(bottom[:2])
    outward /= np.linalg.norm(outward, axis=-1, keepdims=True)
    slope = (radius_bottom - radius_top) / height
    normals = np.concatenate([outward, np.full((*outward.shape[:-1], 1), slope)], axis=-1)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    mesh.add(triangles.reshape(-1, 3), normals.reshape(-1, 3), material)
    b = np.array(bottom)
    disc(mesh, (b[0], b[1], b[2] + height), radius_top, material, segments=segments)
    cap = Mesh()
    disc(cap, (b[0], b[1], b[2]), radius_bottom, material, segments=segments)
    cap.normals[:] = (0.0, 0.0, -1.0)
    mesh.extend(cap)


# --- the table ---------------------------------------------------------------------------


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
# Angular steps of a hole's circle (a multiple of 8: the tiles' corners are steps).
HOLE_SEGMENTS = 48


@dataclass(frozen=True)
class PocketCut:
    """One pocket as built: the hole through the bed (a dark liner below it), its edge
    on the physics' capture line (PocketShapes.edge_radii), and the
    larger cut through the rail around it, whose wall runs from one cushion's back end
    to the other's (billiards.record.trajectory.PocketShapes gives the hole and the mouths)."""

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


def _walls(shape: TableShape) -> list[NoseLine]:
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
    walls = _walls(shape)
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
    line = _walls(shape)[run.wall]
    origin, along, outward = np.array(line.origin), np.array(line.along), np.array(line.outward)
    return (
        JawEnd(origin + run.span[0] * along, -along, outward, run.jaw_slopes[0], run.jaw_radius),
        JawEnd(origin + run.span[1] * along, along, outward, run.jaw_slopes[1], run.jaw_radius),
    )


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


# --- surfaces with round holes ------------------------------------------------------------

Rect = tuple[float, float, float, float]  # x0, y0, x1, y1


def _clip(polygon: FloatArray, rect: Rect) -> FloatArray:
    """A convex polygon (K, 2) clipped to an axis-aligned rectangle (Sutherland-Hodgman).

    A crossing is computed from the edge's endpoints in a fixed order, so two polygons
    sharing an edge get the very same point on the clip line (no cracks between them).
    """
    for axis, bound, sign in ((0, rect[0], 1.0), (0, rect[2], -1.0), (1, rect[1], 1.0), (1, rect[3], -1.0)):  # fmt: skip
        if len(polygon) == 0:
            break
        inside = sign * (polygon[:, axis] - bound) >= 0
        kept = []
        for k in range(len(polygon)):
            j = (k + 1) % len(polygon)
            if inside[k]:
                kept.append(polygon[k])
            if inside[k] != inside[j]:
                p, q = sorted((polygon[k], polygon[j]), key=tuple)
                kept.append(p + (bound - p[axis]) / (q[axis] - p[axis]) * (q - p))
        polygon = np.array(kept).reshape(-1, 2)
    return polygon


# A hole's tile: the square around it, this many hole radii from its centre to a side
# (far enough that each side's points see the part of the hole's polygon they join).
TILE_REACH = 1.5


def _zipper(
    inner: FloatArray, inner_angles: FloatArray, outer: FloatArray, outer_angles: FloatArray
) -> list[FloatArray]:
    """Triangles filling the ring between two closed polygons around a common centre,
    each given by its points in increasing angle (radians in [0, 2 pi), the inner
    polygon's first at 0): one pass round, always advancing along the polygon whose
    next point comes first."""
    n, m = len(inner), len(outer)
    ahead_inner = np.append(inner_angles, 2 * math.pi)
    ahead_outer = np.append(outer_angles, outer_angles[0] + 2 * math.pi)
    triangles = []
    i = j = 0
    while i < n or j < m:
        if j == m or (i < n and ahead_inner[i + 1] <= ahead_outer[j + 1]):
            triangles.append(np.array([inner[i], inner[(i + 1) % n], outer[j % m]]))
            i += 1
        else:
            triangles.append(np.array([inner[i % n], outer[j], outer[(j + 1) % m]]))
            j += 1
    return triangles


def holed_surface(rects: list[Rect], holes: list[tuple[float, float, float]]) -> list[FloatArray]:
    """Triangles (T, 3, 2) covering each of some disjoint rectangles less round holes,
    one array per rectangle, all of them one conforming mesh: every edge is shared
    whole by the triangles on both sides (a vertex inside another triangle's edge
    would leave pixel cracks where the rasterizer rounds the two differently).

    Each hole sits in a square tile (TILE_REACH radii to a side); the rest is a grid
    through every rectangle's and tile's sides and each hole's centre, two triangles
    a cell. Inside a tile,
    the ring between the hole's polygon (HOLE_SEGMENTS steps, from angle 0) and the
    tile's sides (with a point wherever a grid line meets them) is zipped into
    triangles, clipped to the rectangles. The tiles must not overlap.
    """
    squares = [
        (x - TILE_REACH * r, y - TILE_REACH * r, x + TILE_REACH * r, y + TILE_REACH * r)
        for x, y, r in holes
    ]
    # Grid lines through each hole's centre too: a point mid-side on each of its tile's
    # sides, so each point of the sides joins at most an eighth of the hole.
    xs = np.unique([v for b in (*rects, *squares) for v in (b[0], b[2])] + [h[0] for h in holes])
    ys = np.unique([v for b in (*rects, *squares) for v in (b[1], b[3])] + [h[1] for h in holes])
    found: list[list[FloatArray]] = [[] for _ in rects]

    def within(box_: Rect, x: float, y: float) -> bool:
        return box_[0] < x < box_[2] and box_[1] < y < box_[3]

    for x0, x1 in itertools.pairwise(xs):
        for y0, y1 in itertools.pairwise(ys):
            middle = (0.5 * (x0 + x1), 0.5 * (y0 + y1))
            if any(within(square, *middle) for square in squares):
                continue
            for index, rect in enumerate(rects):
                if within(rect, *middle):
                    corners = np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
                    found[index] += [corners[[0, 1, 2]], corners[[0, 2, 3]]]
                    break
    steps = np.linspace(0.0, 2 * math.pi, HOLE_SEGMENTS + 1)
    ray = np.column_stack((np.cos(steps), np.sin(steps)))
    for (x, y, r), square in zip(holes, squares, strict=True):
        centre = np.array((x, y))
        inner = (centre + r * ray)[:-1]  # as circle_points: the liner meets it exactly
        x0, y0, x1, y1 = square
        inside_x = [v for v in xs if x0 < v < x1]
        inside_y = [v for v in ys if y0 < v < y1]
        sides = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        sides += [(v, y0) for v in inside_x] + [(v, y1) for v in inside_x]
        sides += [(x0, v) for v in inside_y] + [(x1, v) for v in inside_y]
        outer = np.array(sides)
        angles = np.mod(np.arctan2(outer[:, 1] - y, outer[:, 0] - x), 2 * math.pi)
        order = np.argsort(angles, kind="stable")
        ring = _zipper(inner, steps[:-1], outer[order], angles[order])
        overlapping = [
            (index, rect)
            for index, rect in enumerate(rects)
            if rect[0] < x1 and rect[2] > x0 and rect[1] < y1 and rect[3] > y0
        ]
        for triangle in ring:
            for index, rect in overlapping:
                part = _clip(triangle, rect)
                for j in range(1, len(part) - 1):
                    found[index].append(part[[0, j, j + 1]])
    out = []
    for triangles in found:
        if not triangles:
            out.append(np.zeros((0, 3, 2)))
            continue
        array = np.array(triangles)
        u, v = array[:, 1] - array[:, 0], array[:, 2] - array[:, 0]
        out.append(array[np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) > 1e-14])
    return out


def flat_surface(
    mesh: Mesh, triangles: FloatArray, z: float, material: Material, up: bool = True
) -> None:
    """2-D triangles (T, 3, 2) laid horizontally at height z, facing up (or down)."""
    positions = np.concatenate([triangles, np.full((*triangles.shape[:2], 1), z)], axis=2)
    normal = (0.0, 0.0, 1.0 if up else -1.0)
    mesh.add(positions.reshape(-1, 3), np.tile(normal, (positions.shape[0] * 3, 1)), material)


def wall(
    mesh: Mesh, segments: FloatArray, low: float, high: float, facing: FloatArray, m: Material
) -> None:
    """Vertical quads from z = low to high over segments (S, 2, 2) in the plane, each
    facing the point `facing` (x, y). Segments of no length are left out."""
    if len(segments):
        segments = segments[np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1) > 1e-12]
    if len(segments) == 0:
        return
    a, b = segments[:, 0], segments[:, 1]
    along = b - a
    normal = np.column_stack((-along[:, 1], along[:, 0]))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    flip = np.einsum("ij,ij->i", normal, facing - 0.5 * (a + b)) < 0
    normal[flip] *= -1
    z0, z1 = np.full((len(a), 1), low), np.full((len(a), 1), high)
    p0, p1, p2, p3 = np.hstack((a, z0)), np.hstack((b, z0)), np.hstack((b, z1)), np.hstack((a, z1))
    quads = np.stack([p0, p1, p2, p0, p2, p3], axis=1)
    normals = np.repeat(np.hstack((normal, np.zeros((len(a), 1))))[:, None], 6, axis=1)
    mesh.add(quads.reshape(-1, 3), normals.reshape(-1, 3), m)


def circle_points(centre: tuple[float, float], radius: float, steps: int) -> FloatArray:
    """A closed polygon (steps + 1, 2) round a circle, from angle 0 (as holed_surface)."""
    angles = np.linspace(0.0, 2 * math.pi, steps + 1)
    return np.array(centre) + radius * np.column_stack((np.cos(angles), np.sin(angles)))


def segments_outside_rect(points: FloatArray, low: FloatArray, high: FloatArray) -> FloatArray:
    """The parts (S, 2, 2) of a polyline's segments outside an axis-aligned rectangle."""
    found = []
    for p, q in itertools.pairwise(points):
        # Liang-Barsky: the segment's parameters inside the rectangle, [enter, leave].
        enter, leave = 0.0, 1.0
        step = q - p
        for axis in (0, 1):
            if abs(step[axis]) < 1e-15:
                if not low[axis] <= p[axis] <= high[axis]:
                    enter, leave = 1.0, 0.0
                continue
            t0 = (low[axis] - p[axis]) / step[axis]
            t1 = (high[axis] - p[axis]) / step[axis]
            enter, leave = max(enter, min(t0, t1)), min(leave, max(t0, t1))
        if enter >= leave:
            found.append((p, q))
            continue
        if enter > 0:
            found.append((p, p + enter * step))
        if leave < 1:
            found.append((p + leave * step, q))
    return np.array(found).reshape(-1, 2, 2)


def segment_outside_circles(
    a: FloatArray, b: FloatArray, circles: list[tuple[float, float, float]]
) -> FloatArray:
    """The parts (S, 2, 2) of the segment a-b outside every circle (x, y, radius)."""
    step = b - a
    cuts: list[tuple[float, float]] = []
    for x, y, r in circles:
        # |a + t step - c|^2 = r^2
        f = a - np.array((x, y))
        qa, qb, qc = float(step @ step), 2.0 * float(f @ step), float(f @ f) - r * r
        disc_ = qb * qb - 4 * qa * qc
        if disc_ > 0:
            root = math.sqrt(disc_)
            cuts.append(((-qb - root) / (2 * qa), (-qb + root) / (2 * qa)))
    kept = [(0.0, 1.0)]
    for c0, c1 in cuts:
        kept = [
            piece
            for t0, t1 in kept
            for piece in ((t0, min(t1, c0)), (max(t0, c1), t1))
            if piece[1] > piece[0]
        ]
    return np.array([(a + t0 * step, a + t1 * step) for t0, t1 in kept]).reshape(-1, 2, 2)


# --- cushions, rails and pockets ----------------------------------------------------------

CUSHION_FOOT = 0.016  # m behind the nose: where the cushion's underside meets the bed


def _cushion_profile(shape: TableShape) -> list[tuple[float, float]]:
    """The cushion's cross-section as (distance behind the nose, height), convex."""
    cw = shape.cushion_width
    return [
        (cw, 0.0),
        (CUSHION_FOOT, 0.0),
        (0.0, shape.nose_height - 0.006),
        (0.003, shape.nose_height + 0.002),
        (cw, shape.rail_top - 0.002),
    ]


JAW_STEPS = 8  # steps of a cushion end's rounding


def cushion(mesh: Mesh, shape: TableShape, run: CushionRun) -> None:
    """One cushion between two pockets (or corners): its profile swept along the nose
    line over run.span, each end cut back behind the nose by its jaw slope; with a
    jaw radius, the rubber rounds from the nose into the end's face (jaw_rounding)."""
    line = _walls(shape)[run.wall]
    o = np.array([*line.origin, 0.0])
    t = np.array([*line.along, 0.0])
    n = np.array([*line.outward, 0.0])
    profile = _cushion_profile(shape)
    corners = []
    for s_end in (0, 1):
        for depth, height in profile:
            if s_end == 0:
                s = run.span[0] - run.jaw_slopes[0] * depth
            else:
                s = run.span[1] + run.jaw_slopes[1] * depth
            corners.append(o + s * t + depth * n + (0.0, 0.0, height))
    count = len(profile)
    faces = [list(range(count)), list(range(count, 2 * count))]
    for k in range(count):
        j = (k + 1) % count
        faces.append([k, j, count + j, count + k])
    convex_solid(mesh, np.array(corners), faces, CUSHION_GREEN)
    if run.jaw_radius > 0:
        for end in jaw_ends(shape, run):
            jaw_rounding(mesh, shape, end)


def jaw_rounding(mesh: Mesh, shape: TableShape, end: JawEnd) -> None:
    """The rubber of a cushion's end rounding into the pocket: the profile swept on
    round the jaw (JawEnd.point) from the nose, where it meets the straight cushion,
    to the face, which closes it flat. Smooth normals round the turn, so the nose and
    the face are one surface; at nose height it is the physics' jaw circle."""
    cw = shape.cushion_width
    profile = np.array(_cushion_profile(shape))  # (K, 2) depth, height
    angles = np.linspace(0.0, end.turn, JAW_STEPS + 1)
    local = np.array([[end.point(d, a) for a in angles] for d, _ in profile])  # (K, A, 2)
    local[..., 1] = np.minimum(local[..., 1], cw)  # the back stays against the rail
    xy = end.place(local)
    heights = np.broadcast_to(profile[:, 1:2], local.shape[:2])
    points = np.concatenate([xy, heights[..., None]], axis=2)  # (K, A, 3)
    # Each profile edge's outward normal in (depth, height), turned with the rounding.
    centre = profile.mean(axis=0)
    count = len(profile)
    positions, normals = [], []
    for k in range(count):
        j = (k + 1) % count
        (d0, h0), (d1, h1) = profile[k], profile[j]
        edge_normal = np.array((h1 - h0, -(d1 - d0)))
        if edge_normal @ (0.5 * (profile[k] + profile[j]) - centre) < 0:
            edge_normal = -edge_normal
        edge_normal /= np.linalg.norm(edge_normal)
        for a in range(JAW_STEPS):
            quad_points = [points[k, a], points[j, a], points[j, a + 1], points[k, a + 1]]
            quad_normals = []
            for angle in (angles[a], angles[a], angles[a + 1], angles[a + 1]):
                # Behind the nose (+depth) is -normal(angle) in the plane.
                plan = -edge_normal[0] * end.normal(angle)
                world = end.place(plan[None])[0] - end.mouth
                quad_normals.append((world[0], world[1], edge_normal[1]))
            for q in (0, 1, 2, 0, 2, 3):
                positions.append(quad_points[q])
                normals.append(quad_normals[q])
    # The face: the profile laid flat where the rounding ends, facing the pocket.
    face = points[:, -1]
    outward = end.place(end.normal(end.turn)[None])[0] - end.mouth
    for k in range(1, count - 1):
        for q in (0, k, k + 1):
            positions.append(face[q])
            normals.append((outward[0], outward[1], 0.0))
    normal_array = np.array(normals)
    normal_array /= np.linalg.norm(normal_array, axis=1, keepdims=True)
    mesh.add(np.array(positions), normal_array, CUSHION_GREEN)


def _ring_rects(
    low: tuple[float, float],
    high: tuple[float, float],
    inner_low: tuple[float, float],
    inner_high: tuple[float, float],
) -> list[Rect]:
    """The band between an outer rectangle and an inner one, as eight rectangles (four
    corners, four sides) that meet corner to corner, as the inner one meets them."""
    xs = (low[0], inner_low[0], inner_high[0], high[0])
    ys = (low[1], inner_low[1], inner_high[1], high[1])
    return [
        (xs[i], ys[j], xs[i + 1], ys[j + 1]) for i in range(3) for j in range(3) if (i, j) != (1, 1)
    ]


def bed_rects(shape: TableShape) -> list[Rect]:
    """The bed under the table's whole top: first the cloth, to the cushions' feet,
    then the eight pieces of the band around it (under the cushions and the rail)."""
    length, width, outer, foot = shape.length, shape.width, shape.outer, CUSHION_FOOT
    cloth: Rect = (-foot, -foot, length + foot, width + foot)
    band = _ring_rects(
        (-outer, -outer),
        (length + outer, width + outer),
        (-foot, -foot),
        (length + foot, width + foot),
    )
    return [cloth, *band]


def build_table(shape: TableShape, pockets: PocketShapes | None = None) -> Mesh:
    """Cloth bed, cushions with a nose, wooden rails with sights, apron and legs; with
    `pockets`, the six holes cut through the bed (TableShape.pocket_lip wider: the lip
    and liner below are billiards.stage.pocket_mesh's) and the rail, and the cushions
    stopping at the mouths. Without, no hole anywhere."""
    mesh = Mesh()
    length, width = shape.length, shape.width
    cw, outer, top, bottom = shape.cushion_width, shape.outer, shape.rail_top, shape.rail_bottom
    cuts = pocket_cuts(shape, pockets) if pockets is not None else []
    holes = [cut.hole for cut in cuts]

    # The bed at z = 0 under the whole top: green cloth to the cushions' feet, and
    # beyond (under the cushions and rails, seen only inside a pocket's opening) the
    # dark leather of the pocket's shelf.
    # One mesh for both, so that they meet without cracks.
    lipped = [(x, y, radius + shape.pocket_lip) for x, y, radius in holes]
    pieces = holed_surface(bed_rects(shape), lipped)
    flat_surface(mesh, pieces[0], 0.0, CLOTH_GREEN)
    flat_surface(mesh, np.concatenate(pieces[1:]), 0.0, POCKET_LEATHER)

    for run in cushion_runs(shape, pockets):
        cushion(mesh, shape, run)

    # The rail: its top (cut open at each pocket), its outer sides and underside, the
    # face behind the cushions, and the leather-faced wall of each pocket's cut.
    inner_low, inner_high = np.array((-cw, -cw)), np.array((length + cw, width + cw))
    rail_cuts = [cut.rail for cut in cuts]
    rail_rects = _ring_rects(
        (-outer, -outer), (length + outer, width + outer), (-cw, -cw), (length + cw, width + cw)
    )
    flat_surface(mesh, np.concatenate(holed_surface(rail_rects, rail_cuts)), top, RAIL_WOOD)
    x0, y0, x1, y1 = -outer, -outer, length + outer, width + outer
    flat_surface(
        mesh,
        np.array([[(x0, y0), (x1, y0), (x1, y1)], [(x0, y0), (x1, y1), (x0, y1)]]),
        bottom,
        RAIL_WOOD,
        up=False,
    )
    outside = [
        ((x0, y0), (x1, y0), (0.0, -1.0, 0.0)),
        ((x1, y0), (x1, y1), (1.0, 0.0, 0.0)),
        ((x1, y1), (x0, y1), (0.0, 1.0, 0.0)),
        ((x0, y1), (x0, y0), (-1.0, 0.0, 0.0)),
    ]
    for (ax, ay), (bx, by), normal in outside:
        quad(
            mesh,
            np.array([(ax, ay, bottom), (bx, by, bottom), (bx, by, top), (ax, ay, top)]),
            normal,
            RAIL_WOOD,
        )
    inner = np.array(
        [(-cw, -cw), (length + cw, -cw), (length + cw, width + cw), (-cw, width + cw), (-cw, -cw)]
    )
    middle = np.array((length / 2, width / 2))
    for a, b in itertools.pairwise(inner):
        wall(mesh, segment_outside_circles(a, b, rail_cuts), 0.0, top, middle, RAIL_WOOD)
    for x, y, radius in rail_cuts:
        arc = segments_outside_rect(
            circle_points((x, y), radius, 2 * HOLE_SEGMENTS), inner_low, inner_high
        )
        wall(mesh, arc, 0.0, top, np.array((x, y)), POCKET_LEATHER)

    # Under the rails, the apron (the table's body), slightly set back, with a
    # moulding round its foot, proud of it.
    inset = 0.02
    box(
        mesh,
        (-outer + inset, -outer + inset, shape.apron_bottom),
        (length + outer - inset, width + outer - inset, bottom),
        APRON_WOOD,
    )
    proud = inset - 0.008
    box(
        mesh,
        (-outer + proud, -outer + proud, shape.apron_bottom),
        (length + outer - proud, width + outer - proud, shape.apron_bottom + 0.028),
        RAIL_WOOD,
    )

    # Sights: small pearl diamonds inlaid in the rail tops, each in a dark setting
    # (flush: a fraction of a millimetre over the wood only against depth fighting).
    for x, y, along_x in shape.sights():
        for lift, grow, material in (
            (0.0002, SIGHT_BAND, SIGHT_SETTING),
            (0.0003, 0.0, SIGHT_PEARL),
        ):
            along, across = (half + grow for half in SIGHT_HALF)
            a_, b_ = (along, across) if along_x else (across, along)
            z = top + lift
            corners = np.array([(x - a_, y, z), (x, y - b_, z), (x + a_, y, z), (x, y + b_, z)])
            quad(mesh, corners, (0.0, 0.0, 1.0), material)

    # Legs: four turned posts under the apron's corners.
    leg = 0.075
    for x in (-outer + 0.16, length + outer - 0.16):
        for y in (-outer + 0.16, width + outer - 0.16):
            cylinder(
                mesh,
                (x, y, shape.floor),
                shape.apron_bottom - shape.floor,
                leg,
                leg * 0.75,
                LEG_WOOD,
                20,
            )
            box(
                mesh,
                (x - leg - 0.01, y - leg - 0.01, shape.floor),
                (x + leg + 0.01, y + leg + 0.01, shape.floor + 0.06),
                LEG_WOOD,
            )
    return mesh


# --- the room and the lamp ---------------------------------------------------------------


@dataclass(frozen=True)
class Lamp:
    """The fixture over the table: a long canopy with three glowing shades."""

    centre: tuple[float, float, float]
    length: float = 1.35
    height: float = 0.95  # bottom of the shades above the cloth
    spacing: float = 0.55  # between the shades' centres, along x

    def light_positions(self) -> list[tuple[float, float, float]]:
        cx, cy, _ = self.centre
        z = self.height + 0.02
        return [(cx + k * self.spacing, cy, z) for k in (-1, 0, 1)]


def build_lamp(lamp: Lamp, ceiling: float) -> Mesh:
    mesh = Mesh()
    cx, cy, _ = lamp.centre
    z0 = lamp.height
    # Canopy bar that carries the shades, hung from the ceiling by two rods.
    bar_z = z0 + 0.17
    box(
        mesh,
        (cx - lamp.length / 2, cy - 0.035, bar_z),
        (cx + lamp.length / 2, cy + 0.035, bar_z + 0.05),
        LAMP_SHADE,
    )
    for k in (-1, 1):
        x = cx + k * lamp.length * 0.35
        box(
            mesh,
            (x - 0.006, cy - 0.006, bar_z + 0.05),
            (x + 0.006, cy + 0.006, ceiling),
            LAMP_BRASS,
        )
    for lx, ly, _ in lamp.light_positions():
        cylinder(mesh, (lx, ly, z0), 0.16, 0.19, 0.06, LAMP_SHADE, segments=32)
        cylinder(mesh, (lx, ly, z0 + 0.16), 0.012, 0.04, 0.04, LAMP_BRASS, segments=16)
        # The glowing diffuser closing the shade's mouth, facing down.
        glow = Mesh()
        disc(glow, (lx, ly, z0 - 0.001), 0.18, LAMP_GLOW, segments=32)
        glow.normals[:] = (0.0, 0.0, -1.0)
        mesh.extend(glow)
    return mesh


@dataclass(frozen=True)
class Room:
    centre: tuple[float, float]
    half_x: float = 4.2
    half_y: float = 3.4
    floor: float = -0.79
    ceiling: float = 2.25
    wainscot: float = 0.95  # height of the wooden panelling above the floor

    @classmethod
    def around(cls, length: float, width: float, floor: float) -> Room:
        """The room about a table of this size: 8.4 x 6.8 m, and 3 m or more of floor
        beyond each end and 2.8 m beyond each side of a larger table (a 12-ft one)."""
        return cls(
            (length / 2, width / 2),
            half_x=max(4.2, length / 2 + 3.0),
            half_y=max(3.4, width / 2 + 2.8),
            floor=floor,
        )


def build_room(room: Room) -> Mesh:
    """Floor and four walls with panelling, facing inwards (the ceiling: build_ceiling)."""
    mesh = Mesh()
    cx, cy = room.centre
    x0, x1 = cx - room.half_x, cx + room.half_x
    y0, y1 = cy - room.half_y, cy + room.half_y
    f, c, w = room.floor, room.ceiling, room.floor + room.wainscot
    quad(
        mesh,
        np.array([(x0, y0, f), (x1, y0, f), (x1, y1, f), (x0, y1, f)], dtype=np.float64),
        (0, 0, 1),
        FLOOR_WOOD,
    )
    walls = [
        ((x0, y1), (x1, y1), (0.0, -1.0, 0.0)),
        ((x1, y0), (x0, y0), (0.0, 1.0, 0.0)),
        ((x0, y0), (x0, y1), (1.0, 0.0, 0.0)),
        ((x1, y1), (x1, y0), (-1.0, 0.0, 0.0)),
    ]
    for (ax, ay), (bx, by), normal in walls:
        for low, high, material in ((f, w, WAINSCOT), (w, c, WALL_PAINT)):
            corners = np.array(
                [(ax, ay, low), (bx, by, low), (bx, by, high), (ax, ay, high)], dtype=np.float64
            )
            quad(mesh, corners, normal, material)
    return mesh


def build_ceiling(room: Room) -> Mesh:
    """The ceiling, facing down: drawn apart from the room, so that a camera above it
    (an overhead view of a long table) can leave it out, as it leaves out the lamp."""
    mesh = Mesh()
    cx, cy = room.centre
    x0, x1 = cx - room.half_x, cx + room.half_x
    y0, y1 = cy - room.half_y, cy + room.half_y
    c = room.ceiling
    quad(
        mesh,
        np.array([(x0, y0, c), (x0, y1, c), (x1, y1, c), (x1, y0, c)], dtype=np.float64),
        (0, 0, -1),
        CEILING,
    )
    return mesh


def load_table_mesh(path: str | Path) -> Mesh:
    """A user's own table, read with trimesh: metres, table frame, z up, cloth z = 0.

    Vertex or face colours in the file are used when present; otherwise the table
    is drawn in the rail's wood.
    """
    import trimesh  # only for a mesh of one's own (its import alone takes 0.4 s)

    try:
        loaded = trimesh.load_mesh(str(path), process=False)
    except Exception as error:  # trimesh raises many kinds for unreadable files
        raise ValueError(f"{path}: cannot read the table mesh ({error})") from None
    if isinstance(loaded, trimesh.Scene):
        parts = [g for g in loaded.dump() if isinstance(g, trimesh.Trimesh)]
        loaded = trimesh.util.concatenate(parts) if parts else None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise ValueError(f"{path}: no triangles in the table mesh")
    faces = np.asarray(loaded.faces)
    vertices = np.asarray(loaded.vertices, dtype=np.float64)
    positions = vertices[faces].reshape(-1, 3)
    normals = np.repeat(np.asarray(loaded.face_normals, dtype=np.float64), 3, axis=0)
    mesh = Mesh()
    mesh.add(positions, normals, RAIL_WOOD)
    visual: Any = loaded.visual
    kind = getattr(visual, "kind", None)
    if kind in ("vertex", "face"):
        if kind == "vertex":
            rgb = np.asarray(visual.vertex_colors, dtype=np.float64)[faces].reshape(-1, 4)[:, :3]
        else:
            rgb = np.repeat(np.asarray(visual.face_colors, dtype=np.float64)[:, :3], 3, axis=0)
        mesh.colours = srgb_to_linear(rgb / 255.0)
        mesh.materials[:, 3] = PLAIN
    return mesh
