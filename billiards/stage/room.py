"""The room round the table and the lamp over it, as numpy triangle meshes, and the
light they give (the lamp's spots and the room's fill)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from billiards.stage import materials
from billiards.stage.meshes import Mesh, box, cylinder, disc, quad, upright_quads

Colour = tuple[float, float, float]
# cos of the lamp shades' cut-off: a pool of light on the cloth, falling off towards
# the rails and the corners (lighting.glsl's smoothstep runs from here to nearly 1).
SPOT_CONE = 0.62
LIGHTS = 4  # lighting.glsl's: the lamp's three spots and the room's fill


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
        materials.LAMP_SHADE,
    )
    for k in (-1, 1):
        x = cx + k * lamp.length * 0.35
        box(
            mesh,
            (x - 0.006, cy - 0.006, bar_z + 0.05),
            (x + 0.006, cy + 0.006, ceiling),
            materials.LAMP_BRASS,
        )
    for lx, ly, _ in lamp.light_positions():
        cylinder(mesh, (lx, ly, z0), 0.16, 0.19, 0.06, materials.LAMP_SHADE, segments=32)
        cylinder(mesh, (lx, ly, z0 + 0.16), 0.012, 0.04, 0.04, materials.LAMP_BRASS, segments=16)
        # The glowing diffuser closing the shade's mouth, facing down.
        glow = Mesh()
        disc(glow, (lx, ly, z0 - 0.001), 0.18, materials.LAMP_GLOW, segments=32)
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
        materials.FLOOR_WOOD,
    )
    walls = [
        ((x0, y1), (x1, y1), (0.0, -1.0, 0.0)),
        ((x1, y0), (x0, y0), (0.0, 1.0, 0.0)),
        ((x0, y0), (x0, y1), (1.0, 0.0, 0.0)),
        ((x1, y1), (x1, y0), (-1.0, 0.0, 0.0)),
    ]
    upright_quads(mesh, walls, [(f, w, materials.WAINSCOT), (w, c, materials.WALL_PAINT)])
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
        materials.CEILING,
    )
    return mesh


@dataclass(frozen=True)
class Lighting:
    """The lamp's three spots, a dim fill under the ceiling, and the ambient light."""

    positions: tuple[Colour, ...]  # m
    colours: tuple[Colour, ...]  # linear RGB, irradiance at 1 m
    cones: tuple[float, ...]
    ambient_sky: Colour = (0.06, 0.056, 0.05)
    ambient_ground: Colour = (0.015, 0.02, 0.015)
    light_radius: float = 0.12  # m: the size of each shade's glowing mouth

    def __post_init__(self) -> None:
        # lighting.glsl: LIGHTS lights, the last the all-round fill, the others spots.
        if len(self.positions) != LIGHTS or min(self.cones[:-1]) < -0.5 < self.cones[-1]:
            raise ValueError(f"expected {LIGHTS - 1} spots and then the fill: {self.cones}")

    @classmethod
    def over(cls, lamp: Lamp, room: Room) -> Lighting:
        """Warm spots in the lamp's shades, and a dimmer fill for the room around."""
        spots = lamp.light_positions()
        spot: Colour = (0.95, 0.855, 0.72)
        fill: Colour = (2.2, 2.05, 1.9)
        cx, cy = room.centre
        return cls(
            positions=(*spots, (cx, cy, room.ceiling - 0.2)),
            colours=(*(spot for _ in spots), fill),
            cones=(*(SPOT_CONE for _ in spots), -1.0),
        )
