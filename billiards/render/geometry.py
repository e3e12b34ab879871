"""The table, the room and the lamp as numpy triangle meshes (no GL here).

Frame: the physics frame. z is up, the cloth is z = 0 and the playing area is
[0, L] x [0, W] between the cushion noses. Every solid is built convex (boxes,
prisms, discs) so flat normals can be pointed away from its centre; the mesh data
is plain arrays, uploaded by billiards.render.renderer.

Colours are linear RGB (the shaders light in linear space and encode for display).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import trimesh

FloatArray = npt.NDArray[np.float64]

# Surface patterns the scene shader draws procedurally (in_material.w).
PLAIN, WOOD, PLANKS, CLOTH = 0.0, 1.0, 2.0, 3.0


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
APRON_WOOD = Material(linear_rgb("#4a220f"), specular=0.25, shininess=40.0, pattern=WOOD)
LEG_WOOD = Material(linear_rgb("#3e1c0c"), specular=0.2, shininess=40.0, pattern=WOOD)
SIGHT_PEARL = Material(linear_rgb("#f2ead8"), specular=0.8, shininess=120.0, emissive=0.15)
POCKET_HOLE = Material(linear_rgb("#050505"), specular=0.0)
POCKET_LEATHER = Material(linear_rgb("#1a1410"), specular=0.3, shininess=30.0)
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


def box(mesh: Mesh, low: tuple[float, ...], high: tuple[float, ...], material: Material) -> None:
    """An axis-aligned box from corner `low` to corner `high`, flat-shaded."""
    solid = trimesh.creation.box(bounds=np.array([low, high], dtype=np.float64))
    mesh.add(solid.triangles.reshape(-1, 3), np.repeat(solid.face_normals, 3, axis=0), material)


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
    profile = np.array([[radius_bottom, 0.0], [radius_top, height]])
    side = trimesh.creation.revolve(profile, sections=segments)
    triangles = side.triangles + np.array(bottom)  # (T, 3, 3)
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
    apron_bottom: float = -0.30
    floor: float = -0.79  # the cloth stands 79 cm above the floor
    corner_mouth: float = 0.082  # distance from the corner to each corner jaw's nose
    side_mouth: float = 0.064  # half the side pocket's mouth

    @property
    def outer(self) -> float:
        """From a cushion nose to the rail's outer edge."""
        return self.cushion_width + self.rail_width

    def pockets(self) -> list[tuple[float, float, float]]:
        """(x, y, hole radius) of the six pocket openings, as drawn on the rail."""
        length, width = self.length, self.width
        off = 0.026
        corner = 0.064
        side = 0.066
        return [
            (-off, -off, corner),
            (length + off, -off, corner),
            (-off, width + off, corner),
            (length + off, width + off, corner),
            (length / 2, -0.045, side),
            (length / 2, width + 0.045, side),
        ]

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


def _cushion_profile(shape: TableShape) -> list[tuple[float, float]]:
    """The cushion's cross-section as (distance behind the nose, height), convex."""
    cw = shape.cushion_width
    return [
        (cw, 0.0),
        (0.016, 0.0),
        (0.0, shape.nose_height - 0.006),
        (0.003, shape.nose_height + 0.002),
        (cw, shape.rail_top - 0.002),
    ]


def cushion(
    mesh: Mesh,
    shape: TableShape,
    origin: tuple[float, float],
    along: tuple[float, float],
    outward: tuple[float, float],
    span: tuple[float, float],
    jaw_slopes: tuple[float, float],
) -> None:
    """One cushion between two pockets: its profile swept along the nose line.

    span is where the nose starts and ends along `along`; behind the nose each end
    is cut back towards its pocket by `jaw_slopes` metres per metre (the jaws).
    """
    o = np.array([origin[0], origin[1], 0.0])
    t = np.array([along[0], along[1], 0.0])
    n = np.array([outward[0], outward[1], 0.0])
    profile = _cushion_profile(shape)
    corners = []
    for s_end in (0, 1):
        for depth, height in profile:
            s = span[0] - jaw_slopes[0] * depth if s_end == 0 else span[1] + jaw_slopes[1] * depth
            corners.append(o + s * t + depth * n + (0.0, 0.0, height))
    count = len(profile)
    faces = [list(range(count)), list(range(count, 2 * count))]
    for k in range(count):
        j = (k + 1) % count
        faces.append([k, j, count + j, count + k])
    convex_solid(mesh, np.array(corners), faces, CUSHION_GREEN)


def build_table(shape: TableShape) -> Mesh:
    """Cloth bed, cushions with a nose, wooden rails with sights, pockets, apron, legs."""
    mesh = Mesh()
    length, width = shape.length, shape.width
    cw, outer = shape.cushion_width, shape.outer

    # The cloth bed runs under the cushions.
    quad(
        mesh,
        np.array(
            [
                (-cw, -cw, 0),
                (length + cw, -cw, 0),
                (length + cw, width + cw, 0),
                (-cw, width + cw, 0),
            ],
            dtype=np.float64,
        ),
        (0.0, 0.0, 1.0),
        CLOTH_GREEN,
    )

    corner, side = shape.corner_mouth, shape.side_mouth
    half = length / 2
    for y0, out in ((0.0, -1.0), (width, 1.0)):
        cushion(mesh, shape, (0.0, y0), (1.0, 0.0), (0.0, out), (corner, half - side), (1.0, -0.35))
        cushion(
            mesh,
            shape,
            (0.0, y0),
            (1.0, 0.0),
            (0.0, out),
            (half + side, length - corner),
            (-0.35, 1.0),
        )
    for x0, out in ((0.0, -1.0), (length, 1.0)):
        cushion(
            mesh, shape, (x0, 0.0), (0.0, 1.0), (out, 0.0), (corner, width - corner), (1.0, 1.0)
        )

    # Rails: two long ones over the whole length, two short ones between them.
    top, bottom = shape.rail_top, -0.12
    box(mesh, (-outer, -outer, bottom), (length + outer, -cw, top), RAIL_WOOD)
    box(mesh, (-outer, width + cw, bottom), (length + outer, width + outer, top), RAIL_WOOD)
    box(mesh, (-outer, -cw, bottom), (-cw, width + cw, top), RAIL_WOOD)
    box(mesh, (length + cw, -cw, bottom), (length + outer, width + cw, top), RAIL_WOOD)

    # Under the rails, the apron (the table's body), slightly set back.
    inset = 0.02
    box(
        mesh,
        (-outer + inset, -outer + inset, shape.apron_bottom),
        (length + outer - inset, width + outer - inset, bottom),
        APRON_WOOD,
    )

    # Sights: small pearl diamonds set into the rail tops.
    for x, y, along_x in shape.sights():
        a, b = (0.014, 0.007) if along_x else (0.007, 0.014)
        z = top + 0.0006
        corners = np.array([(x - a, y, z), (x, y - b, z), (x + a, y, z), (x, y + b, z)])
        quad(mesh, corners, (0.0, 0.0, 1.0), SIGHT_PEARL)

    # Pockets: a leather rim and a dark opening over the rail and the jaws.
    for x, y, radius in shape.pockets():
        disc(mesh, (x, y, top + 0.0012), radius + 0.012, POCKET_LEATHER, inner=radius)
        disc(mesh, (x, y, top + 0.0012), radius, POCKET_HOLE)
        # The hole's throat, visible from low views: a dark cylinder below the rim.
        cylinder(mesh, (x, y, -0.09), top + 0.0011 + 0.09, radius, radius, POCKET_HOLE, segments=24)

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


def build_room(room: Room) -> Mesh:
    """Floor, four walls with panelling and a ceiling, all facing inwards."""
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
    quad(
        mesh,
        np.array([(x0, y0, c), (x0, y1, c), (x1, y1, c), (x1, y0, c)], dtype=np.float64),
        (0, 0, -1),
        CEILING,
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


def load_table_mesh(path: str | Path) -> Mesh:
    """A user's own table, read with trimesh: metres, table frame, z up, cloth z = 0.

    Vertex or face colours in the file are used when present; otherwise the table
    is drawn in the rail's wood.
    """

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
