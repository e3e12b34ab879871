"""From a trajectory to a film or a still: the frame loop.

The loop renders each frame on this thread while billiards.render.video's writer thread
feeds ffmpeg, so drawing and encoding overlap on a multi-core machine.
"""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

import numpy as np
import numpy.typing as npt
from PIL import Image
from tqdm import tqdm

from billiards.record.trajectory import Trajectory
from billiards.render.director import directed_shots
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.render.sound.soundtrack import film_sound
from billiards.render.sound.voices import SAMPLE_RATE
from billiards.render.video import VideoWriter
from billiards.scene.render_table import RenderSettings
from billiards.shell.atomic import atomic_output
from billiards.stage.cameras import CameraPose, CameraTimeline, Stage


@dataclass(frozen=True)
class FilmReport:
    path: Path
    frames: int
    seconds: float  # wall-clock time spent
    width: int
    height: int
    fps: float

    @property
    def frames_per_second(self) -> float:
        return self.frames / self.seconds if self.seconds > 0 else float("inf")


def camera_timeline(trajectory: Trajectory, settings: RenderSettings) -> CameraTimeline:
    """The scene's [[camera]] shots, else the director's for this run."""
    aspect = settings.width / settings.height
    shots = settings.cameras or directed_shots(trajectory, aspect)
    return CameraTimeline(shots, Stage.of(trajectory), aspect)


def camera_poses(cameras: CameraTimeline, clock: FilmClock) -> Iterator[tuple[CameraPose, bool]]:
    """Each frame's camera pose, and whether the camera moves on to the next frame."""
    poses = [cameras.pose(float(t)) for t in clock.sim_times]
    for index, pose in enumerate(poses):
        following = poses[index + 1] if index + 1 < len(poses) else pose
        yield pose, following != pose


def render_film(
    trajectory: Trajectory,
    settings: RenderSettings,
    output: str | Path,
    *,
    progress: TextIO | None = sys.stderr,
) -> FilmReport:
    """Render the whole trajectory to an MP4 at `output`.

    Frames follow the settings' clock (slow motion included); the sound track is the
    contacts' clicks on that clock when settings.sound is on. A tqdm progress bar goes
    to `progress` (None: no bar).
    """
    path = Path(output)
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    audio = (
        film_sound(trajectory.events, clock, settings, trajectory.strike, trajectory)
        if settings.sound
        else None
    )
    cameras = camera_timeline(trajectory, settings)
    size = (settings.width, settings.height)
    started = time.perf_counter()
    with _renderer(trajectory, settings) as renderer:
        # yuv420p, converted by the renderer's last GL pass, where the GL has it.
        pixel_format = renderer.output.film_format()
        with (
            tqdm(
                total=clock.frame_count,
                desc="render",
                unit="frame",
                file=progress,
                disable=progress is None,
            ) as bar,
            VideoWriter(
                path,
                size,
                clock.fps,
                quality=settings.quality,
                pixel_format=pixel_format,
                audio=audio,
                sample_rate=SAMPLE_RATE,
            ) as writer,
        ):
            exposures = clock.exposures(settings.shutter)
            for index, (pose, moving) in enumerate(camera_poses(cameras, clock)):
                time_s, exposure = float(clock.sim_times[index]), float(exposures[index])
                writer.write(renderer.draw(time_s, pose, moving, exposure, pixel_format))
                bar.update()
    return FilmReport(
        path=path,
        frames=clock.frame_count,
        seconds=time.perf_counter() - started,
        width=size[0],
        height=size[1],
        fps=clock.fps,
    )


def render_still(
    trajectory: Trajectory, settings: RenderSettings, time_s: float
) -> npt.NDArray[np.uint8]:
    """The picture (height x width x 3) at simulation time `time_s`."""
    cameras = camera_timeline(trajectory, settings)
    with _renderer(trajectory, settings) as renderer:
        return renderer.frame(time_s, cameras.pose(time_s), settings.shutter / settings.fps)


@contextlib.contextmanager
def _renderer(trajectory: Trajectory, settings: RenderSettings) -> Iterator[Renderer]:
    """A Renderer of `trajectory` as `settings` ask, on a GL context of its own; both
    released after."""
    ctx = create_context()
    renderer = None
    try:
        size = (settings.width, settings.height)
        renderer = Renderer(
            ctx,
            trajectory,
            size,
            antialias=settings.antialias,
            table_mesh=settings.table_mesh,
            cue=settings.cue,
        )
        yield renderer
    finally:
        if renderer is not None:
            renderer.release()
        ctx.release()


def save_still(pixels: npt.NDArray[np.uint8], path: str | Path) -> Path:
    """Write a still with Pillow (format from the extension), whole or not at all."""
    target = Path(path)
    with atomic_output(target, suffix=target.suffix) as temporary:
        Image.fromarray(pixels).save(temporary)
    return target
