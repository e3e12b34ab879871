"""Facts about ball colours by name: a ball whose id names a colour (a carom set's
white, yellow and red, a snooker set's colours) is drawn in that colour, in the film's
texture and in the top view, and carries no label."""

from __future__ import annotations

import colorsys

import numpy as np
import pytest
from PIL import Image

from billiards.pictures.top_view import Layout, draw_top_view
from billiards.record.trajectory import Trajectory
from billiards.stage.ball_colors import RGB, ball_color, ball_label
from billiards.stage.textures import ball_texture

RADIUS = 0.03075
TABLE = (2.84, 1.42)
CAROM = {"white": (0.5, 0.7), "yellow": (1.4, 0.7), "red": (2.3, 0.7)}


def hue_and_saturation(rgb: RGB | np.ndarray) -> tuple[float, float, float]:
    """Hue in degrees, saturation and value (0-1) of an sRGB colour (0-255)."""
    red, green, blue = (float(c) / 255.0 for c in rgb)
    hue, saturation, value = colorsys.rgb_to_hsv(red, green, blue)
    return 360.0 * hue, saturation, value


def looks(rgb: RGB | np.ndarray, name: str) -> bool:
    """Whether a colour reads as `name` (white, yellow or red) to an eye."""
    hue, saturation, value = hue_and_saturation(rgb)
    if name == "white":
        return saturation < 0.15 and value > 0.8
    if name == "yellow":
        return 40.0 <= hue <= 65.0 and saturation > 0.6 and value > 0.7
    if name == "red":
        return (hue <= 12.0 or hue >= 348.0) and saturation > 0.6 and value > 0.5
    raise ValueError(name)


@pytest.mark.parametrize("name", ["white", "yellow", "red"])
def test_a_carom_ball_is_the_colour_it_is_named(name: str) -> None:
    assert looks(ball_color(name).rgb, name), ball_color(name)
    assert looks(ball_color(name.capitalize()).rgb, name)  # "Red" as "red"
    assert not ball_color(name).striped and ball_label(name) == ""


def test_a_snooker_set_is_coloured_by_name() -> None:
    names = ("red", "yellow", "green", "brown", "blue", "pink", "black")
    colours = {ball_color(name).rgb for name in names}
    assert len(colours) == len(names)
    assert max(ball_color("black").rgb) < 50
    green_hue, _, _ = hue_and_saturation(ball_color("green").rgb)
    blue_hue, _, _ = hue_and_saturation(ball_color("blue").rgb)
    assert 90 <= green_hue <= 170 and 200 <= blue_hue <= 250


@pytest.mark.parametrize("name", ["white", "yellow", "red"])
def test_the_films_ball_texture_is_the_named_colour_without_a_label(name: str) -> None:
    texture = ball_texture(name, 128)[..., :3].reshape(-1, 3)
    # One colour all over: no label disc, no marks.
    assert np.all(np.max(np.abs(texture.astype(int) - texture[0].astype(int)), axis=1) <= 2)
    assert looks(texture[0], name)


def carom_at_rest() -> Trajectory:
    times = np.array([0.0, 0.5])
    positions = np.full((len(times), len(CAROM), 3), RADIUS)
    for index, (x, y) in enumerate(CAROM.values()):
        positions[:, index, :2] = (x, y)
    orientations = np.zeros((len(times), len(CAROM), 4))
    orientations[..., 3] = 1.0
    return Trajectory(tuple(CAROM), RADIUS, TABLE, times, positions, orientations, (), 0.0)


def test_the_top_view_draws_carom_balls_in_their_named_colours() -> None:
    picture: Image.Image = draw_top_view(carom_at_rest(), 800)
    layout = Layout.fit(TABLE, picture.width)
    for name, (x, y) in CAROM.items():
        # Half a radius off the centre: where a label's spot would be, the ball's colour.
        column, row = layout.to_pixels(np.array(x + 0.5 * RADIUS), np.array(y))
        colour = np.asarray(picture.getpixel((round(float(column)), round(float(row)))))
        assert looks(colour, name), (name, colour)
