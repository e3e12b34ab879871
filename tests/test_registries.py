"""The names a scene file may give are the names the physics implements: the scene
reader keeps its own lists (it imports nothing of the physics), so a name added to one
side and not the other fails here."""

from __future__ import annotations

import pytest

from billiards.physics import laws
from billiards.physics.engine import setup
from billiards.physics.engine.motion_law import MOTION_LAWS
from billiards.scene import reader as scene
from billiards.scene.reader import parse_scene

BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [2.0, 0.0]\n'


def test_the_scene_reader_names_the_physics_models() -> None:
    assert sorted(scene.MODELS) == sorted(MOTION_LAWS)
    assert scene.Physics.model == setup.Setup.model


def test_the_scene_reader_names_every_ball_law_and_no_other() -> None:
    assert sorted(scene.BALL_MODELS) == sorted(laws.BALL_LAWS)
    assert scene.Physics.ball_model == laws.DEFAULT_BALL_LAW


@pytest.mark.parametrize("name", scene.BALL_MODELS)
def test_the_spin_model_takes_every_ball_law(name: str) -> None:
    text = f'[physics]\nmodel = "spin"\nball_model = "{name}"\n' + BALL
    assert parse_scene(text).physics.ball_model == name


def test_the_scene_reader_names_every_cushion_law_and_no_other() -> None:
    assert sorted(scene.CUSHION_MODELS) == sorted(laws.CUSHION_LAWS)


@pytest.mark.parametrize("name", scene.CUSHION_MODELS)
def test_the_spin_model_takes_every_cushion_law(name: str) -> None:
    text = f'[physics]\nmodel = "spin"\ncushion_model = "{name}"\n' + BALL
    assert parse_scene(text).physics.cushion_model == name


def test_the_defaults_name_the_seed_laws() -> None:
    assert laws.DEFAULT_BALL_LAW in laws.BALL_LAWS
    assert laws.DEFAULT_CUSHION_LAW in laws.CUSHION_LAWS
    assert setup.Setup.ball_law == laws.DEFAULT_BALL_LAW
    assert setup.Setup.cushion_law == laws.DEFAULT_CUSHION_LAW
    assert scene.Physics.cushion_model == laws.DEFAULT_CUSHION_LAW
