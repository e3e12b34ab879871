"""Export speed and size: the seed break and pool_break as .glb and as a replay page.

    python scripts/bench_export.py                    # break and pool_break, 3 repeats
    python scripts/bench_export.py spin_break --repeats 1

For each scene it prints, from a simulation already made (the export alone):
  glb s      seconds to build and write the .glb (best of the repeats),
  html s     the same for the page (the .glb embedded, three.js bundled),
  glb kB     the .glb's size; html kB the page's,
  keys/ball  translation keys per ball (mean, and the most a ball has),
  rot/ball   rotation keys per ball (mean, most) at the default angle bound,
  deviation  the largest distance (m) of the keys' curves (float64) from the
             simulated centres, before any drop.
Aims for the seed break: under 2 s and under 1 MB for the .glb, under 3 MB for the page.
The machine's speed can swing from minute to minute: compare rows of one run.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from billiards.export.shot import ExportReport, export_gltf
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene


def best(scene: str, repeats: int, folder: Path, page: bool) -> tuple[float, ExportReport]:
    result = simulate_scene(load_scene(scene))
    fastest, report = float("inf"), None
    for index in range(repeats):
        if page:
            report = export_gltf(result, html=folder / f"{scene}-{index}.html")
        else:
            report = export_gltf(result, folder / f"{scene}-{index}.glb")
        fastest = min(fastest, report.seconds)
    assert report is not None
    return fastest, report


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenes", nargs="*", default=["break", "pool_break"])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    header = (
        f"{'scene':<12} {'glb s':>6} {'html s':>6} {'glb kB':>7} {'html kB':>8} "
        f"{'keys/ball':>10} {'rot/ball':>10} {'deviation':>10}"
    )
    print(header)
    with tempfile.TemporaryDirectory() as work:
        folder = Path(work)
        for scene in args.scenes:
            glb_seconds, glb = best(scene, args.repeats, folder, page=False)
            html_seconds, html = best(scene, args.repeats, folder, page=True)
            keys = list(glb.translation_keys.values())
            turns = list(glb.rotation_keys.values())
            print(
                f"{scene:<12} {glb_seconds:>6.2f} {html_seconds:>6.2f} "
                f"{glb.sizes['.glb'] / 1e3:>7.0f} {html.sizes['.html'] / 1e3:>8.0f} "
                f"{sum(keys) / len(keys):>6.1f} {max(keys):>3} "
                f"{sum(turns) / len(turns):>6.1f} {max(turns):>3} {glb.deviation:>10.1e}"
            )


if __name__ == "__main__":
    main()
