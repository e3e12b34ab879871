"""python -m billiards.render: from a scene file to an MP4 film (or one still).

    python -m billiards.render                       # the seed break -> break.mp4
    python -m billiards.render my.toml -o shot.mp4 --width 1920 --height 1080 --fps 60
    python -m billiards.render --frame 2.5 -o still.png   # one still at t = 2.5 s

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

from billiards.render.settings import PRESETS, CameraShot, RenderSettings

if TYPE_CHECKING:
    from billiards.scene import Scene
    from billiards.trajectory import Trajectory

EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 1, 2, 130


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python -m billiards.render",
        description="Simulate a pool break and render it, headless, to an MP4 film.",
    )
    parser.add_argument("scene", nargs="?", help="scene file (TOML); default: the seed break")
    parser.add_argument("-o", "--output", help="film (.mp4) or, with --frame, image (.png) path")
    parser.add_argument("--width", type=int, help="pixels (even); default 1280")
    parser.add_argument("--height", type=int, help="pixels (even); default 720")
    parser.add_argument("--fps", type=float, help="frames per second; default 30")
    parser.add_argument("--quality", type=int, help="x264 crf, 0-51, lower is better; default 23")
    parser.add_argument(
        "--antialias", type=int, choices=(0, 2, 4, 8), help="MSAA samples; default 4"
    )
    parser.add_argument("--camera", choices=PRESETS, help="film every frame from this preset")
    parser.add_argument("--frame", type=float, metavar="T", help="render one still at t = T s")
    parser.add_argument(
        "--trajectory", help="render a saved trajectory (.npz) instead of simulating"
    )
    parser.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    return parser.parse_args(argv)


def _settings(base: RenderSettings, args: argparse.Namespace) -> RenderSettings:
    """The scene's [render] settings with the command line's options on top."""
    changes: dict[str, object] = {}
    for key in ("width", "height", "quality", "antialias"):
        value = getattr(args, key)
        if value is not None:
            changes[key] = value
    if args.fps is not None:
        changes["fps"] = args.fps
    if args.camera is not None:
        changes["cameras"] = (CameraShot(preset=args.camera),)
    settings = dataclasses.replace(base, **changes)  # type: ignore[arg-type]
    for key in ("width", "height"):
        value = getattr(settings, key)
        if value < 16 or value % 2:
            raise ValueError(f"--{key} {value}: expected an even number of pixels >= 16")
    if not (math.isfinite(settings.fps) and 1.0 <= settings.fps <= 240.0):
        raise ValueError(f"--fps {settings.fps:g}: expected a number in [1, 240]")
    if not 0 <= settings.quality <= 51:
        raise ValueError(f"--quality {settings.quality}: expected an x264 crf in [0, 51]")
    return settings


def main(argv: list[str] | None = None) -> int:
    args = parse_arguments(argv)
    try:
        return _run(args)
    except KeyboardInterrupt:
        print("\ninterrupted: no output written", file=sys.stderr)
        return EXIT_INTERRUPTED


def _run(args: argparse.Namespace) -> int:
    from billiards.render.context import ContextError
    from billiards.scene import SceneError, load_scene
    from billiards.trajectory import Trajectory
    from billiards.video import VideoError

    try:
        scene = load_scene(args.scene)
        settings = _settings(scene.render, args)
    except (SceneError, ValueError) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_USAGE
    if args.frame is not None and not math.isfinite(args.frame):
        print(f"error: --frame {args.frame}: expected a time in s", file=sys.stderr)
        return EXIT_USAGE

    if args.trajectory:
        try:
            trajectory = Trajectory.load(args.trajectory)
        except (OSError, KeyError, ValueError) as error:
            print(
                f"error: {args.trajectory}: cannot read the trajectory ({error})", file=sys.stderr
            )
            return EXIT_USAGE
    else:
        trajectory = _simulate(scene, settings, args.frame)

    try:
        if args.frame is not None:
            return _still(trajectory, settings, args)
        return _film(trajectory, settings, args)
    except (ContextError, VideoError) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_FAILED
    except (OSError, ValueError) as error:
        # A table mesh trimesh cannot read, or an output path that cannot be written.
        print(f"error: {_one_line(error)}", file=sys.stderr)
        return EXIT_FAILED


def _one_line(error: BaseException) -> str:
    text = str(error).strip() or type(error).__name__
    return text.splitlines()[0]


def _simulate(scene: Scene, settings: RenderSettings, still_time: float | None) -> Trajectory:
    from billiards.physics import simulate
    from billiards.trajectory import record_trajectory

    result = simulate(scene)
    start = -settings.lead
    end = result.rest_time + settings.tail
    if still_time is not None:
        # Put the still's time exactly on a recorded frame, so no interpolation
        # blurs a contact that happens between frames.
        steps = math.floor((still_time - start) * settings.fps)
        start = still_time - steps / settings.fps
        end = max(end, still_time)
    return record_trajectory(
        result,
        fps=settings.fps,
        start=start,
        end=end,
        table_size=(scene.table.length, scene.table.width),
    )


def _still(trajectory: Trajectory, settings: RenderSettings, args: argparse.Namespace) -> int:
    from billiards.render.film import render_still, save_still

    output = Path(args.output or Path(settings.output).with_suffix(".png").name)
    if output.suffix.lower() not in (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp"):
        print(f"error: {output}: a still needs an image file name (.png, .jpg)", file=sys.stderr)
        return EXIT_USAGE
    pixels = render_still(trajectory, settings, args.frame)
    save_still(pixels, output)
    if not args.quiet:
        print(
            f"wrote {output} ({settings.width}x{settings.height}, t = {args.frame:g} s)",
            file=sys.stderr,
        )
    return 0


def _film(trajectory: Trajectory, settings: RenderSettings, args: argparse.Namespace) -> int:
    from billiards.render.film import render_film

    output = Path(args.output or settings.output)
    if output.suffix.lower() != ".mp4":
        print(f"error: {output}: the film is an MP4 file (name it .mp4)", file=sys.stderr)
        return EXIT_USAGE
    report = render_film(trajectory, settings, output, progress=None if args.quiet else sys.stderr)
    if not args.quiet:
        print(
            f"wrote {report.path} ({report.frames} frames, {report.frames / report.fps:.1f} s, "
            f"{report.width}x{report.height} at {report.fps:g} fps) in {report.seconds:.1f} s "
            f"({report.frames_per_second:.1f} frames/s)",
            file=sys.stderr,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
