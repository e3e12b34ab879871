"""What each ball looks like: its colour and whether it is striped.

Shared by the film's renderer and the top-view picture. The object balls follow
the usual pool set: 1-7 solids, 8 black, 9-15 stripes in the colours of 1-7. An id
that names a colour (a carom set's "white", "yellow" and "red"; a snooker set's
"green", "brown", "blue", "pink", "black"; in any case) is that colour, plain and
unlabelled. Any other id gets a colour of its own from a hash of the id (the same on
every run).
"""

from __future__ import annotations

import colorsys
import hashlib
from dataclasses import dataclass

RGB = tuple[int, int, int]

CUE_WHITE: RGB = (245, 242, 228)  # slightly warm, like a real cue ball
STRIPE_WHITE: RGB = CUE_WHITE

# The colours of the solids 1..7; stripe n + 8 has the colour of solid n.
SUIT: dict[int, RGB] = {
    1: (247, 196, 22),  # yellow
    2: (24, 64, 178),  # blue
    3: (214, 36, 34),  # red
    4: (92, 38, 142),  # purple
    5: (242, 112, 24),  # orange
    6: (10, 110, 58),  # green, darker than the cloth
    7: (128, 26, 36),  # maroon
}
EIGHT_BLACK: RGB = (22, 22, 24)

# Balls named for their colour: a carom set (white, yellow, red) and a snooker set.
NAMED: dict[str, RGB] = {
    "white": CUE_WHITE,
    "yellow": (250, 204, 24),
    "red": (204, 22, 30),
    "green": (16, 122, 64),
    "brown": (112, 62, 30),
    "blue": (28, 74, 196),
    "pink": (240, 128, 168),
    "black": EIGHT_BLACK,
    "orange": SUIT[5],
    "purple": SUIT[4],
}


@dataclass(frozen=True)
class BallColor:
    rgb: RGB  # 0-255; for a stripe, the colour of its band
    striped: bool  # white with a coloured band around the middle


def ball_color(ball_id: str) -> BallColor:
    """The look of a ball by id: "cue", "1".."15", a colour's name, or anything else
    (a hashed colour)."""
    if ball_id == "cue":
        return BallColor(CUE_WHITE, striped=False)
    if ball_id.lower() in NAMED:
        return BallColor(NAMED[ball_id.lower()], striped=False)
    if ball_id.isascii() and ball_id.isdigit():  # "²" is a digit int() refuses
        number = int(ball_id)
        if number == 8:
            return BallColor(EIGHT_BLACK, striped=False)
        if 1 <= number <= 7:
            return BallColor(SUIT[number], striped=False)
        if 9 <= number <= 15:
            return BallColor(SUIT[number - 8], striped=True)
    return BallColor(_hashed_rgb(ball_id), striped=False)


def ball_label(ball_id: str) -> str:
    """The text printed on a ball: its id, nothing on the cue ball or on a ball named
    for its colour."""
    return "" if ball_id == "cue" or ball_id.lower() in NAMED else ball_id


def _hashed_rgb(ball_id: str) -> RGB:
    """A saturated mid-bright colour from a stable hash (Python's hash() is salted)."""
    digest = hashlib.sha256(ball_id.encode("utf-8")).digest()
    hue = digest[0] / 256.0
    saturation = 0.55 + 0.35 * digest[1] / 255.0
    value = 0.65 + 0.3 * digest[2] / 255.0
    red, green, blue = colorsys.hsv_to_rgb(hue, saturation, value)
    return (round(red * 255), round(green * 255), round(blue * 255))
