"""The replay page as its users open it: in a real headless Chromium, scrubbed to three
times, and compared with the film's stills at those times from the same camera.

Chromium comes from the system packages (.ci/run installs it when missing); where it
is absent, or no headless OpenGL context can be made for the film's stills, the
browser test skips and says why.
"""

from __future__ import annotations

import dataclasses
import functools
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

from billiards.export import export_gltf
from billiards.export.page import THREE_VERSION
from billiards.physics.engine.result import SimulationResult
from billiards.record.window import film_trajectory
from billiards.scene.reader import load_scene
from billiards.scene.render_table import CameraShot, RenderSettings
from billiards.simulation import simulate_scene
from tests.render.fixtures import needs_gl

WIDTH, HEIGHT = 1280, 720
TIMES = (0.6, 1.2, 2.5)  # s: the break opening, the pack spreading, balls coming to rest
SEARCH = 8  # px: how far each ball's patch is looked for in the other picture
NEAR = 3.0  # px: "in the same place"
Picture = npt.NDArray[np.float64]


@functools.cache
def seed_break() -> SimulationResult:
    return simulate_scene(load_scene("break"))


def chromium() -> str:
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    pytest.skip("Chromium is not installed (apt-get install chromium; .ci/run does)")


BACKGROUND = (21, 23, 26)  # the page's, #15171a: all a page shows before it has drawn
BUDGETS = (3000, 10000, 30000)  # ms of virtual time: more when a loaded machine is slow


def screenshot(page: Path, fragment: str, out: Path) -> Picture:
    """The page at WIDTH x HEIGHT once it has drawn the shot, as grey levels. A shot
    taken before the page drew (on a loaded machine) is background only: taken again,
    with more time."""
    for budget in BUDGETS:
        done = subprocess.run(
            [
                chromium(),
                "--headless=new",
                "--no-sandbox",  # CI runs as root
                "--disable-gpu",
                "--use-angle=swiftshader",  # WebGL on the CPU
                "--enable-unsafe-swiftshader",
                "--no-first-run",
                f"--window-size={WIDTH},{HEIGHT}",
                f"--virtual-time-budget={budget}",
                f"--screenshot={out}",
                f"{page.as_uri()}#{fragment}",
            ],
            capture_output=True,
            text=True,
            check=False,
            timeout=180,
        )
        assert done.returncode == 0 and out.exists(), done.stderr[-2000:]
        rgb = np.asarray(Image.open(out).convert("RGB"))
        if np.mean(np.all(rgb == BACKGROUND, axis=-1)) < 0.5:
            return grey(rgb)
    raise AssertionError(f"{page.name}#{fragment}: the page drew nothing in {BUDGETS[-1]} ms")


def grey(rgb: npt.NDArray[np.uint8]) -> Picture:
    return np.asarray(rgb, dtype=np.float64) @ np.array([0.2126, 0.7152, 0.0722])


def edges(picture: Picture) -> Picture:
    """Gradient magnitude: ball outlines, whatever either renderer's lighting."""
    gy, gx = np.gradient(picture)
    return np.asarray(np.hypot(gx, gy))


def shift_of(
    first: Picture, second: Picture, centre: tuple[float, float], half: int
) -> tuple[int, int]:
    """The shift (dx, dy) in px that best lays the patch of `first` round `centre` on
    `second` (normalised cross-correlation of their edges, within SEARCH px)."""
    x, y = round(centre[0]), round(centre[1])
    patch = first[y - half : y + half + 1, x - half : x + half + 1]
    patch = (patch - patch.mean()) / (patch.std() + 1e-9)
    best, where = -np.inf, (0, 0)
    for dy in range(-SEARCH, SEARCH + 1):
        for dx in range(-SEARCH, SEARCH + 1):
            other = second[y + dy - half : y + dy + half + 1, x + dx - half : x + dx + half + 1]
            other = (other - other.mean()) / (other.std() + 1e-9)
            score = float(np.mean(patch * other))
            if score > best:
                best, where = score, (dx, dy)
    return where


def ball_pixels(
    result: SimulationResult, settings: RenderSettings, time: float
) -> npt.NDArray[np.float64]:
    """Where the film's overhead camera puts each ball still on the table (px)."""
    from billiards.stage.cameras import Stage, preset_pose

    trajectory = film_trajectory(result, settings)
    pose = preset_pose("overhead", Stage.of(trajectory), WIDTH / HEIGHT)
    flat = result.positions_at(np.array([time]))[0]
    points = np.column_stack([flat, np.full(len(flat), result.radius)])
    pocketed = {e.balls[0] for e in result.events if e.kind == "pocket" and e.time <= time}
    keep = [i for i, ball in enumerate(result.ball_ids) if ball not in pocketed]
    return pose.project(points[keep], WIDTH, HEIGHT)


class _Fetches(HTMLParser):
    """The tags of a page that would fetch something (src, href or data)."""

    def __init__(self) -> None:
        super().__init__()
        self.found: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.found += [f"<{tag} {name}>" for name, _ in attrs if name in ("src", "href", "data")]


def fetched(text: str) -> list[str]:
    parser = _Fetches()
    parser.feed(text)
    return parser.found


def test_the_fetch_check_can_fail() -> None:
    assert fetched('<p><script src="three.js"></script></p>') == ["<script src>"]


def film_stills(result: SimulationResult, settings: RenderSettings) -> list[Picture]:
    from billiards.render.gl.context import create_context
    from billiards.render.gl.renderer import Renderer
    from billiards.stage.cameras import Stage, preset_pose

    trajectory = film_trajectory(result, settings)
    pose = preset_pose("overhead", Stage.of(trajectory), WIDTH / HEIGHT)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (WIDTH, HEIGHT), settings.antialias, None)
    try:
        return [grey(renderer.frame(t, pose, 0.0)) for t in TIMES]
    finally:
        renderer.release()
        ctx.release()


def test_the_page_is_one_offline_file_below_3_mb(tmp_path: Path) -> None:
    page = tmp_path / "shot.html"
    export_gltf(seed_break(), html=page)
    text = page.read_text()
    assert page.stat().st_size < 3_000_000
    assert fetched(text) == []  # nothing to fetch: every script inline
    assert f"three.js {THREE_VERSION}" in text


@pytest.mark.long
@needs_gl
@pytest.mark.gl
def test_the_page_shows_the_balls_where_the_film_does(tmp_path: Path) -> None:
    chromium()
    result = seed_break()
    # No cue: the page draws none, and the stick's edges beside a ball would move its match.
    settings = dataclasses.replace(
        RenderSettings(), cameras=(CameraShot(preset="overhead"),), shutter=0.0, cue=False
    )
    page = tmp_path / "shot.html"
    export_gltf(result, html=page, settings=settings)
    stills = film_stills(result, settings)
    half = 14  # px: a ball's patch, about its diameter and a half
    shots = []
    for index, (time, still) in enumerate(zip(TIMES, stills, strict=True)):
        shown = screenshot(page, f"t={time}&camera=1-overhead&clean", tmp_path / f"{index}.png")
        shots.append(shown)
        film_edges, page_edges = edges(still), edges(shown)
        for centre in ball_pixels(result, settings, time):
            dx, dy = shift_of(film_edges, page_edges, (centre[0], centre[1]), half)
            assert np.hypot(dx, dy) <= NEAR, (time, centre, (dx, dy))
    # The check can fail: the film's first still against the page at the second time.
    film_edges, page_edges = edges(stills[0]), edges(shots[1])
    moved = [
        np.hypot(*shift_of(film_edges, page_edges, (c[0], c[1]), half))
        for c in ball_pixels(result, settings, TIMES[0])
    ]
    assert max(moved) > NEAR
