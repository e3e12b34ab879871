"""Recorded trajectories: sampling, the rolling rotation, save and load."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from billiards.record.orientations import rolling_rotation
from billiards.record.quaternions import rotate
from billiards.record.sampling import record_trajectory
from billiards.record.trajectory import Trajectory
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene
from tests.scenes import R, scene_of


@pytest.mark.parametrize("heading", [0.0, 0.7, 2.5, -1.9])
def test_rolling_rotation_leaves_the_contact_point_at_rest(heading: float) -> None:
    # Over a tiny step ds the material point under the centre must move by -ds
    # relative to the centre, cancelling the centre's own motion.
    ds = 1e-6
    step = ds * np.array([[np.cos(heading), np.sin(heading)]])
    turn = rolling_rotation(step, R)[0]
    bottom = np.array([0.0, 0.0, -R])
    moved = rotate(turn, bottom) - bottom
    assert np.allclose(moved[:2] + step[0], 0.0, atol=1e-15)
    assert abs(moved[2]) < 1e-10
    # ... and the top moves forward by ds as well (twice the centre's speed).
    top = np.array([0.0, 0.0, R])
    assert np.allclose((rotate(turn, top) - top)[:2], step[0], atol=1e-15)


def test_rolling_rotation_is_three_steps_about_the_horizontal_axis() -> None:
    step = np.array([[0.03, -0.02]])
    turn = rolling_rotation(step, R)[0]
    axis = np.array([0.02, 0.03, 0.0]) / np.hypot(0.03, 0.02)  # z x v_hat
    angle = np.hypot(0.03, 0.02) / R
    expected = np.array([*(np.sin(angle / 2) * axis), np.cos(angle / 2)])
    assert np.allclose(turn, expected, atol=1e-15)


def test_a_ball_rolled_one_circumference_returns_to_its_orientation() -> None:
    speed = 0.4
    scene = scene_of([("cue", (0.3, 0.5), (speed, 0.0))])
    result = simulate_scene(scene)
    circumference = 2 * np.pi * R
    # time at which it has rolled one circumference: s = v t - a t^2 / 2
    a = 0.0981
    t = (speed - np.sqrt(speed**2 - 2 * a * circumference)) / a
    trajectory = record_trajectory(result, fps=1 / t, start=0.0, end=t)
    assert trajectory.times[-1] == pytest.approx(t, rel=1e-12)
    q = trajectory.orientations[-1, 0]
    # One full turn about a fixed axis is the quaternion -identity (not +identity,
    # which a ball that never turned would also give).
    assert q == pytest.approx([0.0, 0.0, 0.0, -1.0], abs=1e-9)


def test_trajectory_samples_the_film_window_and_survives_save_and_load(tmp_path: Path) -> None:
    result = simulate_scene(load_scene())
    trajectory = record_trajectory(result, fps=30, start=-0.5, end=result.rest_time + 1)
    assert trajectory.times[0] == -0.5
    assert trajectory.fps == pytest.approx(30)
    assert trajectory.times[-1] <= result.rest_time + 1 < trajectory.times[-1] + 1 / 30
    count = len(trajectory.times)
    assert trajectory.positions.shape == (count, 16, 3)
    assert trajectory.orientations.shape == (count, 16, 4)
    assert np.allclose(np.linalg.norm(trajectory.orientations, axis=2), 1.0)
    # Before the shot the balls wait where they start, unturned.
    assert np.array_equal(trajectory.positions[0, :, :2], result.initial_positions)
    assert np.array_equal(trajectory.orientations[0], np.tile([0.0, 0, 0, 1], (16, 1)))
    assert np.all(trajectory.positions[..., 2] == R)
    path = tmp_path / "break.npz"
    trajectory.save(path)
    loaded = Trajectory.load(path)
    assert loaded.ball_ids == trajectory.ball_ids
    assert loaded.events == trajectory.events
    assert np.array_equal(loaded.positions, trajectory.positions)
    assert np.array_equal(loaded.orientations, trajectory.orientations)
    assert loaded.rest_time == trajectory.rest_time and loaded.table_size == trajectory.table_size


def test_a_saved_trajectory_carries_its_scenes_render_settings_typed(tmp_path: Path) -> None:
    import dataclasses

    from billiards.scene.reader import parse_scene

    scene = parse_scene(
        '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [0.5, 0]\n'
        "[render]\nwidth = 320\nheight = 180\nfps = 24\nsound = false\n"
        '[[camera]]\npreset = "overhead"\n'
        '[[camera]]\nstart = 1\neye = [1, -1, 0.5]\ntarget = [1, 0.5, 0]\ntransition = "ease"\n',
        "small.toml",
    )
    trajectory = dataclasses.replace(
        record_trajectory(simulate_scene(scene), fps=10.0),
        scene_source=scene.source,
        render_settings=scene.render,
    )
    trajectory.save(tmp_path / "t.npz")
    loaded = Trajectory.load(tmp_path / "t.npz")
    assert loaded.scene_source == "small.toml"
    assert loaded.render_settings == scene.render  # the same typed settings, eye a tuple
    unsaved = record_trajectory(simulate_scene(scene), fps=10.0)
    unsaved.save(tmp_path / "u.npz")
    assert Trajectory.load(tmp_path / "u.npz").render_settings is None


def test_render_settings_read_back_from_a_record_are_checked() -> None:
    from billiards.scene.render_table import RenderSettings, settings_from_record, settings_record

    record = settings_record(RenderSettings())
    assert settings_from_record(record) == RenderSettings()
    with pytest.raises(ValueError, match=r"fps = 0\.5: expected a number in"):
        settings_from_record({**record, "fps": 0.5})
    with pytest.raises(ValueError, match="not a record of render settings"):
        settings_from_record({**record, "speed": 2})
