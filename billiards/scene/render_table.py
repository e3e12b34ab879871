"""The scene file's [render] table and [[camera]] shots, as frozen dataclasses.

Part of the scene reader's floor: billiards.scene.reader reads these tables with the same
TableReader as every other section (`Scene.render`), so every command refuses a bad
[render] key with the same line. The numbers are checked by one validator
(`render_setting_problem`), for the scene file and the command line alike. Imports no
GL, and nothing of the physics or the renderer.

Camera shot times are simulation seconds (the trajectory's clock, which starts a
moment before the cue ball moves), so a shot stays on the event it was written for
even when a film later maps its own time to simulation time non-linearly.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from billiards.scene.bounds import BOUNDS, bounded
from billiards.scene.tables import SceneError, TableReader

# Named camera set-ups (billiards.stage.cameras places them for a given table).
PRESETS = ("overhead", "behind_cue", "low_side", "orbit", "corner", "rack")
TRANSITIONS = ("cut", "ease")
ANTIALIAS_SAMPLES = (0, 2, 4, 8)
SLOW_MOTION_SOUNDS = ("match", "natural")


@dataclass(frozen=True)
class CameraShot:
    """One shot: from `start` the camera shows `preset`, or looks from `eye` at `target`.

    A shot lasts until the next one starts. `transition` says how it is entered:
    "cut", or "ease" from the previous shot's view over `ease` seconds. `orbit`
    turns the eye about the vertical through the target, in degrees per second.
    """

    start: float | None = None  # s, simulation time; None: when the film starts
    preset: str | None = None
    eye: tuple[float, float, float] | None = None  # m, table frame (z up, cloth z = 0)
    target: tuple[float, float, float] | None = None  # m
    fov: float | None = None  # degrees, vertical; None: the preset's (40 for eye/target)
    orbit: float | None = None  # degrees/s; None: the preset's own (only "orbit" turns)
    transition: str = "cut"
    ease: float = 1.0  # s, how long an "ease" transition takes


@dataclass(frozen=True)
class RenderSettings:
    width: int = 1280
    height: int = 720
    fps: float = 30.0
    quality: int = 23  # x264 crf: lower is better and larger
    # The film's file; None: named after the scene (billiards.shell.cli.default_output:
    # `render masse_shot` -> masse_shot.mp4, the seed break -> break.mp4).
    output: str | None = None
    # MSAA samples per pixel at 720p and below: 0 (off), 2, 4 or 8; a larger frame takes
    # as many per share of the screen (billiards.render.gl.frame_output.msaa_samples)
    antialias: int = 4
    lead: float = 0.5  # s of film before the cue ball moves
    tail: float = 1.0  # s of film after the last ball stops
    table_mesh: str | None = None  # a mesh file (trimesh) drawn instead of the built table
    sound: bool = True  # a sound track of the contacts, muxed into the film as AAC
    sound_seed: int = 0  # picks each contact's small variation: same seed, same samples
    # Playback speed around the first contacts, in (0, 1]; 1 is off (billiards.render.slow_motion).
    slow_motion: float = 1.0
    # "match": the clicks slow down too (longer, lower); "natural": real-speed clicks
    # placed at their slowed film times.
    slow_motion_sound: str = "match"
    # The share of each frame's time its shutter is open: each ball is drawn over that
    # span of its path (motion blur), 0 for none (every ball sharp).
    shutter: float = 0.5
    # The cue drawn striking the ball at t = 0 (for a stroke or a cue ball given a
    # velocity; billiards.stage.cue), with its sound.
    cue: bool = True
    cameras: tuple[CameraShot, ...] = ()  # empty: the default film's shots


@dataclass(frozen=True)
class Limit:
    """What one [render] number must be: `accepts` holds, else "expected `expected`"."""

    expected: str
    accepts: Callable[[float], bool]
    whole: bool = False  # a whole number, not any finite one


LIMITS = {
    # yuv420p halves the chroma planes: H.264 needs even sizes.
    "width": Limit("an even whole number >= 16", lambda v: v >= 16 and v % 2 == 0, whole=True),
    "height": Limit("an even whole number >= 16", lambda v: v >= 16 and v % 2 == 0, whole=True),
    "fps": Limit("a number in [1, 240]", lambda v: 1.0 <= v <= 240.0),
    "quality": Limit(
        "an x264 crf in [0, 51] (lower is better)", lambda v: 0 <= v <= 51, whole=True
    ),
    "antialias": Limit("one of 0, 2, 4, 8", lambda v: v in ANTIALIAS_SAMPLES, whole=True),
    "lead": Limit(
        BOUNDS["render.lead"].expected(),
        lambda v: BOUNDS["render.lead"].low <= v <= BOUNDS["render.lead"].high,
    ),
    "tail": Limit(
        BOUNDS["render.tail"].expected(),
        lambda v: BOUNDS["render.tail"].low <= v <= BOUNDS["render.tail"].high,
    ),
    "sound_seed": Limit("a whole number >= 0", lambda v: v >= 0, whole=True),
    "slow_motion": Limit(
        "a playback speed in (0, 1] (1 = no slow motion)", lambda v: 0.0 < v <= 1.0
    ),
    "shutter": Limit(
        "a share of the frame time in [0, 1] (0 = no motion blur)", lambda v: 0.0 <= v <= 1.0
    ),
}


def render_setting_problem(key: str, value: float) -> str | None:
    """What a [render] number should have been, or None when `value` will do.

    The one check of these numbers: the scene reader and the command line both ask it.
    """
    limit = LIMITS[key]
    return None if math.isfinite(value) and limit.accepts(value) else limit.expected


def settings_record(settings: RenderSettings) -> dict[str, Any]:
    """The settings as JSON values (what a saved trajectory keeps: the scene's settings,
    typed and checked, not its tables), for `settings_from_record` to read back."""
    return dataclasses.asdict(settings)


def settings_from_record(record: Mapping[str, Any]) -> RenderSettings:
    """The settings `settings_record` wrote; ValueError if `record` is not such."""
    try:
        shots = tuple(
            CameraShot(**{key: _tuple(value) for key, value in shot.items()})
            for shot in record["cameras"]
        )
        settings = RenderSettings(**{**record, "cameras": shots})
    except (KeyError, TypeError) as error:
        raise ValueError(f"not a record of render settings ({error})") from None
    for key in LIMITS:
        value = getattr(settings, key)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(f"render settings: {key} = {value!r}: expected a number")
        expected = render_setting_problem(key, value)
        if expected is not None:
            raise ValueError(f"render settings: {key} = {value!r}: expected {expected}")
    return settings


def _tuple(value: Any) -> Any:
    """A JSON array back as the tuple it was (a shot's eye or target)."""
    return tuple(value) if isinstance(value, list) else value


def _limited(reader: TableReader, key: str) -> Any:
    """A [render] number of the right kind that LIMITS accepts (the dataclass default
    when the key is absent)."""
    limit = LIMITS[key]
    value = reader.raw(key, getattr(RenderSettings, key))
    reader.note(key, getattr(RenderSettings, key), limit.expected)
    kind = int if limit.whole else int | float
    wrong_kind = isinstance(value, bool) or not isinstance(value, kind)
    if wrong_kind or render_setting_problem(key, value) is not None:
        raise reader.fail(key, value, limit.expected)
    return value if limit.whole else float(value)


def parse_render_settings(root: TableReader) -> RenderSettings:
    """The [render] table and [[camera]] array of a scene file's top-level table (whose
    other keys are the caller's to read and finish)."""
    reader = root.table("render")
    table_mesh = reader.raw("table_mesh")
    if table_mesh is not None:
        if not isinstance(table_mesh, str) or not table_mesh:
            raise reader.fail("table_mesh", table_mesh, "a mesh file path (a string)")
        # A relative path is read next to the scene file, as its author would expect.
        mesh_path = Path(table_mesh)
        if not mesh_path.is_absolute():
            mesh_path = Path(root.source).parent / mesh_path
        if not mesh_path.is_file():
            raise reader.fail("table_mesh", table_mesh, f"an existing mesh file (no {mesh_path})")
        table_mesh = str(mesh_path)
    settings = RenderSettings(
        width=_limited(reader, "width"),
        height=_limited(reader, "height"),
        fps=_limited(reader, "fps"),
        quality=_limited(reader, "quality"),
        output=reader.string("output", "") if reader.has("output") else None,
        antialias=_limited(reader, "antialias"),
        lead=_limited(reader, "lead"),
        tail=_limited(reader, "tail"),
        table_mesh=table_mesh,
        sound=reader.boolean("sound", RenderSettings.sound),
        sound_seed=_limited(reader, "sound_seed"),
        slow_motion=_limited(reader, "slow_motion"),
        slow_motion_sound=reader.string(
            "slow_motion_sound", RenderSettings.slow_motion_sound, SLOW_MOTION_SOUNDS
        ),
        shutter=_limited(reader, "shutter"),
        cue=reader.boolean("cue", RenderSettings.cue),
        cameras=tuple(_camera_shot(shot) for shot in root.tables("camera")),
    )
    reader.finish()
    _check_shot_order(settings.cameras, root.source)
    return settings


def _camera_shot(reader: TableReader) -> CameraShot:
    start = bounded(reader, "start", 0.0) if reader.has("start") else None
    preset = reader.string("preset", "", PRESETS) if reader.has("preset") else None
    eye = _point(reader, "eye")
    target = _point(reader, "target")
    if preset is None and (eye is None or target is None):
        key = "eye" if eye is None else "target"
        choices = ", ".join(PRESETS)
        raise reader.missing(key, f"[x, y, z] in m, or a preset ({choices})")
    if preset is not None and eye is not None and target is None:
        raise reader.missing("target", "[x, y, z] in m when eye is given")
    if eye is not None and target is not None and eye == target:
        raise reader.fail("target", list(target), "a point other than the eye")
    shot = CameraShot(
        start=start,
        preset=preset,
        eye=eye,
        target=target,
        fov=reader.number("fov", 40.0, low=1.0, high=150.0) if reader.has("fov") else None,
        orbit=bounded(reader, "orbit", 0.0) if reader.has("orbit") else None,
        transition=reader.string("transition", CameraShot.transition, TRANSITIONS),
        ease=bounded(reader, "ease", CameraShot.ease),
    )
    reader.finish()
    return shot


def _point(reader: TableReader, key: str) -> tuple[float, float, float] | None:
    if not reader.has(key):
        return None
    x, y, z = reader.vector(key, (0.0, 0.0, 0.0), size=3)
    bound = BOUNDS[f"camera.{key}"]
    if not all(bound.low <= value <= bound.high for value in (x, y, z)):
        raise reader.fail(key, [x, y, z], f"coordinates each in {bound.range_text()}")
    return (x, y, z)


def _check_shot_order(shots: tuple[CameraShot, ...], source: str) -> None:
    previous: float | None = None
    for index, shot in enumerate(shots):
        if shot.start is None:
            if index > 0:
                raise SceneError(
                    f"{source}: camera[{index}].start: missing; expected a time in s "
                    "(only the first shot may omit it)"
                )
            continue
        if previous is not None and shot.start <= previous:
            raise SceneError(
                f"{source}: camera[{index}].start = {shot.start:g}: expected a time after "
                f"the previous shot's start ({previous:g} s)"
            )
        previous = shot.start
