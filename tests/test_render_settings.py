"""The scene file's [render] keys and [[camera]] shots, read with the rest of the scene."""

from __future__ import annotations

from pathlib import Path

import pytest

from billiards.scene.reader import SceneError, load_scene, parse_scene
from billiards.scene.render_table import CameraShot, RenderSettings

BALLS = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\n'


def render_of(text: str) -> RenderSettings:
    return parse_scene(BALLS + text, "t.toml").render


def test_render_keys_and_camera_shots_are_read() -> None:
    settings = render_of(
        """
[render]
width = 640
height = 360
fps = 60
quality = 18
output = "shot.mp4"
antialias = 2

[[camera]]
preset = "overhead"

[[camera]]
start = 2.0
eye = [1.0, -1.0, 0.5]
target = [1.0, 0.5, 0.0]
fov = 30
transition = "ease"
ease = 0.5
"""
    )
    assert (settings.width, settings.height, settings.fps, settings.quality) == (640, 360, 60.0, 18)
    assert settings.output == "shot.mp4" and settings.antialias == 2
    assert settings.cameras == (
        CameraShot(preset="overhead"),
        CameraShot(
            start=2.0,
            eye=(1.0, -1.0, 0.5),
            target=(1.0, 0.5, 0.0),
            fov=30.0,
            transition="ease",
            ease=0.5,
        ),
    )


def test_defaults_need_no_render_table() -> None:
    assert render_of("") == RenderSettings()


def test_the_shutter_is_read_and_zero_turns_motion_blur_off() -> None:
    assert render_of("[render]\nshutter = 0").shutter == 0.0
    assert render_of("[render]\nshutter = 0.25").shutter == 0.25
    assert RenderSettings().shutter == 0.5


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[render]\nwidth = 641", "render.width = 641: expected an even"),
        ("[render]\nantialias = 3", "render.antialias = 3: expected one of 0, 2, 4, 8"),
        ("[render]\nquality = 60", "render.quality = 60"),
        ("[render]\nspeed = 2", "render.speed: unknown key"),
        (
            "[render]\nshutter = -0.5",
            "render.shutter = -0.5: expected a share of the frame time in [0, 1]",
        ),
        ('[render]\nshutter = "half"', "render.shutter = 'half': expected a share"),
        (
            '[[camera]]\npreset = "drone"',
            "camera[0].preset = 'drone': expected one of \"overhead\"",
        ),
        ("[[camera]]\neye = [0, 0, 1]", "camera[0].target: missing; expected [x, y, z]"),
        (
            '[[camera]]\npreset = "overhead"\n[[camera]]\npreset = "orbit"',
            "camera[1].start: missing",
        ),
        (
            '[[camera]]\nstart = 2\npreset = "overhead"\n[[camera]]\nstart = 1\npreset = "orbit"',
            "camera[1].start = 1",
        ),
        ('[[camera]]\npreset = "overhead"\ntransition = "wipe"', "camera[0].transition = 'wipe'"),
    ],
)
def test_bad_render_settings_are_one_line_errors(text: str, message: str) -> None:
    with pytest.raises(SceneError) as caught:
        render_of(text)
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_a_table_mesh_is_found_next_to_the_scene_file(tmp_path: Path) -> None:
    (tmp_path / "table.glb").write_bytes(b"")
    scene = tmp_path / "my.toml"
    scene.write_text(BALLS + '[render]\ntable_mesh = "table.glb"\n')
    assert load_scene(scene).render.table_mesh == str(tmp_path / "table.glb")


def test_a_missing_table_mesh_is_a_scene_error(tmp_path: Path) -> None:
    scene = tmp_path / "my.toml"
    scene.write_text(BALLS + '[render]\ntable_mesh = "nope.glb"\n')
    with pytest.raises(SceneError) as caught:
        load_scene(scene)
    assert "render.table_mesh = 'nope.glb': expected an existing mesh file" in str(caught.value)


@pytest.mark.parametrize(
    ("key", "bad"),
    [
        ("width", "17"),
        ("height", "8"),
        ("fps", "0.5"),
        ("quality", "52"),
        ("slow_motion", "0.0"),
        ("shutter", "1.5"),
    ],
)
def test_the_scene_file_and_the_command_line_reject_a_render_number_alike(
    key: str, bad: str
) -> None:
    from billiards.render.__main__ import _settings, build_parser

    with pytest.raises(SceneError) as from_file:
        render_of(f"[render]\n{key} = {bad}")
    with pytest.raises(ValueError) as from_options:
        _settings(RenderSettings(), build_parser().parse_args([f"--{key.replace('_', '-')}={bad}"]))
    expected = str(from_file.value).split(": expected ", 1)[1]
    assert str(from_options.value).endswith(f": expected {expected}")


def test_the_cue_is_drawn_unless_turned_off() -> None:
    assert RenderSettings().cue
    assert render_of("[render]\ncue = false\n").cue is False


def test_a_cue_that_is_not_true_or_false_is_an_error_naming_it() -> None:
    with pytest.raises(SceneError, match=r"render\.cue.*'no'.*true or false"):
        render_of('[render]\ncue = "no"\n')
