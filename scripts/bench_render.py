"""Render speed of the default film: render-only, encode-only and end to end.

    python scripts/bench_render.py                      # 1280x720 and 1920x1080 at 30 fps
    python scripts/bench_render.py --sizes 640x360 --antialias 0 --slow-motion 0.25
    python scripts/bench_render.py --shutter 0                       # no motion blur

For each size it prints frames/s of
  render   drawing and reading back every frame of the default film (no encoding),
           in the film's pixel format (yuv420p: the GL side converts),
  encode   H.264-encoding those same frames (read back from a raw file, no drawing),
  e2e      the whole film as `python -m billiards.render` makes it (drawing and
           encoding overlapped, context and textures included, the sound track
           synthesized and muxed as AAC by the same ffmpeg run), in a fresh process,
  e2e CPU  that process's CPU time and its ffmpeg's (user + sys) per frame: on a
           shared machine it moves far less than frames/s,
  silent   the same with --no-sound,
the time to synthesize the sound track, and the peak resident memory of the
end-to-end process and its ffmpeg (the larger).
The machine's speed can swing from minute to minute: compare rows of one run.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from billiards.record.trajectory import Trajectory
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.film import camera_poses, camera_timeline, render_film
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.render.sound.soundtrack import film_sound
from billiards.render.video import VideoWriter, frame_bytes
from billiards.scene.reader import load_scene
from billiards.scene.render_table import RenderSettings
from billiards.simulation import simulate_scene


def render_only(
    trajectory: Trajectory, settings: RenderSettings, raw: Path
) -> tuple[float, int, str]:
    """frames/s of drawing and reading back as a film does (frames saved raw for the
    encode pass), the frame count and the pixel format."""
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    cameras = camera_timeline(trajectory, settings)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (settings.width, settings.height), settings.antialias)
    pixel_format = renderer.output.film_format()
    spent = 0.0
    with raw.open("wb") as sink:
        exposures = clock.exposures(settings.shutter)
        for index, (pose, moving) in enumerate(camera_poses(cameras, clock)):
            started = time.perf_counter()
            frame = renderer.draw(
                float(clock.sim_times[index]), pose, moving, float(exposures[index]), pixel_format
            )
            spent += time.perf_counter() - started
            sink.write(frame)
    renderer.release()
    ctx.release()
    return clock.frame_count / spent, clock.frame_count, pixel_format


def sound_seconds(trajectory: Trajectory, settings: RenderSettings) -> float:
    """s to synthesize the film's sound track (median of 3)."""
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    spent = []
    for _ in range(3):
        started = time.perf_counter()
        film_sound(trajectory.events, clock, settings, trajectory.strike, trajectory)
        spent.append(time.perf_counter() - started)
    return sorted(spent)[1]


def encode_only(
    raw: Path, settings: RenderSettings, frames: int, pixel_format: str, out: Path
) -> float:
    size = frame_bytes((settings.width, settings.height), pixel_format)
    started = time.perf_counter()
    with (
        raw.open("rb") as source,
        VideoWriter(
            out,
            (settings.width, settings.height),
            settings.fps,
            quality=settings.quality,
            pixel_format=pixel_format,
        ) as writer,
    ):
        for _ in range(frames):
            writer.write(source.read(size))
    return frames / (time.perf_counter() - started)


def end_to_end_child(settings: RenderSettings, out: str) -> None:
    """Runs in a fresh process: the film as the CLI makes it; prints JSON."""
    started = time.perf_counter()
    scene = load_scene(None)
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    report = render_film(trajectory, settings, out, progress=None)
    seconds = time.perf_counter() - started
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)  # ffmpeg, waited for
    cpu = sum(u.ru_utime + u.ru_stime for u in (own, children))
    print(
        json.dumps(
            {
                "frames": report.frames,
                "seconds": seconds,
                "cpu_seconds": cpu,
                "peak_kib": max(own.ru_maxrss, children.ru_maxrss),
            }
        )
    )


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--sizes", default="1280x720,1920x1080")
    parser.add_argument("--fps", type=float, default=30.0)
    parser.add_argument("--antialias", type=int, default=RenderSettings.antialias)
    parser.add_argument("--slow-motion", type=float, default=RenderSettings.slow_motion)
    parser.add_argument("--shutter", type=float, default=RenderSettings.shutter)
    parser.add_argument("--child", nargs=8, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        run_child(args.child)
        return

    scene = load_scene(None)
    command = "python scripts/bench_render.py " + " ".join(sys.argv[1:])
    print(f"# {command.strip()}")
    print(
        f"# default film, {args.fps:g} fps, antialias {args.antialias}, "
        f"slow motion {args.slow_motion:g}, shutter {args.shutter:g}, {os.cpu_count()} cores"
    )
    print(
        "| size | frames | render fps | encode fps | e2e fps (sound) | e2e s "
        "| e2e CPU ms/frame | silent fps | sound synth s | peak MiB |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for size in args.sizes.split(","):
        width, height = (int(v) for v in size.lower().split("x"))
        settings = RenderSettings(
            width=width,
            height=height,
            fps=args.fps,
            antialias=args.antialias,
            slow_motion=args.slow_motion,
            shutter=args.shutter,
        )
        trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
        synth = sound_seconds(trajectory, settings)
        with tempfile.TemporaryDirectory(prefix="bench_render.") as folder:
            raw = Path(folder) / "frames.raw"
            render_fps, frames, pixel_format = render_only(trajectory, settings, raw)
            encode_fps = encode_only(
                raw, settings, frames, pixel_format, Path(folder) / "encode.mp4"
            )
            raw.unlink()
            runs = {
                sound: end_to_end(settings, sound, Path(folder)) for sound in ("sound", "silent")
            }
        result = runs["sound"]
        e2e = result["frames"] / result["seconds"]
        silent = runs["silent"]["frames"] / runs["silent"]["seconds"]
        print(
            f"| {width}x{height} | {frames} | {render_fps:.1f} | {encode_fps:.1f} | {e2e:.1f} "
            f"| {result['seconds']:.1f} | {result['cpu_seconds'] / frames * 1000:.0f} "
            f"| {silent:.1f} | {synth:.2f} "
            f"| {result['peak_kib'] / 1024:.0f} |",
            flush=True,
        )


def run_child(fields: list[str]) -> None:
    """The --child process: one end-to-end film from its eight fields (end_to_end)."""
    width, height, fps, antialias, slow, shutter, sound, out = fields
    child = RenderSettings(
        width=int(width),
        height=int(height),
        fps=float(fps),
        antialias=int(antialias),
        slow_motion=float(slow),
        shutter=float(shutter),
        sound=sound == "sound",
    )
    end_to_end_child(child, out)


def end_to_end(settings: RenderSettings, sound: str, folder: Path) -> dict[str, float]:
    """One film made end to end in a fresh process (--child), with sound or "silent":
    its frames, seconds, CPU seconds and peak memory as the child reports them."""
    done = subprocess.run(
        [
            sys.executable,
            __file__,
            "--child",
            str(settings.width),
            str(settings.height),
            str(settings.fps),
            str(settings.antialias),
            str(settings.slow_motion),
            str(settings.shutter),
            sound,
            str(folder / f"{sound}.mp4"),
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    report: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return report


if __name__ == "__main__":
    main()
