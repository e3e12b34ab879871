"""Facts about pockets in the film and the plot: holes only where the physics has
pockets, a dropping ball seen through its hole and gone after, pocketed balls marked."""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import numpy.typing as npt
import pytest

from billiards.physics.pockets import pocket_table
from billiards.pictures.top_view import POCKET, Layout, draw_top_view, pocketed_marks
from billiards.record.drop import GONE_DEPTH
from billiards.record.pocket_shapes import PocketShapes
from billiards.record.trajectory import Event, Trajectory
from billiards.render.gl.renderer import Renderer
from billiards.stage.cameras import CameraPose, Stage, preset_pose
from billiards.stage.holed_surfaces import HOLE_SEGMENTS, circle_points, holed_surface
from billiards.stage.materials import CUSHION_GREEN, POCKET_HOLE, SIGHT_PEARL, SIGHT_SETTING
from billiards.stage.pocket_mesh import build_pocket_liners
from billiards.stage.table import JAW_STEPS, bed_rects, build_table
from billiards.stage.table_plan import TableShape, cushion_runs, pocket_cuts
from tests.render.fixtures import (
    LENGTH,
    RADIUS,
    WIDTH,
    gl_context,  # noqa: F401 (the ctx fixture)
    rolling_trajectory,
)

SIZE = (192, 108)
POCKETS = PocketShapes.of(pocket_table((LENGTH, WIDTH), RADIUS))
SIDE_BOTTOM = (LENGTH / 2, -POCKETS.holes[1, 2])  # its hole's centre
Image = npt.NDArray[np.uint8]


def with_balls(pockets: PocketShapes | None, *places: tuple[float, float, float]) -> Trajectory:
    """The rolling fixture with balls 1, 2, ... put at `places` for the whole film."""
    base = rolling_trajectory()
    positions = base.positions.copy()
    for index, place in enumerate(places, start=1):
        positions[:, index] = place
    return dataclasses.replace(base, positions=positions, pockets=pockets)


def hole_centres() -> npt.NDArray[np.float64]:
    return np.column_stack((POCKETS.holes[:, :2], np.zeros(len(POCKETS.holes))))


# --- the table's shapes (no GL) ---------------------------------------------------------


def test_a_holed_surface_is_its_rectangle_less_the_holes_polygon() -> None:
    radius = 0.05
    [triangles] = holed_surface([(0.0, 0.0, 1.0, 0.5)], [(0.4, 0.25, radius)])
    u, v = triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    area = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]).sum()
    steps = HOLE_SEGMENTS
    hole = 0.5 * steps * radius**2 * math.sin(2 * math.pi / steps)
    assert area == pytest.approx(0.5 - hole, rel=1e-9)
    centroids = triangles.mean(axis=1)
    assert np.all(np.hypot(centroids[:, 0] - 0.4, centroids[:, 1] - 0.25) > 0.95 * radius)


def test_a_holed_surface_is_one_mesh_without_t_junctions() -> None:
    # The cloth and the shelf of a table with pockets: every edge inside the surface is
    # shared whole by two triangles; only the outer border and the holes' edges are not.
    shape = TableShape(LENGTH, WIDTH)
    cuts = pocket_cuts(shape, POCKETS)
    outer = shape.outer
    rects = bed_rects(shape)
    triangles = np.concatenate(holed_surface(rects, [cut.hole for cut in cuts]))
    edges: dict[tuple[tuple[float, float], ...], int] = {}
    for triangle in np.round(triangles, 12):
        for first, second in ((0, 1), (1, 2), (2, 0)):
            key = tuple(sorted((tuple(triangle[first]), tuple(triangle[second]))))
            edges[key] = edges.get(key, 0) + 1
    assert max(edges.values()) == 2
    chord = math.cos(math.pi / HOLE_SEGMENTS)
    for (a, b), count in edges.items():
        if count == 1:
            middle = 0.5 * (np.array(a) + np.array(b))
            on_border = np.isclose(
                np.abs(middle - (LENGTH / 2, WIDTH / 2)), (LENGTH / 2 + outer, WIDTH / 2 + outer)
            ).any()
            # (a hole's polygon edge, or a piece of one where a rectangle's side cuts it)
            on_hole = any(
                r * chord - 1e-9 <= np.hypot(*(middle - (x, y))) <= r
                for x, y, r in (cut.hole for cut in cuts)
            )
            assert on_border or on_hole, (a, b)


def covered(triangles: npt.NDArray[np.float64], point: npt.NDArray[np.float64]) -> bool:
    """Whether any of the triangles (T, 3, 2+) covers the point (x, y)."""
    a, b, c = (triangles[:, k, :2] for k in range(3))

    def side(p: npt.NDArray[np.float64], q: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return (q[:, 0] - p[:, 0]) * (point[1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (
            point[0] - p[:, 0]
        )

    sides = np.stack([side(a, b), side(b, c), side(c, a)])
    return bool(np.any(np.all(sides >= 0, axis=0) | np.all(sides <= 0, axis=0)))


def test_the_bed_has_a_hole_over_a_liner_at_each_pocket_and_none_without() -> None:
    shape = TableShape(LENGTH, WIDTH)
    for pockets in (None, POCKETS):
        mesh = build_table(shape, pockets)
        bed = (np.abs(mesh.positions[:, 2]) < 1e-12) & (mesh.normals[:, 2] > 0.5)
        triangles = mesh.positions[bed].reshape(-1, 3, 3)
        if pockets is not None:  # the lip and liner fill each hole
            mesh.extend(build_pocket_liners(shape, pockets))
        dark = np.all(np.isclose(mesh.colours, POCKET_HOLE.colour), axis=1)
        for x, y, radius in POCKETS.holes:
            liner = np.hypot(mesh.positions[:, 0] - x, mesh.positions[:, 1] - y) < 1.01 * radius
            for dx, dy in ((0.0, 0.0), (0.8 * radius, 0.0), (0.0, -0.8 * radius)):
                assert covered(triangles, np.array((x + dx, y + dy))) == (pockets is None)
            assert (dark & liner & (mesh.positions[:, 2] < -0.05)).any() == (pockets is not None)


def test_the_cushions_stop_at_the_mouths() -> None:
    shape = TableShape(LENGTH, WIDTH)
    runs = cushion_runs(shape, POCKETS)
    assert len(runs) == 6
    a = float(np.linalg.norm(POCKETS.mouths[0, 0] - POCKETS.holes[0, :2]))
    half = POCKETS.holes[1, 2]
    spans = sorted(run.span for run in runs)
    assert spans[0] == pytest.approx((a, WIDTH - a))
    assert (a, LENGTH / 2 - half) in [pytest.approx(span) for span in spans]
    assert (LENGTH / 2 + half, LENGTH - a) in [pytest.approx(span) for span in spans]
    whole = cushion_runs(shape, None)
    assert sorted(run.span for run in whole) == [(0.0, WIDTH)] * 2 + [(0.0, LENGTH)] * 2


# --- pictures ---------------------------------------------------------------------------


def picture(ctx: object, trajectory: Trajectory) -> tuple[Image, npt.NDArray[np.float64]]:
    """An overhead frame at t = 0, and a function of where points project."""
    renderer = Renderer(ctx, trajectory, SIZE, antialias=0)  # type: ignore[arg-type]
    try:
        pose = preset_pose("overhead", Stage.of(trajectory), SIZE[0] / SIZE[1])
        return renderer.frame(0.0, pose), pose.project(hole_centres(), *SIZE)
    finally:
        renderer.release()


def at(image: Image, point: npt.NDArray[np.float64]) -> npt.NDArray[np.int64]:
    return image[int(point[1]), int(point[0])].astype(np.int64)


@pytest.mark.gl
def test_holes_are_dark_with_pockets_and_absent_without(ctx: object) -> None:
    far = (LENGTH / 2, WIDTH / 2, GONE_DEPTH)  # balls 1 and 2 away (gone)
    plain, where = picture(ctx, with_balls(None, far, far))
    holed, _ = picture(ctx, with_balls(POCKETS, far, far))
    for point in where:
        assert at(plain, point).max() > 60, at(plain, point)  # cushion or rail
        assert at(holed, point).max() < 25, at(holed, point)  # into the liner


@pytest.mark.gl
def test_a_dropping_ball_shows_through_its_hole_and_not_through_the_cloth(ctx: object) -> None:
    sunk = (*SIDE_BOTTOM, 0.0)  # half below the cloth, in the side pocket
    hidden = (0.3 * LENGTH, 0.3 * WIDTH, -1.05 * RADIUS)  # under open cloth
    image, where = picture(ctx, with_balls(POCKETS, sunk, hidden))
    # the 1's white spot fills its hole's middle (half sunk: darkened to about half)
    assert at(image, where[1]).min() > 60
    pose = preset_pose("overhead", Stage.of(with_balls(None)), SIZE[0] / SIZE[1])
    spot = pose.project(np.array([[0.3 * LENGTH, 0.3 * WIDTH, 0.0]]), *SIZE)[0]
    r, g, b = at(image, spot)
    assert g > r + 25 and g > b + 25  # cloth: the 2 below it is not seen


@pytest.mark.gl
def test_a_ball_gone_down_its_pocket_is_not_drawn(ctx: object) -> None:
    # GONE_DEPTH is below the floor: look up at it from further below, where a drawn
    # ball would fill the picture's middle.
    middle = (LENGTH / 2, WIDTH / 2)
    pose = CameraPose((middle[0], middle[1] - 0.01, GONE_DEPTH - 0.4), (*middle, GONE_DEPTH), 40.0)
    frames = []
    for place in ((*middle, GONE_DEPTH), (0.2, 0.2, GONE_DEPTH)):
        renderer = Renderer(ctx, with_balls(POCKETS, place), SIZE, antialias=0)  # type: ignore[arg-type]
        try:
            frames.append(renderer.frame(0.0, pose))
        finally:
            renderer.release()
    assert np.array_equal(frames[0], frames[1])


# --- the plot ---------------------------------------------------------------------------


def pocketed_break() -> Trajectory:
    """The 1 and the 2 drop into the side-bottom pocket, the 3 into foot-left."""
    base = with_balls(POCKETS, (*SIDE_BOTTOM, GONE_DEPTH), (*SIDE_BOTTOM, GONE_DEPTH))
    events = (
        Event(0.2, "pocket", ("2",), 1.0, "side-bottom"),
        Event(0.1, "pocket", ("1",), 1.0, "side-bottom"),
        Event(0.3, "cushion", ("3",), 1.0, "foot-left"),  # a jaw: a cushion contact
        Event(0.4, "pocket", ("3",), 1.0, "foot-left"),
    )
    return dataclasses.replace(base, events=events)


def test_pocketed_balls_are_marked_at_their_pockets_in_the_order_they_dropped() -> None:
    marks = pocketed_marks(pocketed_break())
    assert [(m.ball_id, m.pocket) for m in marks] == [
        ("1", "side-bottom"),
        ("2", "side-bottom"),
        ("3", "foot-left"),
    ]
    assert marks[0].centre == pytest.approx(SIDE_BOTTOM)
    # The second ball of a pocket is moved out from the table, clear of the first.
    assert marks[1].centre[1] < marks[0].centre[1] - 2 * RADIUS
    assert marks[2].centre == pytest.approx((LENGTH, WIDTH))
    assert pocketed_marks(rolling_trajectory()) == []


def test_the_plot_draws_holes_only_for_a_table_with_pockets() -> None:
    def colour_at(trajectory: Trajectory, x: float, y: float) -> npt.NDArray[np.int64]:
        image = draw_top_view(trajectory, 600)
        column, row = Layout.fit((LENGTH, WIDTH), 600).to_pixels(np.array(x), np.array(y))
        return np.asarray(image.getpixel((round(float(column)), round(float(row)))), np.int64)

    # The head-right corner's hole, a little behind the corner of the noses.
    spot = (-0.03, -0.03)
    assert np.abs(colour_at(with_balls(POCKETS), *spot) - POCKET).max() < 8
    assert np.abs(colour_at(with_balls(None), *spot) - POCKET).max() > 40


@pytest.mark.long
def test_the_plots_hole_ends_at_the_capture_line_as_the_films_does() -> None:
    # 2 mm short of each capture line (on the table's side) the plot shows no hole; 2 mm
    # past it, the hole: its edge is the film's (PocketShapes.edge_radii), on the line
    # where a ball's centre drops. A pixel is 0.77 mm at this width.
    table = pocket_table((LENGTH, WIDTH), RADIUS)
    width_px = 3200
    image = np.asarray(draw_top_view(with_balls(POCKETS), width_px), np.int64)
    layout = Layout.fit((LENGTH, WIDTH), width_px)

    def colour_at(point: npt.NDArray[np.float64]) -> npt.NDArray[np.int64]:
        column, row = layout.to_pixels(np.array(point[0]), np.array(point[1]))
        return image[int(row), int(column)]

    for k, name in enumerate(table.names):
        normal, centre = table.capture_normal[k], POCKETS.holes[k, :2]
        on_line = centre - (normal @ centre - table.capture_level[k]) * normal
        past, short = on_line + 0.002 * normal, on_line - 0.002 * normal
        assert np.abs(colour_at(past) - POCKET).max() < 8, name
        assert np.abs(colour_at(short) - POCKET).max() > 25, name


# --- a recorded drop, through the same path as a simulated one ----------------------------


class DropIntoFootLeft:
    """A stand-in simulation result: the 1 rolls at 1 m/s along the diagonal into the
    foot-left pocket, crossing its capture line at DROP s; the cue ball stays put."""

    DROP = 0.3
    ball_ids = ("cue", "1")
    radius = RADIUS
    table_size = (LENGTH, WIDTH)
    rest_time = 0.5
    pockets = pocket_table((LENGTH, WIDTH), RADIUS)
    events = (Event(DROP, "pocket", ("1",), 1.0, "foot-left"),)
    model = "rolling"
    curved_paths = False  # straight lines

    def positions_at(self, times: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        table = self.pockets
        k = table.names.index("foot-left")
        normal, hole = table.capture_normal[k], PocketShapes.of(table).holes[k, :2]
        capture = hole - (normal @ hole - table.capture_level[k]) * normal
        rolled = np.clip(np.asarray(times), 0.0, self.DROP) - self.DROP  # <= 0
        out = np.empty((len(times), 2, 2))
        out[:, 0] = (0.25 * LENGTH, 0.5 * WIDTH)
        out[:, 1] = capture + rolled[:, None] * normal
        return out

    def path_breaks(self) -> npt.NDArray[np.float64]:
        return np.array([0.0, self.DROP])

    def spins_at(self, times: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        raise AssertionError("a rolling result's balls turn by their paths, not its spins")


class SlowDropIntoFootLeft(DropIntoFootLeft):
    """The same, at 0.3 m/s: slower than sqrt(g r), so it rolls round the edge first."""

    SPEED = 0.3

    def positions_at(self, times: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        out = super().positions_at(times)
        capture = super().positions_at(np.array([self.DROP]))[0, 1]
        out[:, 1] = capture + (out[:, 1] - capture) * self.SPEED
        return out


def test_a_slow_ball_rolls_round_the_pockets_edge_then_falls() -> None:
    from billiards.record.drop import DROP_GRAVITY
    from billiards.record.sampling import sample_trajectory

    slow = SlowDropIntoFootLeft()
    drop, speed = slow.DROP, slow.SPEED
    times = drop + np.linspace(0.0, 0.25, 251)
    trajectory = sample_trajectory(slow, times)
    capture = slow.positions_at(np.array([drop]))[0, 1]
    centre = trajectory.positions[:, 1]
    shown = centre[:, 2] > GONE_DEPTH
    # The centre's distance from the edge under where it crossed (the lip it turns on).
    reach = np.hypot(np.linalg.norm(centre[:, :2] - capture, axis=1), centre[:, 2])
    cos_leave = (7 * speed**2 / (DROP_GRAVITY * RADIUS) + 10) / 17  # 0.81 at 0.3 m/s
    on_edge = shown & (centre[:, 2] > cos_leave * RADIUS + 1e-4)
    assert on_edge.sum() >= 10  # about 10 ms and more on the edge
    assert np.allclose(reach[on_edge], RADIUS, atol=1e-6)  # turning about it
    flying = reach[shown & ~on_edge]
    assert np.all(np.diff(flying) > 0) and flying[-1] > 2 * RADIUS  # then off it, falling
    assert np.all(np.diff(centre[shown, 2]) < 0)  # down all the way
    assert not shown[-1]  # and taken away
    # A fast ball leaves the edge at once: its first fall is gravity's alone.
    fast = sample_trajectory(DropIntoFootLeft(), drop + np.array([0.0, 0.02]))
    assert fast.positions[-1, 1, 2] == pytest.approx(RADIUS - 0.5 * DROP_GRAVITY * 0.02**2)


def test_a_recorded_drop_ends_in_its_pocket_in_the_plot() -> None:
    from billiards.pictures.top_view import sample_path_bends

    trajectory = sample_path_bends(DropIntoFootLeft(), (LENGTH, WIDTH))
    assert trajectory.pockets is not None
    assert trajectory.positions[-1, 1, 2] == GONE_DEPTH
    assert trajectory.positions[-1, 1, :2] == pytest.approx((LENGTH, WIDTH))
    [mark] = pocketed_marks(trajectory)
    assert (mark.ball_id, mark.pocket, mark.centre) == ("1", "foot-left", (LENGTH, WIDTH))


def test_a_recorded_drop_thuds_after_it_drops() -> None:
    from billiards.record.window import film_trajectory
    from billiards.render.film_clock import FilmClock
    from billiards.render.sound.soundtrack import film_sound
    from billiards.render.sound.voices import POCKET_FALL_TIME, SAMPLE_RATE
    from billiards.scene.render_table import RenderSettings

    settings = RenderSettings()
    trajectory = film_trajectory(DropIntoFootLeft(), settings)
    clock = FilmClock.of(trajectory, settings.fps)
    track = film_sound(trajectory.events, clock, settings)
    landing = round((DropIntoFootLeft.DROP + POCKET_FALL_TIME - clock.start) * SAMPLE_RATE)
    assert np.max(np.abs(track[:landing])) == 0.0
    assert np.max(np.abs(track[landing : landing + SAMPLE_RATE // 10])) > 0.05


@pytest.mark.gl
def test_a_recorded_drop_is_seen_before_and_gone_after(ctx: object) -> None:
    from billiards.record.window import film_trajectory
    from billiards.scene.render_table import RenderSettings

    trajectory = film_trajectory(DropIntoFootLeft(), RenderSettings())
    renderer = Renderer(ctx, trajectory, SIZE, antialias=0)  # type: ignore[arg-type]
    try:
        pose = preset_pose("overhead", Stage.of(trajectory), SIZE[0] / SIZE[1])
        before = renderer.frame(DropIntoFootLeft.DROP - 0.1, pose)
        after = renderer.frame(float(trajectory.times[-1]), pose)
    finally:
        renderer.release()
    ball_before = DropIntoFootLeft().positions_at(np.array([DropIntoFootLeft.DROP - 0.1]))[0, 1]
    spot = pose.project(np.array([[*ball_before, RADIUS]]), *SIZE)[0]
    assert at(before, spot)[:2].min() > 150  # the 1: yellow
    r, g, b = at(after, spot)
    assert g > r + 25 and g > b + 25  # cloth: the 1 is gone from where it rolled
    hole = pose.project(np.array([[LENGTH, WIDTH, 0.0]]), *SIZE)[0]
    assert at(after, hole).max() < 25


def test_the_drawn_hole_ends_at_the_capture_line() -> None:
    # The hole's edge nearest the table is where a ball's centre drops (within 1 mm),
    # so the picture shows no pocket edge the physics does not have.
    table = pocket_table((LENGTH, WIDTH), RADIUS)
    cuts = pocket_cuts(TableShape(LENGTH, WIDTH), POCKETS)
    for k, cut in enumerate(cuts):
        x, y, radius = cut.hole
        polygon = circle_points((x, y), radius, HOLE_SEGMENTS)
        nearest = float(np.min(polygon @ table.capture_normal[k]))
        assert abs(nearest - table.capture_level[k]) < 0.001, table.names[k]


def test_a_dropping_ball_sinks_past_the_lip_before_it_is_taken_away() -> None:
    from billiards.record.drop import DROP_GONE
    from billiards.record.sampling import sample_trajectory

    drop = DropIntoFootLeft.DROP
    times = drop + np.arange(0, 10) / 60.0
    trajectory = sample_trajectory(DropIntoFootLeft(), times)
    z = trajectory.positions[:, 1, 2]
    shown = z > GONE_DEPTH
    assert np.all(np.diff(z[shown]) < 0)  # sinking all the way
    assert RADIUS - z[shown][-1] > (DROP_GONE - 1.5) * RADIUS  # deep when it goes
    assert shown.sum() >= 5  # seen sinking over several frames at 60 fps
    # It carries on into the hole: towards the corner, past where it was captured.
    table = DropIntoFootLeft.pockets
    k = table.names.index("foot-left")
    past = trajectory.positions[shown, 1, :2] @ table.capture_normal[k] - table.capture_level[k]
    assert np.all(np.diff(past) >= 0) and past[-1] > 0.5 * RADIUS


@pytest.mark.gl
def test_a_ball_seen_from_above_darkens_as_it_sinks_and_is_dark_when_taken_away(
    ctx: object,
) -> None:
    from billiards.record.window import film_trajectory
    from billiards.scene.render_table import RenderSettings

    trajectory = film_trajectory(DropIntoFootLeft(), RenderSettings(fps=60.0, shutter=0.0))
    renderer = Renderer(ctx, trajectory, (384, 216), antialias=0)  # type: ignore[arg-type]
    pose = preset_pose("overhead", Stage.of(trajectory), 16 / 9)
    frames = trajectory.times[(trajectory.times >= DropIntoFootLeft.DROP - 0.02)][:14]
    brightness = []
    try:
        for time in frames:
            centre = trajectory.positions[np.searchsorted(trajectory.times, time), 1]
            if centre[2] <= GONE_DEPTH:
                break
            image = renderer.frame(float(time), pose)
            top = np.array([[centre[0], centre[1], centre[2] + RADIUS]])
            x, y = pose.project(top, 384, 216)[0]
            patch = image[round(y) - 1 : round(y) + 2, round(x) - 1 : round(x) + 2]
            brightness.append(float(patch.max()))
    finally:
        renderer.release()
    assert len(brightness) >= 6
    assert brightness[0] > 150  # the 1, lit on the lip
    assert all(b <= a + 8 for a, b in itertools.pairwise(brightness))
    assert brightness[-1] < 30  # black in the liner by the time it is taken away


def test_each_jaw_is_the_cushions_rubber_rounding_on_the_physics_jaw_circle() -> None:
    # No separate posts: the cushion's own nose (its profile's nose point) sweeps round
    # each jaw's circle, from the nose line into the end's face.
    shape = TableShape(LENGTH, WIDTH)
    mesh = build_table(shape, POCKETS)
    green = np.all(np.isclose(mesh.colours, CUSHION_GREEN.colour), axis=1)
    nose_height = shape.nose_height - 0.006  # the profile's point on the nose line
    at_nose = mesh.positions[green & np.isclose(mesh.positions[:, 2], nose_height)][:, :2]
    for x, y in POCKETS.jaws:
        distance = np.hypot(at_nose[:, 0] - x, at_nose[:, 1] - y)
        on_circle = at_nose[np.abs(distance - POCKETS.jaw_radius) < 1e-9]
        angles = np.unique(np.round(np.arctan2(on_circle[:, 1] - y, on_circle[:, 0] - x), 9))
        assert len(angles) == JAW_STEPS + 1
        # The turn runs from the nose's normal to the face's: 45 degrees at a corner,
        # more at a side pocket, whose face leans away from it.
        span = np.ptp(np.unwrap(np.sort(angles)))
        assert math.radians(44) < span < math.radians(120)


@pytest.mark.gl
def test_a_pockets_shelf_and_liner_are_dark_not_a_pale_rim(ctx: object) -> None:
    # The leather between the hole and the rail's cut, seen from above where the lamp
    # shines straight down on it (a glossy leather read as a pale grey ring there).
    far = (LENGTH / 2, WIDTH / 2, GONE_DEPTH)
    trajectory = with_balls(POCKETS, far, far)
    cuts = pocket_cuts(TableShape(LENGTH, WIDTH), POCKETS)
    size = (384, 216)
    renderer = Renderer(ctx, trajectory, size, antialias=0)  # type: ignore[arg-type]
    try:
        for preset in ("overhead",):
            pose = preset_pose(preset, Stage.of(trajectory), size[0] / size[1])
            image = renderer.frame(0.0, pose)
            for cut in cuts[1::3]:  # the side pockets
                x, y, radius = cut.hole
                away = -1.0 if y < WIDTH / 2 else 1.0  # off the table
                points = np.array(
                    [
                        (x + dx, y + away * math.sqrt((radius + 0.006) ** 2 - dx**2), 0.0)
                        for dx in (-0.03, 0.0, 0.03)
                    ]
                )
                for point in pose.project(points, *size):
                    if 0 <= point[0] < size[0] and 0 <= point[1] < size[1]:
                        assert at(image, point).max() < 40, (preset, at(image, point))
    finally:
        renderer.release()


def test_a_pockets_liner_goes_down_from_a_lip_and_darkens_with_depth() -> None:
    shape = TableShape(LENGTH, WIDTH)
    liners = build_pocket_liners(shape, POCKETS)
    x, y, radius = pocket_cuts(shape, POCKETS)[0].hole
    near = np.hypot(liners.positions[:, 0] - x, liners.positions[:, 1] - y)
    mine = near < radius + shape.pocket_lip + 1e-9
    z, light = liners.positions[mine, 2], liners.colours[mine].sum(axis=1)
    # From the cloth's edge (the lip's top, as wide as the cloth's cut) to the bottom.
    assert z.max() == 0.0 and z.min() == pytest.approx(-shape.liner_depth)
    assert near[mine].max() == pytest.approx(radius + shape.pocket_lip)
    # Lighter near the top (lamp-lit leather), black at the bottom.
    top, deep = light[z > -0.01].mean(), light[z < -0.08].mean()
    assert deep < 0.2 * top
    np.testing.assert_allclose(liners.colours[mine][z < -0.08], 0.0016, atol=2e-3)


def test_the_sights_are_small_pearl_diamonds_inlaid_in_a_setting() -> None:
    shape = TableShape(LENGTH, WIDTH)
    mesh = build_table(shape, None)
    pearl = np.all(np.isclose(mesh.colours, SIGHT_PEARL.colour), axis=1)
    setting = np.all(np.isclose(mesh.colours, SIGHT_SETTING.colour), axis=1)
    assert pearl.sum() == setting.sum() == 6 * len(shape.sights())
    # Flush with the rail's top, within a third of a millimetre.
    assert np.all(mesh.positions[pearl, 2] - shape.rail_top < 0.0004)
    # 16 x 8 mm: a diamond's corners 8 mm along and 4 mm across from its middle.
    first = mesh.positions[pearl][:6, :2]
    span = first.max(axis=0) - first.min(axis=0)
    assert sorted(span.round(4).tolist()) == [0.008, 0.016]


def hole_in_picture(
    pose: CameraPose, size: tuple[int, int], hole: tuple[float, float, float]
) -> npt.NDArray[np.bool_]:
    """The pixels whose ray meets the cloth's plane inside the hole (x, y, radius)."""
    width, height = size
    right, up, forward = pose.basis()
    half = math.tan(math.radians(pose.fov) / 2)
    ys, xs = np.mgrid[0:height, 0:width] + 0.5
    across = (2 * xs / width - 1) * half * width / height
    upward = (1 - 2 * ys / height) * half
    rays = forward + across[..., None] * right + upward[..., None] * up
    eye = np.array(pose.eye)
    reach = -eye[2] / np.minimum(rays[..., 2], -1e-9)
    landing = eye[:2] + reach[..., None] * rays[..., :2]
    return np.hypot(landing[..., 0] - hole[0], landing[..., 1] - hole[1]) < hole[2]


@pytest.mark.long
@pytest.mark.gl
@pytest.mark.parametrize("scene", ["pocket_shot", "pool_break", "throw_shot"])
def test_no_drop_frame_shows_a_sunk_ball_over_the_hole_at_full_brightness(
    ctx: object, scene: str
) -> None:
    # The film's own frames (the director's view of the pocket) from the drop on: once
    # the ball's centre is below the cloth, its pixels over the hole (drawn minus the
    # same frame without it) are darker than its bright parts on the cloth before.
    from billiards.record.window import cue_strike_of, film_trajectory
    from billiards.render.film import camera_poses, camera_timeline
    from billiards.render.film_clock import FilmClock
    from billiards.scene.reader import load_scene
    from billiards.scene.render_table import RenderSettings
    from billiards.simulation import simulate_scene

    size = (320, 180)
    settings = RenderSettings(width=size[0], height=size[1])
    loaded = load_scene(scene)
    trajectory = film_trajectory(simulate_scene(loaded), settings, strike=cue_strike_of(loaded))
    assert trajectory.pockets is not None
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    poses = [pose for pose, _ in camera_poses(camera_timeline(trajectory, settings), clock)]
    drop = next(event for event in trajectory.events if event.kind == "pocket")
    ball = trajectory.ball_ids.index(drop.balls[0])
    gone = trajectory.positions.copy()
    gone[:, ball, 2] = GONE_DEPTH
    shape = TableShape(*trajectory.table_size)
    names = trajectory.pockets.names
    hole = pocket_cuts(shape, trajectory.pockets)[names.index(drop.pocket)].hole
    drawn = Renderer(ctx, trajectory, size)  # type: ignore[arg-type]
    without = Renderer(ctx, dataclasses.replace(trajectory, positions=gone), size)  # type: ignore[arg-type]
    weights = np.array([0.2126, 0.7152, 0.0722])
    first = int(np.searchsorted(clock.sim_times, drop.time))
    sunk_frames = 0
    try:
        for frame in range(first - 1, first + 6):
            time, pose = float(clock.sim_times[frame]), poses[frame]
            with_ball, empty = (
                np.frombuffer(r.draw(time, pose), np.uint8).reshape(size[1], size[0], 4)[..., :3]
                for r in (drawn, without)
            )
            ball_pixels = np.abs(with_ball.astype(int) - empty.astype(int)).sum(axis=2) > 30
            luma = with_ball @ weights
            if frame == first - 1:  # on the cloth still: its bright parts
                assert drop.time > time and ball_pixels.sum() > 100
                bright = float(np.percentile(luma[ball_pixels], 90))
                continue
            sample = int(np.searchsorted(trajectory.times, time))
            if trajectory.positions[sample, ball, 2] >= 0.0:
                continue  # tipping over the edge, its top in the lamp's light
            sunk_frames += 1
            over = ball_pixels & hole_in_picture(pose, size, hole)
            assert np.count_nonzero(over & (luma >= 0.9 * bright)) <= 0.02 * over.sum()
            if over.any():
                assert luma[over].mean() < 0.6 * bright
    finally:
        drawn.release()
        without.release()
    assert sunk_frames >= 1
