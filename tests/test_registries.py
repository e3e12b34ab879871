"""The names a scene file may give are the names the physics implements: the scene
reader keeps its own lists (it imports nothing of the physics), so a name added to one
side and not the other fails here."""

from __future__ import annotations

import pytest

from billiards import scene
from billiards.physics import laws, setup
from billiards.scene import SceneError, parse_scene

BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [2.0, 0.0]\n'


def test_the_scene_reader_names_the_physics_models() -> None:
    assert scene.MODELS == setup.MODELS
    assert scene.Physics.model == setup.Setup.model


def test_the_scene_reader_names_every_cushion_law_and_no_other() -> None:
    registered = set(laws.CUSHION_LAWS) | set(laws.SPIN_CUSHION_LAWS)
    assert sorted(scene.CUSHION_MODELS) == sorted(registered)


def test_every_cushion_law_of_the_rolling_model_has_its_form_at_a_jaw() -> None:
    assert set(laws.CUSHION_LAWS) <= set(laws.JAW_LAWS)
    assert set(laws.JAW_LAWS) <= set(laws.CUSHION_LAWS) | set(laws.SPIN_CUSHION_LAWS)


@pytest.mark.parametrize("name", scene.CUSHION_MODELS)
def test_the_rolling_model_takes_exactly_the_cushion_laws_that_keep_no_spin(name: str) -> None:
    text = f'[physics]\ncushion_model = "{name}"\n' + BALL
    if name in laws.CUSHION_LAWS:
        assert parse_scene(text).physics.cushion_model == name
    else:
        with pytest.raises(SceneError) as caught:
            parse_scene(text)
        assert 'expected physics.model = "spin" first' in str(caught.value)


def test_the_defaults_name_the_seed_laws() -> None:
    assert laws.DEFAULT_BALL_LAW in laws.BALL_LAWS
    assert laws.DEFAULT_CUSHION_LAW in laws.CUSHION_LAWS
    assert setup.Setup.ball_law == laws.DEFAULT_BALL_LAW
    assert setup.Setup.cushion_law == laws.DEFAULT_CUSHION_LAW
    assert scene.Physics.cushion_model == laws.DEFAULT_CUSHION_LAW
