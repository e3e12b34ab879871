"""The cue in the film: it lies along the stroke, meets the ball as it leaves, follows
through and goes (billiards.stage.cue), and its strike is heard."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from billiards.record.trajectory import CueStrike, Trajectory
from billiards.record.window import cue_strike_of
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import ContextError, create_context
from billiards.render.gl.frame_output import region_of
from billiards.render.gl.renderer import Renderer
from billiards.render.sound.soundtrack import film_sound
from billiards.render.sound.voices import SAMPLE_RATE
from billiards.scene.reader import load_scene, parse_scene
from billiards.scene.render_table import RenderSettings
from billiards.scene.stroke import Stroke, strike
from billiards.stage.cameras import CameraPose
from billiards.stage.cue import SECTIONS, CueStroke, cue_mesh
from billiards.stage.table_plan import TableShape
from tests.render.fixtures import CUE_START, LENGTH, RADIUS, WIDTH, rolling_trajectory

TABLE = TableShape(LENGTH, WIDTH)
CENTRE = np.array([*CUE_START, RADIUS])
LEVEL = CueStrike("cue", 0.0, 0.0, (0.0, 0.0), 3.0)
MASSE = CueStrike("cue", -25.0, 40.0, (-0.7, -0.3), 2.8)


def stroke_of(cue: CueStrike) -> CueStroke:
    return CueStroke.of(cue, CENTRE, RADIUS, TABLE)


@pytest.mark.parametrize("cue", [LEVEL, MASSE], ids=["level", "masse"])
def test_the_tip_meets_the_ball_on_its_surface_as_it_leaves(cue: CueStrike) -> None:
    stroke = stroke_of(cue)
    placement = stroke.placement(0.0)
    assert placement is not None
    np.testing.assert_allclose(np.linalg.norm(placement.tip - CENTRE), RADIUS, atol=1e-12)


@pytest.mark.parametrize("cue", [LEVEL, MASSE], ids=["level", "masse"])
def test_the_cue_lies_along_the_stroke_through_its_tip_offset(cue: CueStrike) -> None:
    stroke = stroke_of(cue)
    placement = stroke.placement(-0.3)
    assert placement is not None
    forward = placement.forward
    # Its line on the cloth is the stroke's direction, its drop the drawn elevation.
    heading = math.degrees(math.atan2(forward[1], forward[0]))
    assert heading == pytest.approx(cue.direction, abs=1e-9)
    assert math.degrees(math.asin(-forward[2])) == pytest.approx(stroke.elevation, abs=1e-9)
    assert stroke.elevation >= cue.elevation
    # The axis passes the centre at the tip's offset, b = r sqrt(side^2 + height^2).
    to_centre = CENTRE - placement.tip
    across = to_centre - np.dot(to_centre, forward) * forward
    assert np.linalg.norm(across) == pytest.approx(RADIUS * math.hypot(*cue.tip), abs=1e-12)


def test_the_cue_draws_back_strikes_at_its_speed_and_follows_through() -> None:
    stroke = stroke_of(LEVEL)
    gaps = {t: stroke.gap(t) for t in (-0.5, -0.25, -0.12, -0.001, 0.0, 0.05)}
    assert gaps[-0.5] is not None and gaps[-0.25] is not None and gaps[-0.12] is not None
    assert 0 < gaps[-0.5] < gaps[-0.25] < gaps[-0.12]  # addressing, then drawing back
    assert gaps[0.0] == pytest.approx(0.0, abs=1e-15)
    step = 1e-6
    before = stroke.gap(-step)
    assert before is not None
    assert before / step == pytest.approx(LEVEL.speed, rel=1e-3)  # it meets the ball at V
    follow = gaps[0.05]
    assert follow is not None and follow < 0  # past where the ball was
    assert stroke.placement(3.0) is None  # drawn away


def test_a_level_stroke_is_tilted_over_the_rail_behind_the_ball() -> None:
    """pool_break's cue ball is 0.53 m from the head cushion: a level stick drawn back
    would go through the rail; drawn, its underside passes above it."""
    stroke = stroke_of(LEVEL)
    assert stroke.elevation > 0
    placement = stroke.placement(-0.12)  # drawn back furthest
    assert placement is not None
    along = placement.tip[0] / placement.forward[0]  # back along the axis to x = 0
    underside = placement.tip[2] - along * placement.forward[2] - max(s[3] for s in SECTIONS)
    assert underside > TABLE.rail_top


def test_the_cue_mesh_is_a_stick_of_58_inches_round_its_axis() -> None:
    mesh = cue_mesh()
    low, high = mesh.bounds()
    assert high[0] - low[0] == pytest.approx(1.47)
    radii = np.hypot(mesh.positions[:, 1], mesh.positions[:, 2])
    assert radii.max() < 0.015 and radii[mesh.positions[:, 0] < 0.03].max() < 0.0066


def test_a_cue_ball_given_a_velocity_is_struck_level_at_the_speed_that_gives_it() -> None:
    scene = load_scene("pool_break")
    cue = cue_strike_of(scene)
    assert cue is not None and cue.ball == "cue" and cue.elevation == 0.0
    ball = scene.balls[0]
    assert cue.tip == ball.tip
    assert cue.direction == pytest.approx(
        math.degrees(math.atan2(ball.velocity[1], ball.velocity[0]))
    )
    given = strike(Stroke(cue.speed, cue.direction, 0.0, cue.tip), ball.mass, scene.radius)
    assert given.ball_speed == pytest.approx(math.hypot(*ball.velocity), rel=1e-12)


def test_a_stroke_is_drawn_as_written_and_a_resting_scene_has_none() -> None:
    cue = cue_strike_of(load_scene("masse_shot"))
    assert cue == CueStrike("cue", -25.0, 40.0, (-0.7, -0.3), 2.8)
    resting = parse_scene('[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\n')
    assert cue_strike_of(resting) is None


def test_a_saved_trajectory_keeps_its_strike(tmp_path: Path) -> None:
    trajectory = dataclasses.replace(rolling_trajectory(), strike=MASSE)
    trajectory.save(tmp_path / "t.npz")
    assert Trajectory.load(tmp_path / "t.npz").strike == MASSE
    rolling_trajectory().save(tmp_path / "none.npz")
    assert Trajectory.load(tmp_path / "none.npz").strike is None


def test_the_strike_is_heard_at_t0_unless_the_cue_is_off() -> None:
    trajectory = dataclasses.replace(rolling_trajectory(), events=())
    clock = FilmClock.of(trajectory, 30.0, 1.0)
    at = round((0.0 - clock.start) * SAMPLE_RATE)
    on = film_sound((), clock, RenderSettings(), LEVEL)
    off = film_sound((), clock, RenderSettings(cue=False), LEVEL)
    assert np.abs(on[:at]).max() == 0.0
    assert np.abs(on[at : at + SAMPLE_RATE // 50]).max() > 0.1
    assert np.abs(off).max() == 0.0


# --- drawn --------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def pictures() -> Iterator[tuple[Renderer, Renderer]]:
    try:
        ctx = create_context()
    except ContextError as error:
        pytest.skip(f"no headless OpenGL context: {error}")
    trajectory = dataclasses.replace(rolling_trajectory(start=-0.5), strike=LEVEL)
    with_cue = Renderer(ctx, trajectory, (320, 180), antialias=0)
    without = Renderer(ctx, trajectory, (320, 180), antialias=0, cue=False)
    yield with_cue, without
    with_cue.release()
    without.release()
    ctx.release()


BEHIND = CameraPose(
    (CUE_START[0] - 0.6, CUE_START[1], 0.35), (CUE_START[0] + 0.3, CUE_START[1], 0.0), 40.0
)


@pytest.mark.gl
def test_the_cue_is_drawn_behind_the_ball_until_it_is_drawn_away(
    pictures: tuple[Renderer, Renderer],
) -> None:
    with_cue, without = pictures
    before = with_cue.frame(-0.3, BEHIND).astype(int) - without.frame(-0.3, BEHIND)
    changed = np.abs(before).sum(axis=2) > 30
    # The stick comes up the middle of the picture from its bottom edge, towards the ball.
    assert changed[-5:, 150:170].any()
    assert changed.sum() > 150
    # The shaft is pale maple, lighter than the cloth it covers.
    assert (
        with_cue.frame(-0.3, BEHIND)[changed].mean() > without.frame(-0.3, BEHIND)[changed].mean()
    )
    after = with_cue.frame(1.0, BEHIND).astype(int) - without.frame(1.0, BEHIND)
    assert np.abs(after).max() == 0


@pytest.mark.gl
def test_a_picture_with_the_cue_repeats_bit_for_bit(pictures: tuple[Renderer, Renderer]) -> None:
    with_cue, _ = pictures
    assert with_cue.draw(-0.02, BEHIND) == with_cue.draw(-0.02, BEHIND)


def test_a_raised_cue_follows_through_no_lower_than_the_cloth() -> None:
    stroke = stroke_of(MASSE)
    lowest = min(
        stroke.placement(t).tip[2]  # type: ignore[union-attr]
        for t in np.linspace(0.0, 0.5, 101)
        if stroke.placement(t) is not None
    )
    assert lowest >= SECTIONS[0][2] * math.cos(math.radians(MASSE.elevation)) - 1e-12


SIDE = CameraPose(
    (CUE_START[0] - 0.35, CUE_START[1] - 0.7, 0.55), (CUE_START[0] - 0.35, CUE_START[1], 0.0), 40.0
)


@pytest.mark.gl
def test_the_cue_casts_a_soft_shadow_on_the_cloth_under_it(
    pictures: tuple[Renderer, Renderer],
) -> None:
    with_cue, _ = pictures
    shown = with_cue.frame(-0.02, SIDE).astype(int)
    cue_pass = with_cue.cue_pass
    assert cue_pass is not None
    cue_pass.shadow_rect = lambda placement: None  # type: ignore[method-assign]
    try:
        bare = with_cue.frame(-0.02, SIDE).astype(int)  # the stick alone
    finally:
        del cue_pass.shadow_rect
    darker = (bare - shown).sum(axis=2)
    shadow = darker > 20
    assert shadow.sum() > 40  # a band along the stick, seen from the side
    # a third of the light or more taken under the thin stick (0.67 here), not all of it
    worst = np.unravel_index(np.argmax(darker), darker.shape)
    ratio = shown[worst].sum() / bare[worst].sum()
    assert 0.3 < ratio < 0.75
    # only on the cloth round the stick, where CuePass says it may fall
    placement = cue_pass.stroke.placement(-0.02)
    assert placement is not None
    region = region_of(cue_pass.shadow_corners(placement), SIDE, with_cue.size)
    assert region is not None
    x0, y0, x1, y1 = region
    rows, columns = np.nonzero(darker > 3)
    assert rows.min() >= y0 and rows.max() < y1 and columns.min() >= x0 and columns.max() < x1
    # soft: from its core it fades over several pixels, not at once
    column = darker[:, worst[1]]
    assert np.count_nonzero((column > 3) & (column < 0.5 * column.max())) >= 2
