"""Facts about the top-view picture (billiards.plot) and the ball colours it uses."""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from billiards.pictures.top_view import CLOTH, Layout, draw_top_view, save_picture
from billiards.record.trajectory import Event, Trajectory
from billiards.stage.ball_colors import ball_color, ball_label
from tests.commands import run_module

RADIUS = 0.0286
TABLE = (2.13, 1.065)
WIDTH_PX = 800


def hand_made_break() -> Trajectory:
    """Straight legs between waypoints: the cue ball hits the 1, the 1 and 11 meet cushions."""
    legs = {
        "cue": [(0.0, (0.5325, 0.5325)), (0.6, (1.5975 - 2 * RADIUS, 0.5325)), (1.2, (1.3, 0.3))],
        "1": [(0.6, (1.5975, 0.5325)), (1.8, (2.13 - RADIUS, 0.8)), (2.6, (1.7, 0.8))],
        "11": [(0.0, (1.0, 0.2)), (1.5, (1.8, 1.065 - RADIUS)), (2.5, (2.0, 0.6))],
        "8": [(0.0, (0.3, 0.9))],
    }
    times = np.arange(-0.25, 3.0, 1 / 240)
    positions = np.full((len(times), len(legs), 3), RADIUS)
    for n, waypoints in enumerate(legs.values()):
        when = [t for t, _ in waypoints]
        for k in range(2):
            positions[:, n, k] = np.interp(times, when, [p[k] for _, p in waypoints])
    orientations = np.zeros((len(times), len(legs), 4))
    orientations[..., 3] = 1.0
    events = (
        Event(0.6, "ball", ("cue", "1"), 2.0),
        Event(1.5, "cushion", ("11",), 1.0),
        Event(1.8, "cushion", ("1",), 1.0),
    )
    return Trajectory(
        tuple(legs), RADIUS, TABLE, times, positions, orientations, events, rest_time=2.6
    )


def top_view_size(table_size: tuple[float, float], width_px: int) -> tuple[int, int]:
    """The picture's (width, height) in pixels for a table of this size."""
    layout = Layout.fit(table_size, width_px)
    return layout.width, layout.height


def pixel(image: Image.Image, x: float, y: float) -> np.ndarray:
    column, row = Layout.fit(TABLE, image.width).to_pixels(np.array(x), np.array(y))
    return np.asarray(image.getpixel((round(float(column)), round(float(row)))), dtype=float)


def differs_from_cloth(colour: np.ndarray) -> bool:
    return bool(np.max(np.abs(colour - np.array(CLOTH))) > 30)


@pytest.fixture(scope="module")
def picture() -> Image.Image:
    return draw_top_view(hand_made_break(), WIDTH_PX, "hand-made")


def test_picture_has_the_requested_width_and_the_table_aspect(picture: Image.Image) -> None:
    assert picture.mode == "RGB"
    assert picture.size == top_view_size(TABLE, WIDTH_PX)
    assert picture.width == WIDTH_PX
    assert 0.5 * WIDTH_PX < picture.height < 0.75 * WIDTH_PX


def test_path_is_drawn_where_a_ball_travelled(picture: Image.Image) -> None:
    for x in (0.8, 1.0, 1.2):  # the cue ball's first leg, along y = W/2
        assert differs_from_cloth(pixel(picture, x, 0.5325))
    start, end = np.array([1.5975 - 2 * RADIUS, 0.5325]), np.array([1.3, 0.3])
    middle = 0.5 * (start + end)  # the cue ball's second leg, after the contact
    assert differs_from_cloth(pixel(picture, *middle))


def test_untouched_cloth_stays_cloth_coloured(picture: Image.Image) -> None:
    for x, y in ((0.3, 0.2), (1.0, 0.9), (0.15, 0.5)):
        assert np.max(np.abs(pixel(picture, x, y) - np.array(CLOTH))) <= 3


def test_ball_is_drawn_where_it_came_to_rest(picture: Image.Image) -> None:
    # The 1 rests at (1.7, 0.8): its yellow shows half a radius off its white number spot.
    colour = pixel(picture, 1.7 + 0.75 * RADIUS, 0.8)
    assert np.max(np.abs(colour - np.array(ball_color("1").rgb))) < 40


def test_striped_ball_path_alternates_colour_and_white(picture: Image.Image) -> None:
    # The 11 (red stripe) runs from (1.0, 0.2) to (1.8, W - r): sample along that leg.
    red = np.array(ball_color("11").rgb, dtype=float)
    rise = 1.065 - RADIUS - 0.2
    samples = [pixel(picture, 1.0 + 0.8 * s, 0.2 + rise * s) for s in np.linspace(0.2, 0.8, 60)]
    reddish = sum(np.max(np.abs(c - red)) < 60 for c in samples)
    whitish = sum(np.min(c) > 180 for c in samples)
    assert reddish >= 5 and whitish >= 5


def test_lead_in_before_the_shot_is_left_out() -> None:
    trajectory = hand_made_break()
    early = trajectory.positions.copy()
    early[trajectory.times < 0, 0, 1] = 0.15  # before t = 0 the cue ball was elsewhere
    moved = draw_top_view(
        Trajectory(
            trajectory.ball_ids,
            RADIUS,
            TABLE,
            trajectory.times,
            early,
            trajectory.orientations,
            trajectory.events,
            trajectory.rest_time,
        ),
        WIDTH_PX,
    )
    assert not differs_from_cloth(pixel(moved, 0.5325, 0.3))


def test_png_is_written_whole_with_no_temporary_left(tmp_path: Path, picture: Image.Image) -> None:
    path = tmp_path / "break.png"
    save_picture(picture, path)
    with Image.open(path) as written:
        assert written.size == picture.size
    assert [p.name for p in tmp_path.iterdir()] == ["break.png"]


def test_stripes_share_the_colour_of_their_solid() -> None:
    for number in range(1, 8):
        solid, stripe = ball_color(str(number)), ball_color(str(number + 8))
        assert solid.rgb == stripe.rgb
        assert not solid.striped and stripe.striped
    assert not ball_color("8").striped and max(ball_color("8").rgb) < 50
    assert min(ball_color("cue").rgb) > 200 and ball_label("cue") == ""


def test_unknown_ball_gets_the_same_colour_on_every_run() -> None:
    assert ball_color("ghost").rgb == (237, 37, 140)  # sha256-based, not Python's salted hash
    assert ball_color("ghost") == ball_color("ghost")
    assert ball_color("ghost").rgb != ball_color("phantom").rgb


def run_plot(*args: str) -> subprocess.CompletedProcess[str]:
    return run_module("billiards.plot", *args, timeout=60)


def test_plot_command_with_a_bad_scene_exits_2_with_one_line_and_no_file(tmp_path: Path) -> None:
    scene = tmp_path / "bad.toml"
    scene.write_text("[table]\nlength = -1\n", encoding="utf-8")
    output = tmp_path / "out.png"
    done = run_plot(str(scene), "-o", str(output))
    assert done.returncode == 2
    assert done.stderr.startswith("error: ")
    assert len(done.stderr.strip().splitlines()) == 1
    assert "table.length" in done.stderr
    assert not output.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["bad.toml"]


def test_plot_command_with_a_missing_scene_exits_2(tmp_path: Path) -> None:
    done = run_plot(str(tmp_path / "nowhere.toml"), "-o", str(tmp_path / "out.png"))
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "out.png").exists()


@pytest.mark.long
def test_plot_command_draws_a_simulated_scene_at_the_requested_width(tmp_path: Path) -> None:
    scene = tmp_path / "two.toml"
    scene.write_text(
        '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [1.5, 0.2]\n'
        '[[ball]]\nid = "1"\nposition = [1.2, 0.55]\n',
        encoding="utf-8",
    )
    output = tmp_path / "two.png"
    done = run_plot(str(scene), "-o", str(output), "--width", "640", "--quiet")
    assert done.returncode == 0, done.stderr
    assert done.stdout == ""
    with Image.open(output) as picture:
        assert picture.size == top_view_size(TABLE, 640)
        rgb = picture.convert("RGB")
        assert differs_from_cloth(pixel(rgb, 0.8, 0.5 + 0.3 * 0.2 / 1.5))  # the cue ball's path


def test_a_ball_id_that_is_a_non_ascii_digit_gets_a_colour() -> None:
    from billiards.stage.ball_colors import ball_color

    assert ball_color("²") == ball_color("²")  # hashed, not int("²")


def test_a_ball_in_the_air_is_dotted_over_its_flight_and_nowhere_else() -> None:
    """The 1's first leg is made a hop (its centre above the cloth between 0.6 and 1.2 s,
    a parabola): white dots appear over that stretch of its yellow path, none over the
    stretch after it, and the picture of the break on the cloth is unchanged."""
    trajectory = hand_made_break()
    flying = trajectory.positions.copy()
    hop = (trajectory.times > 0.6) & (trajectory.times < 1.2)
    share = (trajectory.times[hop] - 0.6) / 0.6
    flying[hop, 1, 2] = RADIUS + 0.4 * share * (1.0 - share)  # 10 cm at its top
    jumped = draw_top_view(
        Trajectory(
            trajectory.ball_ids,
            RADIUS,
            TABLE,
            trajectory.times,
            flying,
            trajectory.orientations,
            trajectory.events,
            rest_time=trajectory.rest_time,
        ),
        WIDTH_PX,
        "hand-made",
    )
    flat = np.asarray(draw_top_view(trajectory, WIDTH_PX, "hand-made"), dtype=float)
    changed = np.any(np.asarray(jumped, dtype=float) != flat, axis=2)
    layout = Layout.fit(TABLE, WIDTH_PX)

    def changed_near(time: float) -> bool:
        x, y = (np.interp(time, trajectory.times, trajectory.positions[:, 1, k]) for k in (0, 1))
        column, row = layout.to_pixels(np.array(x), np.array(y))
        around = changed[round(float(row)) - 6 : round(float(row)) + 7]
        return bool(around[:, round(float(column)) - 6 : round(float(column)) + 7].any())

    assert all(changed_near(time) for time in (0.75, 0.9, 1.05))  # the hop's dots
    assert not any(changed_near(time) for time in (1.5, 1.7))  # the leg on the cloth
    assert changed[-layout.footer :].any()  # the legend's "in the air"
