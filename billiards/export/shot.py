"""The export itself: a shot's document, written as .glb, .gltf and/or the page."""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from billiards.export.gltf import (
    CameraPath,
    ShotCamera,
    build_document,
    glb_bytes,
    gltf_text,
)
from billiards.export.tracks import (
    DEFAULT_ANGLE_BOUND,
    ExportedMotion,
    StateChange,
    Tracks,
    linear_track,
    motion_tracks,
    trajectory_tracks,
)
from billiards.record.pocket_shapes import PocketShapes
from billiards.record.sampling import sample_trajectory
from billiards.record.trajectory import Trajectory
from billiards.record.window import SHUTTER_STEPS
from billiards.scene.render_table import RenderSettings
from billiards.shell.atomic import atomic_output
from billiards.stage.cameras import CameraTimeline, Stage, default_shots

FORMATS = (".glb", ".gltf")


@dataclass(frozen=True)
class ExportReport:
    """What an export wrote and measured."""

    paths: tuple[Path, ...]
    seconds: float  # wall-clock
    sizes: dict[str, int]  # bytes per file written, by suffix (".glb", ".gltf", ".html")
    translation_keys: dict[str, int]  # per ball
    rotation_keys: dict[str, int]  # per ball
    deviation: float  # m: largest distance of the keys' curves from the simulated path
    angle_bound: float  # degrees: the rotation keys' bound


def export_gltf(
    source: ExportedMotion | Trajectory,
    output: str | Path | None = None,
    *,
    html: str | Path | None = None,
    settings: RenderSettings | None = None,
    angle_bound: float = DEFAULT_ANGLE_BOUND,
    texture_width: int = 512,
    title: str = "",
    linear: float | None = None,
) -> ExportReport:
    """Write the shot as glTF (`output`: .glb, or .gltf with the data embedded) and/or
    as a replay page (`html`). `source`: a simulation result (exact translation keys)
    or a saved trajectory; `settings`: the film's, for its cameras (default: the
    trajectory's own, else the default film's shots). Each file appears whole or not
    at all (billiards.shell.atomic). `linear` (m): LINEAR translation keys within that
    distance of the path instead of CUBICSPLINE ones, for importers that ignore
    cubic tangents (Blender's). ValueError for an unknown output extension."""
    started = time.perf_counter()
    if output is not None and Path(output).suffix.lower() not in FORMATS:
        raise ValueError(f"{output}: expected a .glb or .gltf file name")
    document, tracks = shot_document(source, settings, angle_bound, texture_width, title, linear)
    written: list[Path] = []
    sizes: dict[str, int] = {}
    binary = glb_bytes(document)
    if output is not None:
        target = Path(output)
        data = binary if target.suffix.lower() == ".glb" else gltf_text(document).encode()
        with atomic_output(target, suffix=target.suffix) as temporary:
            temporary.write_bytes(data)
        written.append(target)
        sizes[target.suffix.lower()] = len(data)
    if html is not None:
        from billiards.export.page import page_html  # the page's bundle only when asked

        page = page_html(binary, title or "billiards shot").encode()
        with atomic_output(html, suffix=".html") as temporary:
            temporary.write_bytes(page)
        written.append(Path(html))
        sizes[".html"] = len(page)
    deviation = 0.0 if isinstance(source, Trajectory) else measured_deviation(source, tracks)
    return ExportReport(
        paths=tuple(written),
        seconds=time.perf_counter() - started,
        sizes=sizes,
        translation_keys={ball.ball: len(ball.times) for ball in tracks.balls},
        rotation_keys={ball.ball: len(ball.rotation_times) for ball in tracks.balls},
        deviation=deviation,
        angle_bound=angle_bound,
    )


def shot_document(
    source: ExportedMotion | Trajectory,
    settings: RenderSettings | None = None,
    angle_bound: float = DEFAULT_ANGLE_BOUND,
    texture_width: int = 512,
    title: str = "",
    linear: float | None = None,
) -> tuple[Any, Tracks]:
    """The glTF document (pygltflib.GLTF2) of a shot, and the keys it holds."""
    if isinstance(source, Trajectory):
        tracks = trajectory_tracks(source, angle_bound)
        stand_in = source
        pockets = source.pockets
        settings = settings or source.render_settings
    else:
        changes: Sequence[StateChange] = getattr(source, "transitions", ())
        tracks = motion_tracks(source, changes, angle_bound)
        # The cameras are placed from the film's own samples (the impact, where the
        # cue ball starts and heads), so that they stand where the film's stand.
        stand_in = sample_trajectory(
            source, film_times(source.rest_time, settings or RenderSettings()), turn=False
        )
        pockets = None if source.pockets is None else PocketShapes.of(source.pockets)
    if linear is not None:
        tracks = dataclasses.replace(
            tracks, balls=tuple(linear_track(ball, linear) for ball in tracks.balls)
        )
    settings = settings or RenderSettings()
    document = build_document(
        tracks,
        events=[_event_record(event) for event in source.events],
        pockets=pockets,
        shots=film_cameras(stand_in, settings),
        director=director_path(stand_in, settings, tracks.end),
        extras={
            "title": title,
            "exact": tracks.exact,
            "linear_error_m": linear,
            "angle_bound_degrees": angle_bound,
            "table_size": list(tracks.table_size),
            "radius": tracks.radius,
            "frame": "+Y up, metres; physics (x, y, z) is glTF (x - L/2, z, W/2 - y)",
        },
        texture_width=texture_width,
    )
    return document, tracks


def film_times(rest_time: float, settings: RenderSettings) -> npt.NDArray[np.float64]:
    """The times billiards.record.window.film_trajectory samples a film at (no still)."""
    steps = SHUTTER_STEPS if settings.shutter > 0 else 1
    fps = settings.fps * math.ceil(1.0 / settings.slow_motion - 1e-9) * steps
    start, end = -settings.lead, rest_time + settings.tail
    count = max(int(np.floor((end - start) * fps + 1e-9)) + 1, 1)
    return np.asarray(start + np.arange(count) / fps)


def film_cameras(trajectory: Trajectory, settings: RenderSettings) -> list[ShotCamera]:
    """The film's shots as still cameras, each at its pose when the film cuts to it."""
    shots = settings.cameras or default_shots(trajectory)
    timeline = CameraTimeline(shots, Stage.of(trajectory), settings.width / settings.height)
    cameras = []
    for index, (shot, placed) in enumerate(zip(shots, timeline.shots, strict=True)):
        name = shot.preset or f"shot-{index + 1}"
        cameras.append(ShotCamera(f"{index + 1}-{name}", timeline.pose(placed.start), placed.start))
    return cameras


# The film's camera as keys: every DIRECTOR_STEP s (its eases and slow orbits are
# smooth at that rate), and a cut as two keys CUT_GAP s apart.
DIRECTOR_STEP = 1.0 / 15.0
CUT_GAP = 1e-3


def director_path(trajectory: Trajectory, settings: RenderSettings, end: float) -> CameraPath:
    """The film's camera over [0, end]: its pose at the sampled times."""
    shots = settings.cameras or default_shots(trajectory)
    timeline = CameraTimeline(shots, Stage.of(trajectory), settings.width / settings.height)
    cuts = [shot.start for shot in timeline.shots[1:] if shot.transition == "cut"]
    times = np.union1d(np.arange(0.0, end, DIRECTOR_STEP), [end, *cuts])
    times = np.union1d(times, [cut - CUT_GAP for cut in cuts])
    times = times[(times >= 0) & (times <= end)]
    return CameraPath(times, tuple(timeline.pose(float(t)) for t in times))


def _event_record(event: Any) -> dict[str, Any]:
    record = {
        "t": float(event.time),
        "kind": str(event.kind),
        "balls": list(event.balls),
        "impact_speed": float(event.impact_speed),
    }
    if event.pocket:
        record["pocket"] = str(event.pocket)
    return record


def measured_deviation(source: ExportedMotion, tracks: Tracks, samples: int = 4001) -> float:
    """m: the largest distance, over an even grid and every key, between the keys'
    curves (float64) and the simulated centres, before each ball's drop."""
    keys = np.concatenate([ball.times for ball in tracks.balls])
    grid = np.union1d(np.linspace(0.0, source.rest_time, samples), keys)
    grid = grid[(grid >= 0) & (grid <= source.rest_time)]
    simulated = source.positions_at(grid)
    curves = tracks.hermite_positions(grid)
    drops = {e.balls[0]: e.time for e in source.events if e.kind == "pocket"}
    largest = 0.0
    for index, ball in enumerate(tracks.balls):
        until = drops.get(ball.ball, np.inf)
        inside = grid <= until
        if inside.any():
            gap = np.hypot(*(curves[inside, index, :2] - simulated[inside, index]).T)
            largest = max(largest, float(gap.max()))
    return largest
