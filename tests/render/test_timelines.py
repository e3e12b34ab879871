"""Camera timelines, the film clock and ball textures (no GL)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from billiards.record.trajectory import ball_state
from billiards.render.film_clock import FilmClock
from billiards.scene.render_table import PRESETS, CameraShot
from billiards.stage.ball_colors import ball_color
from billiards.stage.cameras import CameraTimeline, Stage, default_shots, preset_pose
from billiards.stage.textures import ball_texture, texel_directions
from tests.render.fixtures import rolling_trajectory


def test_every_preset_looks_at_the_table_from_where_it_says() -> None:
    stage = Stage.of(rolling_trajectory())
    for name in PRESETS:
        pose = preset_pose(name, stage)
        # The table's centre is in the picture (the rack view's subject is the impact).
        seen = stage.impact if name == "rack" else (stage.length / 2, stage.width / 2, 0.0)
        x, y = pose.project(np.array([seen]), 160, 90)[0]
        assert 0 <= x <= 160 and 0 <= y <= 90, name
    assert preset_pose("overhead", stage).eye[2] > 1.5
    assert preset_pose("low_side", stage).eye[2] < 0.3
    behind = preset_pose("behind_cue", stage)
    assert behind.eye[0] < stage.cue_start[0] < behind.target[0]


def test_shots_cut_ease_and_orbit() -> None:
    stage = Stage.of(rolling_trajectory())
    shots = (
        CameraShot(preset="overhead"),
        CameraShot(start=1.0, preset="orbit", orbit=90.0),
        CameraShot(
            start=3.0, eye=(0.0, 0.0, 1.0), target=(1.0, 0.5, 0.0), transition="ease", ease=1.0
        ),
    )
    timeline = CameraTimeline(shots, stage, 16 / 9)
    overhead, orbit = preset_pose("overhead", stage), preset_pose("orbit", stage)
    assert timeline.pose(0.99) == overhead  # a cut: the old shot up to the new start
    assert timeline.pose(1.0) == orbit
    # The orbit turns the eye about the vertical through the target: 90 degrees a second.
    turned = timeline.pose(2.0)
    tx, ty, _ = orbit.target
    before = math.atan2(orbit.eye[1] - ty, orbit.eye[0] - tx)
    after = math.atan2(turned.eye[1] - ty, turned.eye[0] - tx)
    assert math.isclose((after - before) % (2 * math.pi), math.pi / 2, rel_tol=1e-9)
    assert math.isclose(math.dist(turned.eye[:2], (tx, ty)), math.dist(orbit.eye[:2], (tx, ty)))
    # The ease starts at the orbit's pose and ends at the new one, halfway in between.
    assert timeline.pose(3.0).eye == pytest.approx(timeline._shot_pose(timeline.shots[1], 3.0).eye)
    middle = timeline.pose(3.5)
    orbit_then = timeline._shot_pose(timeline.shots[1], 3.5)
    assert middle.eye == pytest.approx(
        tuple((a + b) / 2 for a, b in zip(orbit_then.eye, (0.0, 0.0, 1.0), strict=True))
    )
    assert timeline.pose(4.0).eye == (0.0, 0.0, 1.0)


def test_default_film_is_wide_then_low_at_the_rack_then_overhead_then_eases_out() -> None:
    # The cue ball meets the rack at 0.9 s and stops at 10.2 s; the film ends at 11.
    trajectory = rolling_trajectory(end=11.0)
    shots = default_shots(trajectory)
    assert [shot.preset for shot in shots] == ["corner", "rack", "overhead", "corner"]
    assert [shot.transition for shot in shots[1:]] == ["cut", "cut", "ease"]
    # Starts are simulation seconds: the rack shot opens just before the impact.
    assert shots[1].start is not None and 0.6 < shots[1].start < 0.9
    assert shots[2].start is not None and shots[2].start > 0.9 + 0.5
    # The ease out ends within the film, after the last ball has stopped.
    assert shots[3].start is not None
    assert trajectory.rest_time <= shots[3].start + shots[3].ease <= trajectory.times[-1]


def test_rack_view_is_low_and_sees_the_impact() -> None:
    stage = Stage.of(rolling_trajectory())
    pose = preset_pose("rack", stage)
    assert pose.eye[2] < 0.2
    x, y = pose.project(np.array([stage.impact]), 160, 90)[0]
    assert 20 <= x <= 140 and 15 <= y <= 75


def test_film_clock_uses_the_recorded_frames_at_the_trajectory_rate() -> None:
    trajectory = rolling_trajectory(fps=30.0)
    clock = FilmClock.real_time(trajectory, 30.0)
    assert np.array_equal(clock.sim_times, trajectory.times)
    assert clock.duration == pytest.approx(len(trajectory.times) / 30.0)
    doubled = FilmClock.real_time(trajectory, 60.0)
    assert doubled.frame_count == 2 * (clock.frame_count - 1) + 1


def test_ball_state_is_exact_on_frames_and_blends_between() -> None:
    trajectory = rolling_trajectory()
    positions, _ = ball_state(trajectory, float(trajectory.times[20]))
    assert np.array_equal(positions, trajectory.positions[20])
    middle, turned = ball_state(trajectory, float(trajectory.times[20] + trajectory.times[21]) / 2)
    assert middle[0, 0] == pytest.approx(
        (trajectory.positions[20, 0, 0] + trajectory.positions[21, 0, 0]) / 2
    )
    assert np.linalg.norm(turned, axis=1) == pytest.approx(1.0)


def test_ball_textures_show_the_standard_set() -> None:
    width = 128
    d = texel_directions(width, width // 2)
    equator_front = np.unravel_index(
        np.argmin(np.linalg.norm(d - (1.0, 0.0, 0.0), axis=-1)), d.shape[:2]
    )
    pole = (0, 0)
    solid, stripe = ball_texture("3", width), ball_texture("11", width)
    red = np.array(ball_color("3").rgb)
    # A solid is its colour all over (away from the number discs at +-z) ...
    assert np.abs(solid[equator_front][:3].astype(int) - red).max() < 10
    assert np.abs(solid[pole][:3].astype(int) - red).max() < 10
    # ... a stripe is white at the poles and coloured on its band.
    assert np.abs(stripe[equator_front][:3].astype(int) - red).max() < 10
    assert stripe[pole][:3].min() > 200
    # The number disc faces up (+z) at the start: white there, with dark ink nearby.
    top = np.unravel_index(np.argmin(np.linalg.norm(d - (0.0, 0.0, 1.0), axis=-1)), d.shape[:2])
    rows, cols = slice(top[0] - 6, top[0] + 7), slice(top[1] - 6, top[1] + 7)
    assert solid[rows, cols, :3].max() > 200 and solid[rows, cols, :3].min() < 80
    cue = ball_texture("cue", width)
    assert cue[equator_front][0] > 150 and cue[equator_front][1] < 80  # a red mark at +x


def test_the_renderer_never_imports_the_physics() -> None:
    """Only the events type, which the trajectory hands over, may come along."""
    import subprocess
    import sys

    modules = "render.film render.gl.renderer render.film_clock render.slow_motion"
    modules += " render.sound.soundtrack render.gl.context stage.cameras stage.table"
    modules += " stage.room stage.textures"
    imports = "; ".join(f"import billiards.{name}" for name in modules.split())
    imports += "; import billiards.record.window; import billiards.scene.render_table"
    code = f"import sys; {imports}; import billiards.render.video; print(' '.join(sys.modules))"
    loaded = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    physics = {name for name in loaded if name.startswith("billiards.physics")}
    assert physics <= {
        "billiards.physics",
        "billiards.physics.engine",
        "billiards.physics.engine.events",
    }


def test_a_shots_own_fov_overrides_its_presets_even_when_it_is_40() -> None:
    stage = Stage.of(rolling_trajectory())
    preset = preset_pose("behind_cue", stage)
    assert preset.fov != 40.0
    given = CameraTimeline((CameraShot(preset="behind_cue", fov=40.0),), stage, 16 / 9)
    assert given.pose(0.0).fov == 40.0
    left = CameraTimeline((CameraShot(preset="behind_cue"),), stage, 16 / 9)
    assert left.pose(0.0).fov == preset.fov
