"""Facts about the README's first films, as it tells them: the seed break (the default
film) on a table without pockets in about 12 s, and `pool_break`, the film it shows for
pockets, with a drop and the director's cut to that pocket before it. No GL."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from billiards.record.window import film_trajectory
from billiards.render.director import directed_shots
from billiards.render.film_clock import FilmClock
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene

README = Path(__file__).parents[2] / "README.md"


def install_block() -> list[str]:
    """The commands of the README's first code block (install, films, tests)."""
    text = README.read_text(encoding="utf-8")
    block = text.split("## Install, film, test", 1)[1].split("\n\n    ", 1)[1].split("\n\n", 1)[0]
    return [line.strip() for line in ("    " + block).splitlines()]


def test_the_readmes_first_film_is_the_seed_break_without_pockets_in_about_12_s() -> None:
    films = [line for line in install_block() if "billiards.render" in line]
    assert films[0].split("#")[0].split() == [".venv/bin/python", "-m", "billiards.render"]
    scene = load_scene(None)
    assert not scene.table.pockets  # "on a table without pockets"
    trajectory = film_trajectory(simulate_scene(scene), scene.render)
    clock = FilmClock.of(trajectory, scene.render.fps, scene.render.slow_motion)
    said = re.search(r"as they stop: (\d+) s\.", README.read_text(encoding="utf-8"))
    assert said is not None
    assert clock.duration == pytest.approx(float(said.group(1)), abs=0.5)


def test_the_readmes_pocket_film_drops_a_ball_after_a_cut_to_its_pocket() -> None:
    films = [line for line in install_block() if "billiards.render" in line]
    scene_name = films[1].split("#")[0].split()[3]
    assert scene_name == "pool_break" and "pockets" in films[1]
    scene = load_scene(scene_name)
    result = simulate_scene(scene)
    assert result.pockets is not None and result.pocketed
    trajectory = film_trajectory(result, scene.render)
    shots = directed_shots(trajectory, scene.render.width / scene.render.height)
    assert trajectory.pockets is not None
    for drop in result.pocketed:
        x, y, _ = trajectory.pockets.holes[trajectory.pockets.names.index(drop.pocket)]
        before = [shot for shot in shots if shot.start is not None and shot.start < drop.time]
        last = before[-1]  # the shot on screen as the ball drops
        assert last.target is not None and last.start is not None
        assert math.dist(last.target[:2], (x, y)) < 0.3, (drop, last)
        assert drop.time - last.start <= 1.0  # cut to just before the drop
