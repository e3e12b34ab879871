"""A command that is named no output writes one named after its scene: `plot
masse_shot` -> masse_shot.png, `render pool_break` -> pool_break.mp4, a file my.toml ->
my.*, the seed break -> break.*; so two commands on two scenes never clash."""

from __future__ import annotations

from pathlib import Path

import pytest

from billiards.render.__main__ import _output_path, build_parser
from billiards.scene.render_table import RenderSettings
from billiards.shell.cli import default_output, scene_name
from tests.commands import run_module


@pytest.mark.parametrize(
    ("scene", "name"),
    [
        (None, "break"),
        ("break", "break"),
        ("masse_shot", "masse_shot"),
        ("masse_shot.toml", "masse_shot"),
        ("my.toml", "my"),
        ("scenes/my.toml", "my"),
        ("../shots/bank.v2.toml", "bank.v2"),
    ],
)
def test_a_default_output_is_named_after_the_scene(scene: str | None, name: str) -> None:
    assert scene_name(scene) == name
    assert default_output(scene, ".png") == f"{name}.png"


@pytest.mark.parametrize(
    ("arguments", "settings", "output"),
    [
        ([], RenderSettings(), "break.mp4"),
        (["pool_break"], RenderSettings(), "pool_break.mp4"),
        (["scenes/my.toml"], RenderSettings(), "my.mp4"),
        (["pool_break", "--frame", "1"], RenderSettings(), "pool_break.png"),
        (["--trajectory", "saved/shot.npz"], RenderSettings(), "shot.mp4"),
        (["pool_break"], RenderSettings(output="film.mp4"), "film.mp4"),  # [render] output
        (["pool_break", "--frame", "1"], RenderSettings(output="film.mp4"), "film.png"),
        (["pool_break", "-o", "x.mp4"], RenderSettings(output="film.mp4"), "x.mp4"),
    ],
)
def test_render_names_its_film_after_the_scene(
    arguments: list[str], settings: RenderSettings, output: str
) -> None:
    assert _output_path(build_parser().parse_args(arguments), settings) == Path(output)


@pytest.mark.long
def test_plot_after_plot_of_another_scene_does_not_clash(tmp_path: Path) -> None:
    # The case: `plot masse_shot` after `plot` stopped at break.png.
    for scene in ([], ["masse_shot"]):
        run = run_module("billiards.plot", *scene, "--width", "64", "--quiet", cwd=tmp_path)
        assert run.returncode == 0, run.stderr
    assert sorted(path.name for path in tmp_path.iterdir()) == ["break.png", "masse_shot.png"]


@pytest.mark.long
def test_a_sweep_writes_its_scenes_folder(tmp_path: Path) -> None:
    args = ["newtons_cradle", "--runs", "2", "--workers", "0", "--quiet"]
    run = run_module("billiards.sweep", *args, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert [path.name for path in tmp_path.iterdir()] == ["newtons_cradle_sweep"]
    assert (tmp_path / "newtons_cradle_sweep" / "summary.json").is_file()


@pytest.mark.long
@pytest.mark.parametrize(
    ("module", "text"),
    [
        ("billiards.plot", "SCENE.png"),
        ("billiards.render", "SCENE.mp4"),
        ("billiards.sweep", "SCENE_sweep"),
    ],
)
def test_help_says_how_the_default_output_is_named(module: str, text: str) -> None:
    run = run_module(module, "--help")
    assert run.returncode == 0 and text in " ".join(run.stdout.split())
