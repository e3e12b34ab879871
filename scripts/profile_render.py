"""Where the default film's render time goes: per shot, wall-clock and CPU ms a frame.

    python scripts/profile_render.py                     # 1280x720, the default film
    python scripts/profile_render.py --size 1920x1080 --shutter 0
    python scripts/profile_render.py --cprofile 15       # and the 15 costliest functions

Each frame is drawn and read back as the film does it (no encoding). CPU time is the
process's, llvmpipe's rasterizer threads included: on a shared machine it moves far
less than the wall-clock time, so compare CPU columns between runs.
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import sys
import time

from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.film import camera_poses, camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.scene.reader import load_scene
from billiards.scene.render_table import RenderSettings
from billiards.simulation import simulate_scene


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--antialias", type=int, default=RenderSettings.antialias)
    parser.add_argument("--shutter", type=float, default=RenderSettings.shutter)
    parser.add_argument("--cprofile", type=int, default=0, metavar="N")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    settings = RenderSettings(
        width=width, height=height, antialias=args.antialias, shutter=args.shutter
    )
    scene = load_scene(None)
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    cameras = camera_timeline(trajectory, settings)
    exposures = clock.exposures(settings.shutter)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (width, height), settings.antialias)
    profile = cProfile.Profile()
    # per shot: frames, frames with the camera moving, wall s, CPU s
    shots: dict[int, list[float]] = {}
    for index, (pose, moving) in enumerate(camera_poses(cameras, clock)):
        time_s = float(clock.sim_times[index])
        shot = max(k for k, s in enumerate(cameras.shots) if s.start <= time_s or k == 0)
        wall, cpu = time.perf_counter(), time.process_time()
        if args.cprofile:
            profile.enable()
        renderer.draw(time_s, pose, moving, float(exposures[index]))
        if args.cprofile:
            profile.disable()
        row = shots.setdefault(shot, [0, 0, 0.0, 0.0])
        row[0] += 1
        row[1] += moving
        row[2] += time.perf_counter() - wall
        row[3] += time.process_time() - cpu
    renderer.release()
    ctx.release()
    print(f"# python scripts/profile_render.py {' '.join(sys.argv[1:])}".strip())
    print("| shot | frames | moving | wall ms/frame | CPU ms/frame | CPU s |")
    print("| --- | --- | --- | --- | --- | --- |")
    for shot, (count, turning, spent, used) in sorted(shots.items()):
        name = cameras.shots[shot].transition
        print(
            f"| {shot} {name} | {count:.0f} | {turning:.0f} | {spent / count * 1000:.1f} "
            f"| {used / count * 1000:.1f} | {used:.2f} |"
        )
    frames = sum(row[0] for row in shots.values())
    wall = sum(row[2] for row in shots.values())
    cpu = sum(row[3] for row in shots.values())
    print(
        f"| all | {frames:.0f} | | {wall / frames * 1000:.1f} | {cpu / frames * 1000:.1f} "
        f"| {cpu:.2f} |"
    )
    if args.cprofile:
        pstats.Stats(profile).sort_stats("tottime").print_stats(args.cprofile)


if __name__ == "__main__":
    main()
