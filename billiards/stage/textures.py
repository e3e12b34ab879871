"""The standard ball set, painted with Pillow and numpy as equirectangular textures.

Body frame of a ball (identity orientation at t = 0): the texture's poles are the
body y axis, so a stripe is the band around y and the two number discs sit on the
band at +z (facing up at the start) and -z. Texel (u, v) shows the body direction

    d = (cos(lat) cos(lon), sin(lat), cos(lat) sin(lon)),  lon = 2 pi u, lat = pi (v - 1/2)

and shaders/ball.frag looks it up with the same mapping. Edges are
anti-aliased analytically (one texel of smoothing); textures are cached per size.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import numpy.typing as npt
from PIL import Image, ImageDraw, ImageFont

from billiards.stage.ball_colors import CUE_WHITE, ball_color, ball_label

FloatArray = npt.NDArray[np.float64]

IVORY = CUE_WHITE
CUE_MARK = (200, 30, 40)
DISC_RADIUS = 0.42  # rad: the white number disc, about 24 mm across on a 57 mm ball
STRIPE_HALF_WIDTH = 0.56  # sin of the band's half-height: about 56% of the radius


@functools.lru_cache(maxsize=4)
def texel_directions(width: int, height: int) -> FloatArray:
    """Unit body-frame directions (height x width x 3) shown by each texel's centre
    (read-only: every ball's texture of a size shares them)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    lon = 2 * math.pi * u[None, :]
    lat = math.pi * (v[:, None] - 0.5)
    directions = np.stack(
        np.broadcast_arrays(np.cos(lat) * np.cos(lon), np.sin(lat), np.cos(lat) * np.sin(lon)),
        axis=-1,
    )
    directions.setflags(write=False)
    return directions


def _coverage(signed_distance: FloatArray, edge: float) -> FloatArray:
    """0 outside, 1 inside, a smooth one-texel ramp across the edge (distance < 0 inside)."""
    return np.clip(0.5 - signed_distance / edge, 0.0, 1.0)


@functools.lru_cache(maxsize=4)
def _digit_sheet(text: str, size: int) -> FloatArray:
    """Ink coverage (size x size, 0..1) of a ball number, centred, with 6 and 9 underlined."""
    image = Image.new("L", (size, size), 0)
    draw = ImageDraw.Draw(image)
    font_size = int(size * (0.62 if len(text) == 1 else 0.55))
    font = ImageFont.load_default(size=font_size)
    stroke = max(1, size // 48)
    box = draw.textbbox((0, 0), text, font=font, stroke_width=stroke)
    x = (size - (box[2] - box[0])) / 2 - box[0]
    y = (size - (box[3] - box[1])) / 2 - box[1]
    draw.text((x, y), text, fill=255, font=font, stroke_width=stroke, stroke_fill=255)
    if text in ("6", "9"):
        bottom = y + box[3] + size * 0.04
        draw.rectangle((size * 0.36, bottom, size * 0.64, bottom + size * 0.05), fill=255)
    return np.asarray(image, dtype=np.float64) / 255.0


def _sample(sheet: FloatArray, px: FloatArray, py: FloatArray) -> FloatArray:
    """Bilinear lookup of a square sheet at pixel coordinates, 0 outside."""
    size = sheet.shape[0]
    padded = np.pad(sheet, 1)
    x = np.clip(px + 0.5, 0.0, size + 0.999)
    y = np.clip(py + 0.5, 0.0, size + 0.999)
    x0 = np.floor(x).astype(np.int64)
    y0 = np.floor(y).astype(np.int64)
    fx, fy = x - x0, y - y0
    x1 = np.minimum(x0 + 1, size + 1)
    y1 = np.minimum(y0 + 1, size + 1)
    top = padded[y0, x0] * (1 - fx) + padded[y0, x1] * fx
    bottom = padded[y1, x0] * (1 - fx) + padded[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def _blend(base: FloatArray, colour: tuple[int, int, int], amount: FloatArray) -> FloatArray:
    return base * (1 - amount[..., None]) + np.array(colour, dtype=np.float64) * amount[..., None]


def _window(
    shape: tuple[int, ...], centre: tuple[float, float, float], radius: float
) -> tuple[slice, npt.NDArray[np.int64]]:
    """Rows and columns of the texels within `radius` (rad) of a body direction."""
    height, width = shape[0], shape[1]
    lat = math.asin(max(-1.0, min(1.0, centre[1])))
    lon = math.atan2(centre[2], centre[0])
    row0 = max(0, int((lat - radius) / math.pi * height + height / 2) - 1)
    row1 = min(height, int((lat + radius) / math.pi * height + height / 2) + 2)
    reach = math.pi / 2 - abs(lat) - radius
    if reach <= 0.05:
        return slice(row0, row1), np.arange(width)
    half = min(math.pi, radius / math.cos(abs(lat) + radius))
    col0 = int((lon - half) / (2 * math.pi) * width) - 1
    col1 = int((lon + half) / (2 * math.pi) * width) + 2
    return slice(row0, row1), np.arange(col0, col1) % width


def _paint_disc(
    image: FloatArray,
    d: FloatArray,
    centre: tuple[float, float, float],
    radius: float,
    colour: tuple[int, int, int],
    edge: float,
    text: str | None = None,
) -> None:
    """Paint, in place, a disc of `colour` around a unit body direction, with text on it."""
    rows, cols = _window(image.shape, centre, radius + 2 * edge)
    patch_d = d[rows][:, cols]
    c = np.array(centre, dtype=np.float64)
    cos_angle = patch_d @ c
    angle = np.arccos(np.clip(cos_angle, -1.0, 1.0))
    patch = _blend(image[rows][:, cols], colour, _coverage(angle - radius, edge))
    if text is not None:
        # The number on the tangent plane at the disc centre (gnomonic projection):
        # up is +y (the stripe band's axis), right is up x centre, seen from outside.
        up = np.array([0.0, 1.0, 0.0])
        right = np.cross(up, c)
        safe = np.maximum(cos_angle, 0.2)
        a = (patch_d @ right) / safe
        b = (patch_d @ up) / safe
        half = math.tan(radius) * 0.8
        size = 256
        ink = _sample(
            _digit_sheet(text, size), (a / (2 * half) + 0.5) * size, (0.5 - b / (2 * half)) * size
        )
        patch = _blend(patch, (20, 20, 20), np.where(cos_angle > 0.2, ink, 0.0))
    image[rows, cols] = patch


@functools.lru_cache(maxsize=64)
def ball_texture(ball_id: str, width: int = 512) -> npt.NDArray[np.uint8]:
    """RGBA (width/2 x width x 4, sRGB) texture of a ball, row 0 at v = 0.

    Colours come from billiards.stage.ball_colors (shared with the top-view picture):
    "1".."15" are the numbered set, "cue" is the white cue ball with six red marks
    so its roll shows, a ball named for a colour is plain, and any other id gets its
    own colour with its label.
    """
    height = width // 2
    d = texel_directions(width, height)
    edge = math.pi / height  # one texel, in radians on the sphere
    image = np.empty((height, width, 3))
    look = ball_color(ball_id)
    if ball_id == "cue":
        image[:] = IVORY
        marks = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
        for mark in marks:
            centre = (float(mark[0]), float(mark[1]), float(mark[2]))
            _paint_disc(image, d, centre, 0.11, CUE_MARK, edge)
    else:
        if look.striped:
            image[:] = IVORY
            band = np.abs(d[..., 1]) - STRIPE_HALF_WIDTH
            image = _blend(image, look.rgb, _coverage(band, edge))
        else:
            image[:] = look.rgb
        label = ball_label(ball_id)[:2]
        # A ball named for its colour (a carom or snooker ball) is plain, with no disc.
        for centre in ((0.0, 0.0, 1.0), (0.0, 0.0, -1.0)) if label else ():
            _paint_disc(image, d, centre, DISC_RADIUS, IVORY, edge, label)
    rgba = np.empty((height, width, 4), dtype=np.uint8)
    rgba[..., :3] = np.clip(np.rint(image), 0, 255).astype(np.uint8)
    rgba[..., 3] = 255
    rgba.setflags(write=False)
    return rgba
