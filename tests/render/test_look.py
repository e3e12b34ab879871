"""Facts about how the table's surfaces look: wood grain along each rail and mitred
at the corners, a pool of lamp light on the cloth, an apron lit as wood."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.drop import GONE_DEPTH
from billiards.record.trajectory import Trajectory
from billiards.render.gl.context import ContextError, create_context
from billiards.render.gl.renderer import Renderer
from billiards.stage.cameras import CameraPose
from billiards.stage.table_plan import TableShape
from tests.render.fixtures import LENGTH, RADIUS, WIDTH, rolling_trajectory

pytestmark = pytest.mark.gl
Image = npt.NDArray[np.float64]
SHAPE = TableShape(LENGTH, WIDTH)
RAIL_MIDDLE = SHAPE.cushion_width + SHAPE.rail_width / 2  # behind the nose


@pytest.fixture(scope="module")
def renderer() -> Iterator[Renderer]:
    try:
        ctx = create_context()
    except ContextError as error:
        pytest.skip(f"no headless OpenGL context: {error}")
    trajectory: Trajectory = rolling_trajectory()
    made = Renderer(ctx, trajectory, (256, 256), antialias=0)
    yield made
    made.release()
    ctx.release()


def looking_down_at(renderer: Renderer, x: float, y: float, across: float = 0.06) -> Image:
    """A square picture `across` m wide looking straight down at (x, y) on the rail top."""
    height = 0.5
    fov = float(np.degrees(2 * np.arctan(across / 2 / height)))
    top = SHAPE.rail_top
    pose = CameraPose((x, y - 1e-4, top + height), (x, y, top), fov)
    return renderer.frame(0.0, pose).astype(np.float64).mean(axis=2)


def grain_runs_along_x(image: Image) -> bool:
    """Whether the picture changes less along its rows (world x) than its columns."""
    along_x = np.abs(np.diff(image, axis=1)).mean()
    along_y = np.abs(np.diff(image, axis=0)).mean()
    return bool(along_x < 0.2 * along_y)


def grain_runs_along_y(image: Image) -> bool:
    return grain_runs_along_x(image.T)


def test_the_wood_grain_runs_along_each_rail(renderer: Renderer) -> None:
    assert grain_runs_along_x(looking_down_at(renderer, 0.3 * LENGTH, -RAIL_MIDDLE))
    assert grain_runs_along_x(looking_down_at(renderer, 0.6 * LENGTH, WIDTH + RAIL_MIDDLE))
    assert grain_runs_along_y(looking_down_at(renderer, -RAIL_MIDDLE, 0.7 * WIDTH))
    assert grain_runs_along_y(looking_down_at(renderer, LENGTH + RAIL_MIDDLE, 0.3 * WIDTH))


def test_the_rails_meet_in_mitres_at_the_corners(renderer: Renderer) -> None:
    # Either side of the corner's diagonal the grain follows its own rail.
    beyond = SHAPE.cushion_width + 0.75 * SHAPE.rail_width
    offset = 0.02
    short_side = looking_down_at(renderer, -beyond - offset, -beyond + offset, across=0.025)
    long_side = looking_down_at(renderer, -beyond + offset, -beyond - offset, across=0.025)
    assert grain_runs_along_y(short_side)
    assert grain_runs_along_x(long_side)


def test_the_lamp_lights_a_pool_on_the_cloth_that_falls_off_to_the_corners(
    renderer: Renderer,
) -> None:
    pose = CameraPose((LENGTH / 2, WIDTH / 2 - 0.01, 2.2), (LENGTH / 2, WIDTH / 2, 0.0), 55.0)
    image = renderer.frame(0.0, pose).astype(np.float64)
    centre = pose.project(np.array([[LENGTH / 2, 0.7 * WIDTH, 0.0]]), 256, 256)[0]
    corner = pose.project(np.array([[0.12, 0.12, 0.0]]), 256, 256)[0]

    def green(point: npt.NDArray[np.float64]) -> float:
        x, y = int(point[0]), int(point[1])
        return float(image[y - 2 : y + 3, x - 2 : x + 3, 1].mean())

    assert green(corner) < 0.72 * green(centre)


def test_a_ball_casts_its_shadow_on_the_rail_as_on_the_cloth(renderer: Renderer) -> None:
    # A ball resting on the rail's top: its shadow darkens the wood under it, where a
    # shadow drawn only on the cloth's plane could not.
    on_rail = (0.4 * LENGTH, -RAIL_MIDDLE, SHAPE.rail_top + RADIUS)
    trajectory = renderer.trajectory
    positions = trajectory.positions.copy()
    # Seen from off the table: the lamp over the table throws the shadow outwards.
    pose = CameraPose((on_rail[0] + 0.2, on_rail[1] - 0.35, 0.35), on_rail, 30.0)
    beside = np.array([[on_rail[0], on_rail[1] - 1.3 * RADIUS, SHAPE.rail_top]])
    x, y = (int(v) for v in pose.project(beside, 256, 256)[0])
    values = []
    for place in (on_rail, (on_rail[0], on_rail[1], GONE_DEPTH)):
        positions[:, 1] = place
        renderer.trajectory = dataclasses.replace(trajectory, positions=positions.copy())
        try:
            image = renderer.frame(0.0, pose).astype(np.float64)
        finally:
            renderer.trajectory = trajectory
        values.append(float(image[y - 1 : y + 2, x - 1 : x + 2].mean()))
    shadowed, open_wood = values
    assert shadowed < 0.9 * open_wood


def test_a_ball_in_the_air_casts_its_shadow_on_the_cloth(renderer: Renderer) -> None:
    # A ball 10 cm above the cloth (issue 45: a jump's flight), seen from straight
    # above: round its silhouette the cloth is darker than with the ball gone (its
    # shadow reaches further the higher it flies: shadow.vert's reach).
    foot = (0.3 * LENGTH, 0.5 * WIDTH)
    flying = (*foot, RADIUS + 0.10)
    trajectory = renderer.trajectory
    positions = trajectory.positions.copy()
    pose = CameraPose((foot[0], foot[1] - 1e-4, 0.8), (*foot, 0.0), 30.0)
    images = []
    for place in (flying, (*foot, GONE_DEPTH)):
        positions[:, 1] = place
        renderer.trajectory = dataclasses.replace(trajectory, positions=positions.copy())
        try:
            images.append(renderer.frame(0.0, pose).astype(np.float64).sum(axis=2))
        finally:
            renderer.trajectory = trajectory
    shadowed, open_cloth = images
    centre = pose.project(np.array([flying]), 256, 256)[0]
    edge = pose.project(np.array([[foot[0] + RADIUS, foot[1], flying[2]]]), 256, 256)[0]
    silhouette = float(np.hypot(*(edge - centre)))
    rows, columns = np.indices(shadowed.shape)
    apart = np.hypot(columns - centre[0], rows - centre[1])
    around = (apart > 1.3 * silhouette) & (apart < 6 * silhouette)
    ratio = shadowed[around] / np.maximum(open_cloth[around], 1.0)
    assert ratio.min() < 0.85
    assert np.all(shadowed[apart > 12 * silhouette] == open_cloth[apart > 12 * silhouette])
