"""The exported glTF read back: the balls where the simulation has them, at any time."""

from __future__ import annotations

import functools
import math
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from billiards.export import ExportReport, export_gltf
from billiards.export.gltf import to_gltf_points, to_gltf_rotations
from billiards.export.tracks import fall_duration
from billiards.physics.engine.result import SimulationResult
from billiards.record import quaternions
from billiards.record.drop import DROP_GRAVITY
from billiards.record.orientations import rolling_orientations, spin_orientations
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene
from billiards.stage.rack_turns import turns_of
from tests.commands import run_module
from tests.export.gltf_reading import node_channels, read_document

EPS32 = float(np.finfo(np.float32).eps)


@functools.cache
def simulated(name: str) -> SimulationResult:
    return simulate_scene(load_scene(name))


_EXPORTS: dict[str, tuple[Path, ExportReport]] = {}


@pytest.fixture(scope="module", name="exported")
def exported_fixture(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], Path]:
    """`exported(name)`: the shipped scene's .glb, exported once for the module."""

    def exported(name: str) -> Path:
        if name not in _EXPORTS:
            path = tmp_path_factory.mktemp("export") / f"{name}.glb"
            _EXPORTS[name] = (path, export_gltf(simulated(name), path))
        return _EXPORTS[name][0]

    return exported


def float32_tolerance(result: SimulationResult) -> float:
    """m: what float32 storage allows at any time: the values' rounding (a table's
    length) and the key times' rounding (an ulp of the longest time, at the fastest
    speed), with a factor 4 for the Hermite sums."""
    speed = float(np.max(np.hypot(*result.initial_velocities.T)))
    return 4 * EPS32 * (max(result.table_size) + speed * max(result.rest_time, 1.0))


@pytest.mark.long
@pytest.mark.parametrize("name", ["break", "pool_break"])
def test_ball_centres_equal_the_simulation_to_float32_rounding(
    name: str, exported: Callable[[str], Path]
) -> None:
    result = simulated(name)
    path = exported(name)
    report = _EXPORTS[name][1]
    assert report.deviation < 1e-12  # the keys' curves in float64: the simulated path
    channels = node_channels(read_document(path))
    drops = {e.balls[0]: e.time for e in result.events if e.kind == "pocket"}
    times = np.random.default_rng(34).uniform(0.0, result.rest_time, 300)
    simulated_positions = result.positions_at(times)
    tolerance = float32_tolerance(result)
    worst = 0.0
    for index, ball in enumerate(result.ball_ids):
        translation = channels[f"ball-{ball}"]["translation"]
        assert translation.interpolation == "CUBICSPLINE"
        for t, flat in zip(times, simulated_positions[:, index], strict=True):
            if t >= drops.get(ball, math.inf):
                continue
            expected = to_gltf_points(np.array([[*flat, result.radius]]), result.table_size)[0]
            worst = max(worst, float(np.max(np.abs(translation.at(t) - expected))))
    assert worst <= tolerance, (worst, tolerance)
    if name == "pool_break":
        assert drops  # the shot drops balls: their fall is checked below
    for ball, dropped in drops.items():
        node = channels[f"ball-{ball}"]
        fall = fall_duration(result.radius)
        for share in (0.25, 0.5, 0.75):
            t = dropped + share * fall
            height = result.radius - 0.5 * DROP_GRAVITY * (t - dropped) ** 2
            assert node["translation"].at(t)[1] == pytest.approx(height, abs=tolerance)
        assert node["scale"].at(dropped + 0.99 * fall).tolist() == [1, 1, 1]
        assert node["scale"].at(dropped + 1.01 * fall).tolist() == [0, 0, 0]


def test_translation_keys_are_only_at_events_and_state_changes(
    exported: Callable[[str], Path],
) -> None:
    result = simulated("break")
    path = exported("break")
    channels = node_channels(read_document(path))
    for ball in result.ball_ids:
        times = channels[f"ball-{ball}"]["translation"].times
        own = [0.0, *(e.time for e in result.events if ball in e.balls)]
        # Every key is the start, one of its contacts, its stop or the shot's end.
        velocities = result.velocities_at(times)[:, result.ball_ids.index(ball)]
        for t, v in zip(times, velocities, strict=True):
            at_contact = min(abs(t - c) for c in own) <= 1e-6
            at_rest = float(np.hypot(*v)) < 1e-6  # its stop (the key time in float32)
            assert at_contact or at_rest, (ball, t)


@pytest.mark.parametrize("name", ["break", "spin_break"])
def test_rotations_stay_within_the_stated_angle_bound(name: str, tmp_path: Path) -> None:
    result = simulated(name)
    path = tmp_path / "shot.glb"
    bound = 1.0
    export_gltf(result, path, angle_bound=bound)
    channels = node_channels(read_document(path))
    times = np.sort(np.random.default_rng(7).uniform(0.0, result.rest_time, 200))
    turn = spin_orientations if result.model == "spin" else rolling_orientations
    # As the film draws them: the recorded rolling, then each ball's rack turn.
    start = np.column_stack(
        [result.positions_at(np.array([0.0]))[0], np.full(len(result.ball_ids), result.radius)]
    )
    drawn = quaternions.multiply(turn(result, times), turns_of(result.ball_ids, start)[None])
    truth = to_gltf_rotations(drawn)
    worst = 0.0
    for index, ball in enumerate(result.ball_ids):
        rotation = channels[f"ball-{ball}"]["rotation"]
        assert rotation.interpolation == "LINEAR"
        for t, expected in zip(times, truth[:, index], strict=True):
            dot = min(abs(float(np.dot(rotation.at(t), expected))), 1.0)
            worst = max(worst, math.degrees(2 * math.acos(dot)))
    # The bound holds on the 1/240 s grid; between its points the slerp moves away by
    # far less than a hundredth of a degree.
    assert worst <= bound + 0.01, worst


def test_gltf_file_holds_the_same_shot_as_the_glb(
    tmp_path: Path, exported: Callable[[str], Path]
) -> None:
    export_gltf(simulated("break"), tmp_path / "shot.gltf")
    binary = node_channels(read_document(exported("break")))
    text = node_channels(read_document(tmp_path / "shot.gltf"))
    assert binary.keys() == text.keys()
    for node, paths in binary.items():
        for path, channel in paths.items():
            assert np.array_equal(channel.output, text[node][path].output)


def test_events_and_cameras_travel_with_the_file(exported: Callable[[str], Path]) -> None:
    result = simulated("pool_break")
    document = read_document(exported("pool_break"))
    events = document.animations[0].extras["events"]
    assert [e["t"] for e in events] == [e.time for e in result.events]
    assert {e["kind"] for e in events} >= {"ball", "cushion", "pocket"}
    cameras = [node.name for node in document.nodes if node.camera is not None]
    assert "camera-top" in cameras and len(cameras) >= 2
    assert len(document.images) == len(result.ball_ids)  # a numbered texture each


@pytest.mark.long
def test_a_saved_trajectory_exports_its_samples(tmp_path: Path) -> None:
    from billiards.record.trajectory import Trajectory
    from billiards.record.window import film_trajectory

    saved = tmp_path / "break.npz"
    scene = load_scene("break")
    film_trajectory(simulated("break"), scene.render).save(saved)
    done = run_module("billiards.export", "--trajectory", str(saved), "-o", str(tmp_path / "t.glb"))
    assert done.returncode == 0, done.stderr
    trajectory = Trajectory.load(saved)
    channels = node_channels(read_document(tmp_path / "t.glb"))
    points = to_gltf_points(trajectory.positions, trajectory.table_size)
    for index, ball in enumerate(trajectory.ball_ids):
        translation = channels[f"ball-{ball}"]["translation"]
        assert translation.interpolation == "LINEAR"
        for sample in range(0, len(trajectory.times), 17):
            at = translation.at(float(np.float32(trajectory.times[sample])))
            assert np.allclose(at, points[sample, index], atol=1e-6)


def test_the_export_loads_no_gl_and_no_physics_of_its_own() -> None:
    code = (
        "import sys\n"
        "from billiards.record.trajectory import Trajectory\n"
        "import billiards.export.shot, billiards.export.gltf, billiards.export.page\n"
        "assert 'moderngl' not in sys.modules, 'moderngl'\n"
    )
    import subprocess

    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr


def test_linear_keys_stay_within_their_stated_distance(tmp_path: Path) -> None:
    """--linear: chords of the exact curve, for importers that ignore cubic tangents."""
    result = simulated("pool_break")
    error = 1e-4
    report = export_gltf(result, tmp_path / "shot.glb", linear=error)
    assert error / 4 < report.deviation <= error * (1 + 1e-9)
    channels = node_channels(read_document(tmp_path / "shot.glb"))
    drops = {e.balls[0]: e.time for e in result.events if e.kind == "pocket"}
    times = np.random.default_rng(3).uniform(0.0, result.rest_time, 200)
    simulated_positions = result.positions_at(times)
    for index, ball in enumerate(result.ball_ids):
        translation = channels[f"ball-{ball}"]["translation"]
        assert translation.interpolation == "LINEAR"
        for t, flat in zip(times, simulated_positions[:, index], strict=True):
            if t < drops.get(ball, math.inf):
                expected = to_gltf_points(np.array([[*flat, result.radius]]), result.table_size)
                gap = np.abs(translation.at(t) - expected[0]).max()
                assert gap <= error + float32_tolerance(result)


def test_the_film_camera_follows_the_directors_cuts(exported: Callable[[str], Path]) -> None:
    from billiards.record.window import film_trajectory
    from billiards.scene.render_table import RenderSettings
    from billiards.stage.cameras import CameraTimeline, Stage, default_shots

    result = simulated("break")
    film = node_channels(read_document(exported("break")))["camera-film"]
    trajectory = film_trajectory(result, RenderSettings())
    timeline = CameraTimeline(default_shots(trajectory), Stage.of(trajectory), 16 / 9)
    cuts = [shot.start for shot in timeline.shots[1:] if shot.transition == "cut"]
    assert cuts
    for cut in cuts:
        for t in (cut - 0.02, cut + 0.02):  # either side of a cut: that shot's eye
            eye = to_gltf_points(np.array([timeline.pose(t).eye]), result.table_size)[0]
            assert np.allclose(film["translation"].at(t), eye, atol=1e-3), (cut, t)


def test_the_cameras_are_placed_from_the_films_own_samples() -> None:
    from billiards.export.shot import film_times
    from billiards.record.window import film_trajectory
    from billiards.scene.render_table import RenderSettings

    result = simulated("break")
    for settings in (RenderSettings(), RenderSettings(shutter=0.0, slow_motion=0.25, fps=24)):
        film = film_trajectory(result, settings)
        assert np.array_equal(film_times(result.rest_time, settings), film.times)
