"""python -m billiards.render: from a scene file to an MP4 film (or one still).

    python -m billiards.render                       # the seed break -> break.mp4
    python -m billiards.render masse_shot            # a shipped scene -> masse_shot.mp4
    python -m billiards.render my.toml -o shot.mp4 --width 1920 --height 1080 --fps 60
    python -m billiards.render --frame 2.5 -o still.png   # one still at t = 2.5 s
    python -m billiards.render --slow-motion 0.25        # the first contacts at 1/4 speed
    python -m billiards.render --no-sound                # a film without its sound track
    python -m billiards.render --sound-only break.wav    # just the sound track (no OpenGL)

The glue of the package: load the scene, simulate, record a trajectory, render.
Exit codes: 0 done, 1 the film could not be made (no OpenGL, ffmpeg failed),
2 a bad scene file or option, 130 interrupted. Errors are one line on stderr and
never leave a half-written output file.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from billiards.scene.reader import shipped_scene_names
from billiards.scene.render_table import (
    ANTIALIAS_SAMPLES,
    PRESETS,
    SLOW_MOTION_SOUNDS,
    CameraShot,
    RenderSettings,
    render_setting_problem,
)
from billiards.shell import cli

if TYPE_CHECKING:
    from billiards.record.trajectory import Trajectory
    from billiards.scene.reader import Scene

DEFAULT = RenderSettings()


def build_parser() -> argparse.ArgumentParser:
    """The command's options (the site's reference is generated from them)."""
    parser = cli.command_parser(
        "python -m billiards.render",
        "Simulate a scene and render it, headless, to an MP4 film.",
        shipped_scene_names,
    )
    cli.add_force_argument(parser)
    parser.add_argument(
        "-o",
        "--output",
        help="film (.mp4) or, with --frame, image (.png) path (default: [render] output, "
        "else named after the scene: SCENE.mp4 or SCENE.png, break.* for the seed break)",
    )
    parser.add_argument("--width", type=int, help=f"pixels (even); default {DEFAULT.width}")
    parser.add_argument("--height", type=int, help=f"pixels (even); default {DEFAULT.height}")
    parser.add_argument("--fps", type=float, help=f"frames per second; default {DEFAULT.fps:g}")
    parser.add_argument(
        "--quality", type=int, help=f"x264 crf, 0-51, lower is better; default {DEFAULT.quality}"
    )
    parser.add_argument(
        "--antialias",
        type=int,
        choices=ANTIALIAS_SAMPLES,
        help=f"MSAA samples a pixel at 720p (a larger frame: as many per share of the "
        f"screen, 1080p half as many a pixel); default {DEFAULT.antialias}",
    )
    parser.add_argument("--camera", choices=PRESETS, help="film every frame from this preset")
    parser.add_argument("--frame", type=float, metavar="T", help="render one still at t = T s")
    parser.add_argument(
        "--trajectory",
        help="render a saved trajectory (.npz) instead of simulating; with a scene, only its "
        "[render] and [[camera]] tables are used (the motion is the trajectory's)",
    )
    parser.add_argument(
        "--no-sound", action="store_true", help="leave the sound track out (video only)"
    )
    parser.add_argument(
        "--sound-only",
        metavar="WAV",
        help="write only the film's sound track to this .wav file, then stop",
    )
    parser.add_argument(
        "--slow-motion",
        type=float,
        metavar="F",
        help="playback speed around the first contacts, in (0, 1]; 1 = off; "
        f"default {DEFAULT.slow_motion:g}",
    )
    parser.add_argument(
        "--slow-motion-sound",
        choices=SLOW_MOTION_SOUNDS,
        help="slow the clicks to match the picture, or keep them natural; "
        f"default {DEFAULT.slow_motion_sound}",
    )
    parser.add_argument(
        "--shutter",
        type=float,
        metavar="S",
        help="share of each frame's time the shutter is open (motion blur), in [0, 1]; "
        f"0 = none; default {DEFAULT.shutter:g}",
    )
    cli.add_quiet_argument(parser, "no progress bar or summary")
    return parser


# Command-line options that set a [render] number, checked by the same validator.
NUMBER_OPTIONS = ("width", "height", "fps", "quality", "antialias", "slow_motion", "shutter")


def _settings(base: RenderSettings, args: argparse.Namespace) -> RenderSettings:
    """The scene's [render] settings with the command line's options on top."""
    changes: dict[str, object] = {}
    for key in NUMBER_OPTIONS:
        value = getattr(args, key)
        if value is None:
            continue
        expected = render_setting_problem(key, value)
        if expected is not None:
            option = "--" + key.replace("_", "-")
            shown = f"{value:g}" if isinstance(value, float) else str(value)
            raise ValueError(f"{option} {shown}: expected {expected}")
        changes[key] = value
    if args.camera is not None:
        changes["cameras"] = (CameraShot(preset=args.camera),)
    if args.no_sound:
        changes["sound"] = False
    if args.slow_motion_sound is not None:
        changes["slow_motion_sound"] = args.slow_motion_sound
    return dataclasses.replace(base, **changes)  # type: ignore[arg-type]


def main(argv: list[str] | None = None) -> int:
    return cli.run_guarded(lambda: _run(build_parser().parse_args(argv)))


def _run(args: argparse.Namespace) -> int:
    from billiards.render.gl.context import ContextError, GLError
    from billiards.render.gl.frame_output import FrameSizeError
    from billiards.render.video import VideoError
    from billiards.scene.reader import SceneError, load_scene

    with cli.failing_on(SceneError, ValueError):
        scene = load_scene(args.scene)
        settings = _settings(scene.render, args)
    if args.frame is not None and not math.isfinite(args.frame):
        return cli.fail(f"--frame {args.frame}: expected a time in s")
    _check_output(args, settings)  # before any simulating or drawing
    if args.trajectory:
        trajectory, settings = _saved_trajectory(args, scene, settings)
    else:
        trajectory = _simulated_trajectory(args, scene, settings)
    try:
        if args.sound_only is not None:
            return _sound_only(trajectory, settings, args)
        if args.frame is not None:
            return _still(trajectory, settings, args)
        return _film(trajectory, settings, args)
    except FrameSizeError as error:  # the size asked for: bad input
        return cli.fail(error)
    except (ContextError, VideoError) as error:
        return cli.fail(error, cli.EXIT_FAILED)
    except (OSError, ValueError, GLError) as error:
        # A table mesh trimesh cannot read, an output path that cannot be written, or
        # a GL driver that refuses a shader or framebuffer.
        return cli.fail(cli.first_line(error), cli.EXIT_FAILED)


def _saved_trajectory(
    args: argparse.Namespace, scene: Scene, settings: RenderSettings
) -> tuple[Trajectory, RenderSettings]:
    """--trajectory's file, and the settings to film it with: the scene's when one is
    named, else those of the scene it was saved from (the command line's on top)."""
    from billiards.record.trajectory import Trajectory
    from billiards.scene.reader import SceneError

    with cli.reading_trajectory(args.trajectory, SceneError):
        trajectory = Trajectory.load(args.trajectory)
    if args.scene is not None:
        # The scene shapes the film; what moves on it is the trajectory's.
        cli.say(
            f"note: {scene.source}: only its [render] and [[camera]] tables are used; "
            f"the table and the balls' motion are {args.trajectory}'s"
            + (f" (saved from {trajectory.scene_source})" if trajectory.scene_source else "")
        )
    elif trajectory.render_settings is not None:
        # No scene named: render as the scene the trajectory was saved from.
        with cli.failing_on(ValueError):
            settings = _settings(trajectory.render_settings, args)
        _check_output(args, settings)
    _check_frame_within(args.frame, (float(trajectory.times[0]), float(trajectory.times[-1])))
    return trajectory, settings


def _simulated_trajectory(
    args: argparse.Namespace, scene: Scene, settings: RenderSettings
) -> Trajectory:
    """The scene simulated and recorded as the film shows it (around --frame for a still)."""
    import numpy as np

    from billiards.record.window import cue_strike_of, film_trajectory, motion_end
    from billiards.simulation import NonFiniteRun, simulate_scene

    # A number gone wrong is said once, as the run's one line.
    with cli.failing_on(NonFiniteRun, status=cli.EXIT_FAILED), np.errstate(all="ignore"):
        result = simulate_scene(scene)
    if not result.complete:
        cli.say(
            f"warning: {scene.source}: the run was stopped by {result.stopped_by} at "
            f"{result.rest_time:g} s, before every ball came to rest; the film ends there"
        )
    _check_frame_within(args.frame, (-settings.lead, motion_end(result) + settings.tail))
    return film_trajectory(result, settings, args.frame, cue_strike_of(scene))


def _check_frame_within(frame: float | None, span: tuple[float, float]) -> None:
    """--frame (if given) must fall within the film's span."""
    if frame is not None and not span[0] <= frame <= span[1]:
        raise cli.CommandError(
            f"--frame {frame:g}: expected a time in s within the film, {span[0]:g} to {span[1]:g}"
        )


IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp")


def _output_path(args: argparse.Namespace, settings: RenderSettings) -> Path:
    """-o, else the scene's [render] output, else named after the scene (or, for a
    saved trajectory alone, after its file): `render masse_shot` -> masse_shot.mp4;
    a still takes the film's name as a .png."""
    if args.output:
        return Path(args.output)
    named_after = args.scene
    if named_after is None and args.trajectory:
        named_after = Path(args.trajectory).stem
    film = Path(settings.output or cli.default_output(named_after, ".mp4"))
    return Path(film.with_suffix(".png").name) if args.frame is not None else film


def _check_output(args: argparse.Namespace, settings: RenderSettings) -> None:
    """The options' output must be writable and named for what is written."""
    problem = _output_problem(args, settings)
    if problem:
        raise cli.CommandError(problem)


def _output_problem(args: argparse.Namespace, settings: RenderSettings) -> str | None:
    """What is wrong with the options' output, if anything."""
    if args.sound_only is not None:
        if Path(args.sound_only).suffix.lower() != ".wav":
            return f"{args.sound_only}: --sound-only writes a .wav file"
        if args.frame is not None:
            return "--sound-only and --frame: choose one"
        return cli.output_problem(args.sound_only, force=args.force)
    output = _output_path(args, settings)
    if args.frame is not None and output.suffix.lower() not in IMAGE_SUFFIXES:
        return f"{output}: a still needs an image file name (.png, .jpg)"
    if args.frame is None and output.suffix.lower() != ".mp4":
        return f"{output}: the film is an MP4 file (name it .mp4)"
    return cli.output_problem(output, force=args.force)


def _still(trajectory: Trajectory, settings: RenderSettings, args: argparse.Namespace) -> int:
    from billiards.render.film import render_still, save_still

    output = _output_path(args, settings)
    pixels = render_still(trajectory, settings, args.frame)
    save_still(pixels, output)
    if not args.quiet:
        cli.say(f"wrote {output} ({settings.width}x{settings.height}, t = {args.frame:g} s)")
    return 0


def _sound_only(trajectory: Trajectory, settings: RenderSettings, args: argparse.Namespace) -> int:
    from billiards.render.film_clock import FilmClock
    from billiards.render.sound.soundtrack import film_sound
    from billiards.render.sound.voices import SAMPLE_RATE, write_wav

    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    write_wav(
        args.sound_only,
        film_sound(trajectory.events, clock, settings, trajectory.strike, trajectory),
        SAMPLE_RATE,
    )
    if not args.quiet:
        cli.say(
            f"wrote {args.sound_only} ({clock.duration:.2f} s at {SAMPLE_RATE} Hz, "
            f"{len(trajectory.events)} contacts)"
        )
    return 0


def _film(trajectory: Trajectory, settings: RenderSettings, args: argparse.Namespace) -> int:
    from billiards.render.film import render_film

    output = _output_path(args, settings)
    report = render_film(trajectory, settings, output, progress=None if args.quiet else sys.stderr)
    if not args.quiet:
        cli.say(
            f"wrote {report.path} ({report.frames} frames, {report.frames / report.fps:.1f} s, "
            f"{report.width}x{report.height} at {report.fps:g} fps, "
            f"{'with' if settings.sound else 'no'} sound) in {report.seconds:.1f} s "
            f"({report.frames_per_second:.1f} frames/s)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
