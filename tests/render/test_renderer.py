"""Facts about rendered pictures: tiny frames drawn on a real headless GL context.

Skipped, with the reason, only where no OpenGL context can be made.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.trajectory import Trajectory
from billiards.render.gl.background_pass import LOW_RES_SCALE
from billiards.render.gl.ball_pass import SHARP_BELOW
from billiards.render.gl.frame_output import REFERENCE_PIXELS, msaa_samples, sample_scale
from billiards.render.gl.renderer import Renderer
from billiards.scene.render_table import ANTIALIAS_SAMPLES, PRESETS
from billiards.stage.cameras import CameraPose, Stage, preset_pose
from tests.render.fixtures import (
    LENGTH,
    RADIUS,
    WIDTH,
    gl_context,  # noqa: F401 (the ctx fixture)
    rolling_trajectory,
)

pytestmark = pytest.mark.gl

SIZE = (160, 90)
Image = npt.NDArray[np.uint8]


@pytest.fixture(scope="module")
def trajectory() -> Trajectory:
    return rolling_trajectory()


@pytest.fixture(scope="module")
def renderer(ctx: object, trajectory: Trajectory) -> Iterator[Renderer]:
    made = Renderer(ctx, trajectory, SIZE, antialias=4)  # type: ignore[arg-type]
    yield made
    made.release()


def overhead(trajectory: Trajectory) -> CameraPose:
    return preset_pose("overhead", Stage.of(trajectory), SIZE[0] / SIZE[1])


def cue_pixel(trajectory: Trajectory, pose: CameraPose, frame: int) -> tuple[int, int]:
    centre = trajectory.positions[frame, 0][None, :]
    x, y = pose.project(centre, *SIZE)[0]
    return int(x), int(y)  # the pixel that contains the projected centre


def is_green(pixel: Image) -> bool:
    r, g, b = (int(v) for v in pixel)
    return g > r + 25 and g > b + 25


def is_white(pixel: Image) -> bool:
    """The cue ball: bright and nearly grey (its side away from the lamp is shaded)."""
    values = [int(v) for v in pixel]
    return min(values) > 100 and max(values) - min(values) < 50


def test_cloth_is_green_where_the_table_is(renderer: Renderer, trajectory: Trajectory) -> None:
    pose = overhead(trajectory)
    image = renderer.frame(0.0, pose)
    assert image.shape == (SIZE[1], SIZE[0], 3)
    # Open cloth: between the head string and the rack, and near the side cushions.
    spots = np.array(
        [
            [0.45 * LENGTH, 0.25 * WIDTH, 0.0],
            [0.55 * LENGTH, 0.8 * WIDTH, 0.0],
            [0.15 * LENGTH, 0.5 * WIDTH, 0.0],
        ]
    )
    for x, y in pose.project(spots, *SIZE):
        assert is_green(image[int(y), int(x)]), (x, y, image[int(y), int(x)])
    # Outside the table (the floor beyond the rails) is not cloth.
    x, y = pose.project(np.array([[-0.4, -0.4, -0.79]]), *SIZE)[0]
    if 0 <= x < SIZE[0] and 0 <= y < SIZE[1]:
        assert not is_green(image[int(y), int(x)])


def test_cue_ball_is_white_where_the_camera_projects_it(
    renderer: Renderer, trajectory: Trajectory
) -> None:
    for name in ("overhead", "behind_cue", "corner"):
        pose = preset_pose(name, Stage.of(trajectory), SIZE[0] / SIZE[1])
        frame = 0
        image = renderer.frame(float(trajectory.times[frame]), pose)
        x, y = cue_pixel(trajectory, pose, frame)
        assert is_white(image[y, x]), (name, image[y, x])


def test_a_moved_ball_moves_in_the_picture(renderer: Renderer, trajectory: Trajectory) -> None:
    pose = overhead(trajectory)
    first, last = 0, len(trajectory.times) - 1
    before = renderer.frame(float(trajectory.times[first]), pose)
    after = renderer.frame(float(trajectory.times[last]), pose)
    old = cue_pixel(trajectory, pose, first)
    new = cue_pixel(trajectory, pose, last)
    assert new[0] - old[0] > 20  # it rolled about 0.9 m along +x
    assert is_white(before[old[1], old[0]]) and is_green(after[old[1], old[0]])
    assert is_green(before[new[1], new[0]]) and is_white(after[new[1], new[0]])


def test_two_renders_of_the_same_frame_are_identical(
    ctx: object, renderer: Renderer, trajectory: Trajectory
) -> None:
    pose = preset_pose("corner", Stage.of(trajectory), SIZE[0] / SIZE[1])
    first = renderer.draw(0.5, pose)
    # The second draw reuses the cached table; a fresh renderer draws everything anew.
    second = renderer.draw(0.5, pose)
    fresh = Renderer(ctx, trajectory, SIZE, antialias=4)  # type: ignore[arg-type]
    try:
        third = fresh.draw(0.5, pose)
    finally:
        fresh.release()
    assert first == second == third


def test_balls_at_rest_kept_with_the_table_draw_the_same_frame(
    ctx: object, trajectory: Trajectory
) -> None:
    # A still camera keeps the resting rack drawn in with the table and draws only the
    # rolling cue ball; told the camera moves, the renderer draws every ball each frame.
    plain = Renderer(ctx, trajectory, SIZE, antialias=0)  # type: ignore[arg-type]
    try:
        stage = Stage.of(trajectory)
        # From beyond the foot rail, low: the cue ball rolls up behind the rack's apex.
        behind = CameraPose((LENGTH + 0.6, WIDTH / 2 + 0.01, 0.09), (1.3, WIDTH / 2, 0.03), 30.0)
        poses = [preset_pose(name, stage, SIZE[0] / SIZE[1]) for name in PRESETS]
        for pose, time in [*((pose, 0.2) for pose in poses), (poses[0], 0.9), (behind, 0.9)]:
            kept = plain.draw(time, pose, exposure=0.5 / 30)
            drawn = plain.draw(time, pose, moving=True, exposure=0.5 / 30)
            assert kept == drawn, (pose, time)
    finally:
        plain.release()


def test_the_cue_ball_turns_as_it_rolls(ctx: object, trajectory: Trajectory) -> None:
    # Close above the cue ball, following it: its marks move across its face.
    big = Renderer(ctx, trajectory, (96, 96), antialias=0)  # type: ignore[arg-type]
    try:
        patches = []
        for frame in (16, 19):  # 0.1 s apart: it turns about a third of a revolution
            x, y, _ = trajectory.positions[frame, 0]
            pose = CameraPose((x, y - 1e-3, 0.2), (x, y, RADIUS), 20.0)
            patches.append(big.frame(float(trajectory.times[frame]), pose).astype(int))
    finally:
        big.release()
    assert np.abs(patches[0] - patches[1]).max() > 60


def test_a_users_table_mesh_replaces_the_built_table(
    ctx: object, trajectory: Trajectory, tmp_path: Path
) -> None:
    import trimesh

    # A red slab a little larger than the playing area, its top at the cloth's height.
    corners = np.array(
        [
            (x, y, z)
            for x in (-0.15, LENGTH + 0.15)
            for y in (-0.15, WIDTH + 0.15)
            for z in (-0.1, 0.0)
        ]
    )
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]  # fmt: skip
    slab = trimesh.Trimesh(
        corners, faces, vertex_colors=np.tile((200, 40, 40, 255), (8, 1)), process=False
    )
    path = tmp_path / "slab.ply"
    slab.export(path)
    custom = Renderer(ctx, trajectory, SIZE, antialias=0, table_mesh=path)  # type: ignore[arg-type]
    try:
        pose = overhead(trajectory)
        image = custom.frame(0.0, pose)
    finally:
        custom.release()
    x, y = pose.project(np.array([[0.45 * LENGTH, 0.25 * WIDTH, 0.0]]), *SIZE)[0]
    r, g, b = (int(v) for v in image[int(y), int(x)])
    assert r > g + 20 and r > b + 20  # the red slab, not green cloth


def test_a_moving_camera_draws_the_room_plainly_and_a_still_one_sharp_again(
    renderer: Renderer, trajectory: Trajectory
) -> None:
    stage = Stage.of(trajectory)
    pose = preset_pose("low_side", stage, SIZE[0] / SIZE[1])
    renderer.draw(0.5, preset_pose("overhead", stage))  # elsewhere first: nothing cached
    plain = renderer.draw(0.5, pose, moving=True)
    sharp = renderer.draw(0.5, pose)
    assert plain != sharp  # the table's edges without multisampling
    assert renderer.draw(0.5, pose, moving=True) == sharp  # a sharp table is kept
    renderer.draw(0.5, preset_pose("overhead", stage))
    assert renderer.draw(0.5, pose) == sharp


@contextlib.contextmanager
def static_draws(renderer: Renderer) -> Iterator[list[object]]:
    """The framebuffers the renderer draws its static scene into, while in the block."""
    drawn: list[object] = []
    draw_static = renderer.background.draw_static

    def counted(target: object, pose: CameraPose) -> None:
        drawn.append(target)
        draw_static(target, pose)  # type: ignore[arg-type]

    renderer.background.draw_static = counted  # type: ignore[method-assign,assignment]
    try:
        yield drawn
    finally:
        del renderer.background.draw_static


def test_a_shot_the_film_comes_back_to_is_not_drawn_again(
    ctx: object, trajectory: Trajectory
) -> None:
    stage = Stage.of(trajectory)
    wide = preset_pose("corner", stage, SIZE[0] / SIZE[1])
    others = [preset_pose(name, stage, SIZE[0] / SIZE[1]) for name in ("rack", "overhead")]
    fresh = Renderer(ctx, trajectory, SIZE)  # type: ignore[arg-type]
    try:
        first = fresh.draw(0.5, wide)
        for pose in others:
            fresh.draw(0.5, pose)
        with static_draws(fresh) as drawn:
            assert fresh.draw(0.5, wide) == first  # the same bits, from the kept copy
        assert drawn == []
    finally:
        fresh.release()


def test_a_fast_moving_camera_draws_the_room_smaller_and_close_to_the_sharp_one(
    renderer: Renderer, trajectory: Trajectory
) -> None:
    stage = Stage.of(trajectory)
    pose = preset_pose("behind_cue", stage, SIZE[0] / SIZE[1])  # none of it kept yet
    renderer.draw(0.5, preset_pose("overhead", stage))  # far away: a fast move follows
    with static_draws(renderer) as drawn:
        quick = np.frombuffer(renderer.draw(0.5, pose, moving=True), np.uint8)
    assert drawn == [renderer.background.low]
    sharp = np.frombuffer(renderer.draw(0.5, pose), np.uint8)
    difference = np.abs(quick.astype(int) - sharp.astype(int))
    assert difference.mean() < 3.0  # softer edges, the same picture


FRAME_SIZES = ((160, 90), (640, 360), (1280, 720), (1920, 1080), (2560, 1440), (3840, 2160))


@pytest.mark.parametrize("antialias", ANTIALIAS_SAMPLES)
def test_720p_and_smaller_frames_take_the_samples_asked(antialias: int) -> None:
    for size in ((160, 90), (640, 360), (1280, 720), (720, 1280)):
        assert sample_scale(size) == 1.0
        assert msaa_samples(antialias, size, 8) == antialias


@pytest.mark.parametrize("antialias", ANTIALIAS_SAMPLES)
def test_a_larger_frame_takes_as_many_samples_per_share_of_the_screen_and_no_more(
    antialias: int,
) -> None:
    for size in FRAME_SIZES:
        area = size[0] * size[1] / REFERENCE_PIXELS
        samples = msaa_samples(antialias, size, 8)
        assert samples in ANTIALIAS_SAMPLES
        assert max(samples, 1) * max(area, 1.0) >= antialias  # at least 720p's
        if samples > 1:  # and half as many would be fewer
            assert samples / 2 * max(area, 1.0) < antialias


def test_1080p_multisamples_half_as_much_as_720p() -> None:
    # 2.25 times the pixels: 2 samples a pixel is 4.5 per 720p pixel's share
    assert [msaa_samples(a, (1920, 1080), 8) for a in (0, 2, 4, 8)] == [0, 0, 2, 4]
    assert msaa_samples(8, (1280, 720), 4) == 4  # never more than the GL has
    assert sample_scale((1920, 1080)) == 1.5


def test_a_1080p_frame_blurs_and_draws_its_fast_background_as_finely_as_a_720p_one(
    ctx: object, trajectory: Trajectory
) -> None:
    small = Renderer(ctx, trajectory, (1280, 720), antialias=4)  # type: ignore[arg-type]
    large = Renderer(ctx, trajectory, (1920, 1080), antialias=4)  # type: ignore[arg-type]
    try:
        assert small.balls.sharp_below == SHARP_BELOW
        assert small.background.low_colour.size == (832, 468)  # LOW_RES_SCALE of 720p
        assert round(1280 * LOW_RES_SCALE) == 832
        assert small.background.samples == 4
        # the same steps and background on the screen, 1.5 times the pixels a side
        assert large.balls.sharp_below == 1.5 * SHARP_BELOW
        assert large.background.low_colour.size == small.background.low_colour.size
        assert large.background.samples == 2
        # a slowly moving camera: the table at 720p's resolution, filtered up (at 720p
        # drawn straight at the frame's size, its edges smoothed there)
        assert small.background.reduced is None and large.background.reduced is not None
        reduced, colour, _ = large.background.reduced
        assert colour.size == (1280, 720)
        pose = preset_pose("low_side", Stage.of(trajectory), 16 / 9)
        with static_draws(large) as drawn:
            large.draw(0.5, pose, moving=True)
        assert drawn == [reduced]
        with static_draws(small) as drawn:
            small.draw(0.5, pose, moving=True)
        assert drawn == [small.background.framebuffer]
    finally:
        large.release()
        small.release()


def test_without_anti_aliasing_a_slowly_moving_camera_draws_the_room_straight(
    ctx: object, trajectory: Trajectory
) -> None:
    plain = Renderer(ctx, trajectory, (1280, 720), antialias=0)  # type: ignore[arg-type]
    try:
        assert plain.background.reduced is None and plain.background.static_edges is None
        pose = preset_pose("low_side", Stage.of(trajectory), 16 / 9)
        with static_draws(plain) as drawn:
            plain.draw(0.5, pose, moving=True)
        assert drawn == [plain.background.framebuffer]
    finally:
        plain.release()


def edge_steps(image: Image) -> float:
    """How far (rms, px) the rail's near edge, found in each column as the sharpest fall
    of red from the rail's wood to the cushion's cloth, strays from the straight line
    fitted to it: its position in a column is where the cover of the four pixels round
    the fall, measured between the levels just above and below it, ends. A stepped
    (aliased) edge stays on a row and jumps; an anti-aliased one moves a little every
    column."""
    red = image[..., 0].astype(float)
    found, positions = [], []
    for column in range(10, image.shape[1] - 10):
        profile = red[:, column]
        fall = int(np.argmin(np.diff(profile[10:-10]))) + 10
        above, below = profile[fall - 5 : fall - 1].mean(), profile[fall + 3 : fall + 7].mean()
        if above - below < 20:
            continue  # no edge found in this column
        cover = np.clip((profile[fall - 1 : fall + 3] - below) / (above - below), 0.0, 1.0)
        found.append(column)
        positions.append(fall - 1 + cover.sum())
    assert len(found) > image.shape[1] // 2
    columns = np.asarray(found)
    # (a sight inlaid in the rail, or a ball, lies off the line: left out)
    line = np.polyfit(columns, positions, 1)
    off = np.asarray(positions) - np.polyval(line, columns)
    kept = np.abs(off) < 2.0
    line = np.polyfit(columns[kept], np.asarray(positions)[kept], 1)
    off = np.asarray(positions)[kept] - np.polyval(line, columns[kept])
    return float(np.sqrt(np.mean(off**2)))


def test_a_moving_cameras_cushion_edges_are_smoothed(ctx: object, trajectory: Trajectory) -> None:
    # Straight down on the far rail, turned 12 degrees: its edge crosses the picture at a
    # slant, drawn while the camera moves fast (the table drawn small and filtered up).
    size = (320, 180)
    turn = math.radians(12.0)
    x, y = 0.3 * LENGTH, WIDTH
    pose = CameraPose((x, y, 0.6), (x, y, 0.0), 40.0, (-math.sin(turn), math.cos(turn), 0.0))
    steps: dict[int | str, float] = {}
    for antialias in (4, 0):
        made = Renderer(ctx, trajectory, size, antialias=antialias)  # type: ignore[arg-type]
        try:
            made.draw(0.0, preset_pose("overhead", Stage.of(trajectory), 16 / 9))
            with static_draws(made) as drawn:
                moving = made.draw(0.0, pose, moving=True)
            assert drawn == [made.background.low]
            steps[antialias] = edge_steps(as_image(moving, size))
            if antialias:
                steps["still"] = edge_steps(as_image(made.draw(0.0, pose), size))
        finally:
            made.release()
    # Multisampled (a still camera) the edge is straight to a tenth of a pixel; drawn
    # plainly at 0.65 of the size and filtered up, it steps by a third of a pixel rms;
    # smoothed (its line drawn over it), by a tenth (0.098: the full-screen FXAA this
    # replaced left 0.21).
    assert steps["still"] < 0.12
    assert steps[0] > 0.25
    assert steps[4] < 0.13


def as_image(data: bytes, size: tuple[int, int]) -> Image:
    return np.frombuffer(data, np.uint8).reshape(size[1], size[0], 4)[..., :3]


def test_a_moving_cameras_smoothed_frame_repeats_bit_for_bit(
    ctx: object, trajectory: Trajectory
) -> None:
    stage = Stage.of(trajectory)
    pictures = []
    for antialias in (4, 4, 0):
        made = Renderer(ctx, trajectory, (320, 180), antialias=antialias)  # type: ignore[arg-type]
        try:
            made.draw(0.5, preset_pose("overhead", stage, 16 / 9))
            pictures.append(made.draw(0.5, preset_pose("corner", stage, 16 / 9), moving=True))
        finally:
            made.release()
    assert pictures[0] == pictures[1]  # the same bits from a fresh renderer
    assert pictures[0] != pictures[2]  # and its edges smoothed
