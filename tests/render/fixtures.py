"""Hand-made trajectories for the renderer's tests: no physics needed.

The cue ball rolls straight along +x from the head spot towards a resting rack,
slowing at mu g, with the rolling rotation of the README's model section (about the horizontal axis
z x v, by s / r); the rack does not move.
"""

from __future__ import annotations

import gc
import math
import subprocess
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import imageio_ffmpeg
import numpy as np
import numpy.typing as npt
import pytest

from billiards.record.trajectory import Event, Trajectory
from billiards.render.gl.context import ContextError, create_context
from billiards.scene.reader import RACK_ORDER, rack_positions

LENGTH, WIDTH, RADIUS = 2.13, 1.065, 0.0286
CUE_START = (LENGTH / 4, WIDTH / 2)


def rolling_trajectory(
    fps: float = 30.0,
    start: float = -0.5,
    end: float = 1.0,
    speed: float = 1.0,
    deceleration: float = 0.0981,
) -> Trajectory:
    """The cue ball rolling along +x into (short of) a 15-ball rack."""
    count = round((end - start) * fps) + 1
    times = start + np.arange(count) / fps
    ids = ("cue", *RACK_ORDER)
    rack = rack_positions((0.75 * LENGTH, WIDTH / 2), RADIUS, 0.0001)
    positions = np.zeros((count, len(ids), 3))
    positions[:, :, 2] = RADIUS
    positions[:, 0, 0] = CUE_START[0]
    positions[:, 0, 1] = CUE_START[1]
    for index, (x, y) in enumerate(rack, start=1):
        positions[:, index, 0] = x
        positions[:, index, 1] = y
    moving = np.clip(times, 0.0, speed / deceleration)
    travelled = speed * moving - deceleration * moving**2 / 2
    positions[:, 0, 0] += travelled
    orientations = np.zeros((count, len(ids), 4))
    orientations[:, :, 3] = 1.0
    # Rolling along +x turns the ball about +y by s / r (the top moves forward).
    angle = travelled / RADIUS
    orientations[:, 0, 1] = np.sin(angle / 2)
    orientations[:, 0, 3] = np.cos(angle / 2)
    return Trajectory(
        ball_ids=ids,
        radius=RADIUS,
        table_size=(LENGTH, WIDTH),
        times=times,
        positions=positions,
        orientations=orientations,
        events=(Event(0.9, "ball", ("cue", "1"), speed),),
        rest_time=float(min(end, speed / deceleration)),
    )


def ball_pixel_radius(distance: float, fov: float, height: int) -> float:
    """Rough radius in pixels of a ball seen from `distance` with a vertical fov."""
    return RADIUS / (distance * math.tan(math.radians(fov / 2))) * height / 2


# BT.709's luma weights (Kr, Kg, Kb).
BT709_LUMA = np.array([0.2126, 0.7152, 0.0722])


def bt709_yuv420p(picture: npt.NDArray[np.uint8]) -> npt.NDArray[np.uint8]:
    """yuv420p's bytes (the Y plane, U, V) of an RGB(A) picture (H x W x 3 or 4, top row
    first), by BT.709's formula in limited range, chroma from each 2x2 block's mean,
    rounded to the nearest code: the reference for the renderer's GL conversion."""
    height, width = picture.shape[:2]
    rgb = picture[..., :3].astype(np.float64) / 255.0

    def codes(values: npt.NDArray[np.float64]) -> npt.NDArray[np.uint8]:
        return np.clip(np.floor(values + 0.5), 0, 255).astype(np.uint8).ravel()

    luma = rgb @ BT709_LUMA
    mean = rgb.reshape(height // 2, 2, width // 2, 2, 3).mean(axis=(1, 3))
    mean_luma = mean @ BT709_LUMA
    cb = 128 + 224 * (mean[..., 2] - mean_luma) / (2 * (1 - BT709_LUMA[2]))
    cr = 128 + 224 * (mean[..., 0] - mean_luma) / (2 * (1 - BT709_LUMA[0]))
    return np.concatenate([codes(16 + 219 * luma), codes(cb), codes(cr)])


def decode_mp4(path: str | Path) -> tuple[dict[str, Any], list[npt.NDArray[np.uint8]]]:
    """Metadata and RGB frames of a film, through imageio-ffmpeg's reader.

    The reader leaves its ffmpeg pipes to the garbage collector; collect them here,
    with their ResourceWarnings silenced, so they cannot fail a later test.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ResourceWarning)
        reader = imageio_ffmpeg.read_frames(str(path))
        meta: dict[str, Any] = next(reader)
        width, height = meta["size"]
        pictures = [np.frombuffer(f, dtype=np.uint8).reshape(height, width, 3) for f in reader]
        reader.close()
        del reader
        gc.collect()
    return meta, pictures


def decode_audio(path: str | Path, sample_rate: int = 48_000) -> npt.NDArray[np.float32]:
    """A film's sound track, decoded to mono float samples by the bundled ffmpeg."""
    done = subprocess.run(
        [imageio_ffmpeg.get_ffmpeg_exe(), "-v", "error", "-i", str(path), "-map", "0:a:0",
         "-f", "f32le", "-ac", "1", "-ar", str(sample_rate), "pipe:"],
        capture_output=True, check=True,
    )  # fmt: skip
    return np.frombuffer(done.stdout, dtype=np.float32)


def streams(path: str | Path) -> str:
    """ffmpeg's description of a file's streams (lines with "Video:" / "Audio:")."""
    done = subprocess.run(
        [imageio_ffmpeg.get_ffmpeg_exe(), "-hide_banner", "-i", str(path)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    return "\n".join(line for line in done.stderr.splitlines() if "Stream #" in line)


def _gl_unavailable() -> str | None:
    """Why no headless OpenGL context can be made here, or None if one can."""
    try:
        create_context().release()
    except ContextError as error:
        return str(error)
    return None


NO_GL = _gl_unavailable()
# GL tests skip, with the reason, only where no context can be made at all.
needs_gl = pytest.mark.skipif(NO_GL is not None, reason=f"no headless OpenGL context: {NO_GL}")


@pytest.fixture(scope="module", name="ctx")
def gl_context() -> Iterator[object]:
    """`ctx`: one headless GL context per test module that imports this (skips where
    none can be made)."""
    try:
        context = create_context()
    except ContextError as error:
        pytest.skip(f"no headless OpenGL context: {error}")
    yield context
    context.release()
