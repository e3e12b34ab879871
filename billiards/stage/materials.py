"""The surfaces' materials: linear RGB colours from display ones, and the named
materials of the table, the room and the lamp (the shaders light in linear space and
encode for display)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

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
