"""The seed's numbers have one home (billiards.rules.seed): a scene of defaults and a Setup
of defaults are the same run, in either model."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.rules import seed
from billiards.scene.reader import load_scene, parse_scene
from billiards.simulation import setup_from_scene

BALL = '[[ball]]\nid = "cue"\nposition = [0.5, 0.5]\nvelocity = [2.0, 0.0]\n'


@pytest.mark.parametrize("model", ["rolling", "spin"])
def test_a_scene_of_defaults_is_a_setup_of_defaults(model: str) -> None:
    bridged = setup_from_scene(parse_scene(f'[physics]\nmodel = "{model}"\n' + BALL))
    spins = bridged.spins if model == "spin" else None
    defaults = Setup.of(
        bridged.positions, bridged.velocities, bridged.masses, model=model, spins=spins
    )
    for field in fields(Setup):
        ours, theirs = getattr(bridged, field.name), getattr(defaults, field.name)
        if isinstance(ours, np.ndarray):
            assert np.array_equal(ours, theirs), field.name
        else:
            assert ours == theirs, field.name


def test_the_seed_break_is_the_cue_ball_on_the_head_spot_and_the_rack_on_the_foot_spot() -> None:
    scene = load_scene()
    cue, apex = scene.balls[0], scene.balls[1]
    assert cue.position == seed.head_spot(seed.TABLE_SIZE)
    assert cue.velocity == (seed.CUE_SPEED, 0.0) and cue.mass == seed.CUE_MASS
    assert apex.position == seed.foot_spot(seed.TABLE_SIZE) and apex.mass == seed.MASS
    assert parse_scene("").balls == scene.balls  # the file spells out the defaults
