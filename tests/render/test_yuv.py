"""A film's frames as yuv420p: the renderer's last GL pass converts the finished RGBA
picture (BT.709, limited range), ffmpeg encodes it as it is and tags it so, and the
film decodes to the picture that was drawn.

Skipped, with the reason, only where no OpenGL context can be made.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import moderngl
import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.trajectory import Trajectory
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.film import camera_poses, camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.render.gl.frame_output import Yuv420pPass
from billiards.render.gl.renderer import Renderer
from billiards.render.video import VideoWriter, frame_bytes
from billiards.scene.reader import load_scene
from billiards.scene.render_table import RenderSettings
from billiards.simulation import simulate_scene
from billiards.stage.cameras import CameraPose, Stage, preset_pose
from tests.render.fixtures import (
    bt709_yuv420p,
    decode_mp4,
    gl_context,  # noqa: F401 (the ctx fixture)
    rolling_trajectory,
    streams,
)

pytestmark = pytest.mark.gl

Image = npt.NDArray[np.uint8]
# Flat patches of BT.709's 100% colour bars, with their Y, Cb, Cr codes in limited
# range as the standard tabulates them (ITU-R BT.709, rounded).
BARS = {
    (255, 255, 255): (235, 128, 128),
    (0, 0, 0): (16, 128, 128),
    (255, 0, 0): (63, 102, 240),
    (0, 255, 0): (173, 42, 26),
    (0, 0, 255): (32, 240, 118),
    (255, 255, 0): (219, 16, 138),
    (0, 255, 255): (188, 154, 16),
    (255, 0, 255): (78, 214, 230),
}


def bars_and_gradient(width: int, height: int) -> Image:
    """The colour bars as 8-px-wide patches in the top half (each a different colour, so
    a flip or a plane mix-up shows), and a diagonal gradient of every channel below,
    with an odd row and column so 2x2 blocks straddle steps; alpha not 255, as drawn."""
    picture = np.zeros((height, width, 4), dtype=np.uint8)
    picture[..., 3] = 200
    colours = list(BARS)
    for column in range(width // 8):
        picture[: height // 2, 8 * column : 8 * column + 8, :3] = colours[column % len(colours)]
    y, x = np.mgrid[height // 2 : height, 0:width]
    picture[height // 2 :, :, 0] = (x * 255 // (width - 1)).astype(np.uint8)
    picture[height // 2 :, :, 1] = ((y - height // 2) * 255 // (height - height // 2 - 1)).astype(
        np.uint8
    )
    picture[height // 2 :, :, 2] = ((x + 3 * y) % 256).astype(np.uint8)
    picture[height // 2 + 1, 5::7, :3] = (250, 10, 130)
    return picture


def convert(ctx: moderngl.Context, picture: Image) -> Image:
    height, width = picture.shape[:2]
    texture = ctx.texture((width, height), 4, picture.tobytes())
    converter = Yuv420pPass(ctx, (width, height))
    try:
        return np.frombuffer(converter.convert(texture), dtype=np.uint8)
    finally:
        converter.release()
        texture.release()


@pytest.mark.parametrize("size", [(64, 36), (70, 38)])
def test_the_gl_conversion_is_bt709_limited_range_within_one_code(
    ctx: moderngl.Context, size: tuple[int, int]
) -> None:
    width, height = size
    picture = bars_and_gradient(width, height)
    converted = convert(ctx, picture)
    expected = bt709_yuv420p(picture)
    assert converted.shape == expected.shape == (width * height * 3 // 2,)
    assert np.abs(converted.astype(int) - expected).max() <= 1


def test_flat_colour_bars_get_the_codes_bt709_tabulates(ctx: moderngl.Context) -> None:
    width, height = 64, 32
    picture = bars_and_gradient(width, height)
    converted = convert(ctx, picture)
    luma = converted[: width * height].reshape(height, width)
    chroma = width * height // 4
    cb = converted[width * height : width * height + chroma].reshape(height // 2, width // 2)
    cr = converted[width * height + chroma :].reshape(height // 2, width // 2)
    for column, codes in enumerate(BARS.values()):
        x = 8 * column + 4  # the patch's middle: its 2x2 blocks are all of it
        got = (luma[height // 4, x], cb[height // 8, x // 2], cr[height // 8, x // 2])
        assert got == codes, (list(BARS)[column], got)


@pytest.fixture(scope="module")
def trajectory() -> Trajectory:
    return rolling_trajectory()


FILM_SIZE = (192, 108)


@pytest.fixture(scope="module")
def renderer(ctx: moderngl.Context, trajectory: Trajectory) -> Iterator[Renderer]:
    made = Renderer(ctx, trajectory, FILM_SIZE, antialias=4)
    yield made
    made.release()


def side_view(trajectory: Trajectory) -> CameraPose:
    return preset_pose("low_side", Stage.of(trajectory), FILM_SIZE[0] / FILM_SIZE[1])


@pytest.mark.parametrize(("time", "moving"), [(0.9, False), (0.2, False), (0.2, True)])
def test_a_frame_drawn_as_yuv420p_is_its_rgba_picture_converted(
    renderer: Renderer, trajectory: Trajectory, time: float, moving: bool
) -> None:
    # 0.9 s: every ball at rest (the picture is `settled`, read back once per format);
    # 0.2 s: the cue ball rolls (drawn into `work`); moving: the camera's path.
    pose = side_view(trajectory)
    rgba = renderer.draw(time, pose, moving, 0.5 / 30)
    yuv = renderer.draw(time, pose, moving, 0.5 / 30, pixel_format="yuv420p")
    assert renderer.draw(time, pose, moving, 0.5 / 30) == rgba  # the cache keeps both
    assert len(yuv) == frame_bytes(FILM_SIZE, "yuv420p")
    width, height = FILM_SIZE
    picture = np.frombuffer(rgba, dtype=np.uint8).reshape(height, width, 4)
    difference = np.abs(np.frombuffer(yuv, dtype=np.uint8).astype(int) - bt709_yuv420p(picture))
    assert difference.max() <= 1


def flat(picture: Image, reach: int = 2, spread: int = 2) -> npt.NDArray[np.bool_]:
    """The pixels whose (2 reach + 1)^2 neighbourhood varies by at most `spread` codes in
    every channel: where a film's chroma subsampling and compression change nothing."""
    height, width = picture.shape[:2]
    values = picture.astype(int)
    padded = np.pad(values, ((reach, reach), (reach, reach), (0, 0)), mode="edge")
    low, high = values.copy(), values.copy()
    for dy in range(2 * reach + 1):
        for dx in range(2 * reach + 1):
            window = padded[dy : dy + height, dx : dx + width]
            low, high = np.minimum(low, window), np.maximum(high, window)
    return np.all(high - low <= spread, axis=2)


@pytest.mark.parametrize("pixel_format", ["yuv420p", "rgba"])
def test_a_film_decodes_to_the_pictures_drawn(
    renderer: Renderer, trajectory: Trajectory, tmp_path: Path, pixel_format: str
) -> None:
    # Either input (yuv420p converted by the GL, RGBA by ffmpeg) gives a film tagged
    # BT.709 limited range that a decoder turns back into the drawn colours: a wrong
    # matrix, range or tag, swapped planes or a flipped picture would not.
    pose = side_view(trajectory)
    times = np.linspace(0.0, 0.6, 10)
    drawn = []
    path = tmp_path / f"{pixel_format}.mp4"
    with VideoWriter(path, FILM_SIZE, 30.0, pixel_format=pixel_format) as writer:
        for time in times:
            rgba = renderer.draw(float(time), pose, exposure=0.5 / 30)
            width, height = FILM_SIZE
            drawn.append(np.frombuffer(rgba, dtype=np.uint8).reshape(height, width, 4)[..., :3])
            writer.write(
                renderer.draw(float(time), pose, exposure=0.5 / 30, pixel_format=pixel_format)
            )
    assert "yuv420p(tv, bt709, progressive)" in streams(path)
    _, decoded = decode_mp4(path)
    assert len(decoded) == len(drawn)
    # Measured on these frames: mean error <= 1.1 codes and mean shift <= 1.4 (the
    # compression's); decoded as BT.601 3.3 and 5.1, as full range 12 and 14, flipped
    # 45 and 55, U and V swapped 27 and 40.
    for picture, original in zip(decoded, drawn, strict=True):
        where = flat(original)
        assert where.mean() > 0.3  # cloth, floor, walls
        got, want = picture[where].astype(float), original[where].astype(float)
        error = np.abs(got - want).mean()
        shift = np.abs(got.mean(axis=0) - want.mean(axis=0)).max()  # a colour cast
        assert error < 2.0 and shift < 2.5, (error, shift)


Frame = tuple[float, CameraPose, bool, float]  # time, pose, moving, exposure


def parts_and_wholes(
    ctx: moderngl.Context, trajectory: Trajectory, size: tuple[int, int], frames: list[Frame]
) -> int:
    """Draws `frames` in order as yuv420p and asserts each is its whole RGBA picture
    converted, bit for bit; returns how many were converted in part."""
    renderer = Renderer(ctx, trajectory, size, antialias=4)
    whole = Yuv420pPass(ctx, size)
    picture = ctx.texture(size, 4)
    parts = 0
    try:
        for index, (time, pose, moving, exposure) in enumerate(frames):
            converted = renderer.draw(time, pose, moving, exposure, "yuv420p")
            parts += renderer.output.drawn is not None and not moving
            picture.write(renderer.draw(time, pose, moving, exposure))
            assert converted == whole.convert(picture), index
    finally:
        picture.release()
        whole.release()
        renderer.release()
    return parts


@pytest.mark.long
def test_frames_converted_in_part_are_the_frames_converted_whole(ctx: moderngl.Context) -> None:
    # While the camera holds still, each frame converts only where balls move (and
    # moved in the last frame converted): every frame of the default film, break,
    # camera moves and pocketed balls included, must still be its whole picture.
    # The cue's strike too: while it is drawn, where it is is converted as well.
    settings = RenderSettings(width=128, height=72)
    scene = load_scene(None)
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    exposures = clock.exposures(settings.shutter)
    poses = camera_poses(camera_timeline(trajectory, settings), clock)
    frames = [
        (float(clock.sim_times[index]), pose, moving, float(exposures[index]))
        for index, (pose, moving) in enumerate(poses)
    ]
    size = (settings.width, settings.height)
    assert parts_and_wholes(ctx, trajectory, size, frames) > 100  # most, in part


def test_a_ball_that_jumps_between_frames_leaves_no_trace(ctx: moderngl.Context) -> None:
    # Sharp (shutter shut) and fast, 27 cm a frame: where it was in the last frame is
    # not where it is drawn now, and must be converted again too.
    trajectory = rolling_trajectory(start=-0.1, end=0.25, speed=8.0)
    size = (128, 72)
    pose = preset_pose("overhead", Stage.of(trajectory), size[0] / size[1])
    frames = [(k / 30, pose, False, 0.0) for k in range(6)]
    assert parts_and_wholes(ctx, trajectory, size, frames) >= 4


def test_a_gl_without_the_pass_films_in_rgba(
    ctx: moderngl.Context, trajectory: Trajectory, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The pass's shader needs GL_ARB_gpu_shader5 (GL 4.0); where the GL cannot build it
    # a film's frames go as RGBA (ffmpeg converts) instead of failing at frame one.
    renderer = Renderer(ctx, trajectory, FILM_SIZE, antialias=0)
    try:
        assert renderer.output.film_format() == "yuv420p"  # llvmpipe has it
    finally:
        renderer.release()

    def refused(*_: object) -> None:
        raise moderngl.Error("GL_ARB_gpu_shader5 is not supported")

    monkeypatch.setattr("billiards.render.gl.frame_output.Yuv420pPass", refused)
    renderer = Renderer(ctx, trajectory, FILM_SIZE, antialias=0)
    try:
        assert renderer.output.film_format() == "rgba"
        frame = renderer.draw(
            0.1, side_view(trajectory), pixel_format=renderer.output.film_format()
        )
        assert len(frame) == frame_bytes(FILM_SIZE, "rgba")
    finally:
        renderer.release()
