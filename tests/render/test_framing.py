"""Facts about the camera presets' framing, on every table size (1.8-3.6 m) and frame
shape (16:9, 4:3, 1:1, 9:16): the wide presets (overhead, corner, orbit) keep the whole
cloth in the frame, every preset fills a stated share of the frame with cloth, and no
rendered preset is blown white (the overhead view of a 9-ft table, or of any table on a
4:3 film, used to rise through the lamp and the ceiling and film a white screen).

The grid is checked by projecting the cloth through each preset's camera (no GL); a
coarser grid is really rendered, small, and the cloth counted in the picture."""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Iterator

import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.trajectory import Event, Trajectory
from billiards.record.window import film_trajectory
from billiards.render.director import directed_shots
from billiards.render.gl.context import ContextError, create_context
from billiards.render.gl.renderer import Renderer
from billiards.scene.reader import RACK_ORDER, load_scene, rack_positions, shipped_scene_names
from billiards.scene.render_table import PRESETS
from billiards.simulation import simulate_scene
from billiards.stage.cameras import CameraPose, Stage, preset_pose
from billiards.stage.room import Room

RADIUS = 0.0286
LENGTHS = (1.8, 2.13, 2.54, 2.84, 3.2, 3.6)  # m between the cushion noses; width: half
ASPECTS = {"16:9": 16 / 9, "4:3": 4 / 3, "1:1": 1.0, "9:16": 9 / 16}
WIDE = ("overhead", "corner", "orbit")  # the whole table in the picture
# The least share of the frame the cloth fills, by preset (projected; the rendered
# pictures' counts are held to the same shares). The close views (behind the cue, low
# beside the table, beside the rack) look along the cloth and are mostly cloth; the
# wide ones show the room around the table, the corner view most of it (its share is
# smallest on an upright film, where the table stands up the picture from its foot).
LEAST_CLOTH = {
    "overhead": 0.30,
    "corner": 0.05,
    "orbit": 0.05,
    "behind_cue": 0.35,
    "low_side": 0.25,
    "rack": 0.40,
}
BLOWN = 250  # a channel value: a pixel with all three at or above it is blown white
MOST_BLOWN = 0.02  # the share of the frame that may be (the lamp's glowing diffusers)


def stage_on(length: float) -> Stage:
    """A break on a table `length` x `length / 2`: the cue ball from the head spot
    along +x into a rack on the foot spot."""
    width = length / 2
    return Stage(
        length=length,
        width=width,
        cue_start=(length / 4, width / 2, RADIUS),
        cue_direction=(1.0, 0.0),
        film_start=-0.5,
        impact=(0.75 * length - 2 * RADIUS, width / 2, RADIUS),
    )


def cloth_corners(stage: Stage) -> npt.NDArray[np.float64]:
    length, width = stage.length, stage.width
    return np.array([(0.0, 0.0, 0.0), (length, 0.0, 0.0), (length, width, 0.0), (0.0, width, 0.0)])


def cloth_share(pose: CameraPose, stage: Stage, aspect: float, rays: int = 120) -> float:
    """The share of the frame whose line of sight meets the cloth (rails ignored)."""
    right, up, forward = pose.basis()
    tan_v = math.tan(math.radians(pose.fov) / 2)
    middles = (np.arange(rays) + 0.5) / rays * 2 - 1
    across, upward = np.meshgrid(middles * tan_v * aspect, middles * tan_v)
    sight = forward + across[..., None] * right + upward[..., None] * up
    eye = np.array(pose.eye)
    with np.errstate(divide="ignore"):
        reach = np.where(sight[..., 2] < 0, -eye[2] / sight[..., 2], -1.0)
    x = eye[0] + reach * sight[..., 0]
    y = eye[1] + reach * sight[..., 1]
    on_cloth = (reach > 0) & (x >= 0) & (x <= stage.length) & (y >= 0) & (y <= stage.width)
    return float(on_cloth.mean())


def in_frame(pose: CameraPose, points: npt.NDArray[np.float64], aspect: float) -> bool:
    """Whether every point is in front of the camera and inside its frame."""
    _, _, forward = pose.basis()
    if np.any((points - np.array(pose.eye)) @ forward <= 0):
        return False
    height = 1000
    width = round(height * aspect)
    pixels = pose.project(points, width, height)
    return bool(np.all((pixels >= 0) & (pixels <= (width, height))))


GRID = list(itertools.product(PRESETS, LENGTHS, ASPECTS))


@pytest.mark.parametrize(("preset", "length", "aspect"), GRID)
def test_each_preset_frames_the_cloth_on_every_table_and_frame(
    preset: str, length: float, aspect: str
) -> None:
    stage = stage_on(length)
    pose = preset_pose(preset, stage, ASPECTS[aspect])
    share = cloth_share(pose, stage, ASPECTS[aspect])
    assert share >= LEAST_CLOTH[preset], share
    if preset in WIDE:
        assert in_frame(pose, cloth_corners(stage), ASPECTS[aspect])


@pytest.mark.parametrize(("length", "aspect"), list(itertools.product(LENGTHS, ASPECTS)))
def test_the_orbit_keeps_the_cloth_in_frame_all_the_way_round(length: float, aspect: str) -> None:
    stage = stage_on(length)
    pose = preset_pose("orbit", stage, ASPECTS[aspect])
    (ex, ey, ez), (tx, ty, _) = pose.eye, pose.target
    for degrees in range(0, 360, 10):
        c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
        eye = (tx + c * (ex - tx) - s * (ey - ty), ty + s * (ex - tx) + c * (ey - ty), ez)
        turned = CameraPose(eye, pose.target, pose.fov)
        assert in_frame(turned, cloth_corners(stage), ASPECTS[aspect]), degrees


@pytest.mark.parametrize("length", LENGTHS)
def test_the_overhead_view_stands_the_table_up_an_upright_frame(length: float) -> None:
    stage = stage_on(length)
    pose = preset_pose("overhead", stage, 9 / 16)
    pixels = pose.project(cloth_corners(stage), 90, 160)
    spread = pixels.max(axis=0) - pixels.min(axis=0)
    assert spread[1] > 1.5 * spread[0]  # the length runs up the picture


def at_rest_on(length: float) -> Trajectory:
    """A cue ball on the head spot and a rack on the foot spot, still, for a second."""
    width = length / 2
    ids = ("cue", *RACK_ORDER)
    spots = [(length / 4, width / 2), *rack_positions((0.75 * length, width / 2), RADIUS, 1e-4)]
    times = np.array([-0.5, 0.0, 0.5, 1.0])
    positions = np.zeros((len(times), len(ids), 3))
    positions[:, :, :2] = spots
    positions[:, :, 2] = RADIUS
    orientations = np.zeros((len(times), len(ids), 4))
    orientations[..., 3] = 1.0
    return Trajectory(
        ball_ids=ids,
        radius=RADIUS,
        table_size=(length, width),
        times=times,
        positions=positions,
        orientations=orientations,
        events=(Event(0.9, "ball", ("cue", "1"), 1.0),),
        rest_time=1.0,
    )


def cloth_pixels(picture: npt.NDArray[np.uint8]) -> npt.NDArray[np.bool_]:
    """Where the picture shows the green cloth (the bed or the cushions), lit or in shade."""
    red, green, blue = (picture[..., k].astype(np.int32) for k in range(3))
    return (green >= 25) & (green > red * 13 // 10 + 4) & (green > blue * 11 // 10 + 4)


@pytest.fixture(scope="module")
def gl() -> Iterator[object]:
    try:
        context = create_context()
    except ContextError as error:
        pytest.skip(f"no headless OpenGL context: {error}")
    yield context
    context.release()


# Really rendered: the shortest, the 9-ft and the longest table, on every frame shape,
# small (the frame's longer side 240 px).
RENDERED = list(itertools.product((1.8, 2.54, 3.6), ASPECTS))


@pytest.mark.gl
@pytest.mark.parametrize(("length", "aspect"), RENDERED)
def test_each_rendered_preset_shows_the_cloth_and_nothing_blown_white(
    gl: object, length: float, aspect: str
) -> None:
    ratio = ASPECTS[aspect]
    size = (240, 2 * round(120 / ratio)) if ratio >= 1 else (2 * round(120 * ratio), 240)
    trajectory = at_rest_on(length)
    stage = Stage.of(trajectory)
    renderer = Renderer(gl, trajectory, size, antialias=0, cue=False)  # type: ignore[arg-type]
    try:
        for preset in PRESETS:
            picture = renderer.frame(0.5, preset_pose(preset, stage, size[0] / size[1]))
            blown = float(np.all(picture >= BLOWN, axis=2).mean())
            cloth = float(cloth_pixels(picture).mean())
            assert blown <= MOST_BLOWN, (preset, blown)
            assert cloth >= LEAST_CLOTH[preset], (preset, cloth)
    finally:
        renderer.release()


@functools.cache
def shipped_trajectory(name: str) -> Trajectory:
    scene = load_scene(name)
    return film_trajectory(simulate_scene(scene), scene.render)


@pytest.mark.parametrize(
    ("name", "aspect"), list(itertools.product(shipped_scene_names(), ASPECTS))
)
def test_the_directors_every_shot_is_taken_from_inside_the_room(name: str, aspect: str) -> None:
    """The director frames what moves (a whole massé curve, a run round a carom table)
    from far enough to fit it: on an upright frame that took its eye through the wall,
    whose back filled the picture."""
    trajectory = shipped_trajectory(name)
    length, width = trajectory.table_size
    room = Room.around(length, width, floor=-0.79)
    (cx, cy), hx, hy = room.centre, room.half_x, room.half_y
    for shot in directed_shots(trajectory, ASPECTS[aspect]):
        if shot.eye is None:
            continue
        x, y, z = shot.eye
        assert abs(x - cx) < hx and abs(y - cy) < hy, (shot.start, shot.eye)
        # Above the ceiling only over the table, where the ceiling and lamp are left out.
        if z >= room.ceiling:
            assert -0.3 < x < length + 0.3 and -0.3 < y < width + 0.3, (shot.start, shot.eye)


@pytest.mark.gl
def test_the_ceiling_over_the_lamp_is_not_blown_white(gl: object) -> None:
    """The room's fill hangs 0.2 m under the ceiling; lit as a bulb so near, the ceiling
    above the table blazed white in the wide views of square and upright films."""
    trajectory = at_rest_on(2.54)
    renderer = Renderer(gl, trajectory, (160, 160), antialias=0, cue=False)  # type: ignore[arg-type]
    try:
        # From beside the lamp, above its shades, looking up at the ceiling over it.
        pose = CameraPose((1.27 - 1.6, 0.635 - 1.2, 1.3), (1.27, 0.635, 2.25), 60.0)
        picture = renderer.frame(0.5, pose)
    finally:
        renderer.release()
    assert float(np.all(picture >= BLOWN, axis=2).mean()) == 0.0


@pytest.mark.parametrize(("length", "aspect"), list(itertools.product(LENGTHS, ASPECTS)))
def test_the_rack_view_holds_the_cue_ball_and_the_whole_pack(length: float, aspect: str) -> None:
    stage = stage_on(length)
    pose = preset_pose("rack", stage, ASPECTS[aspect])
    pack = rack_positions((0.75 * length, length / 4), RADIUS, 1e-4)
    centres = np.array([stage.impact, *((x, y, RADIUS) for x, y in pack)])
    assert in_frame(pose, centres, ASPECTS[aspect])
