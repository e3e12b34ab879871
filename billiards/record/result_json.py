"""A simulated result as JSON values: what `simulate --json` prints and the library's
`Result.to_dict` gives, in one place. A record of the run beside the film's trajectory:
it reads the physics' result and the scene, and may use libm (the squirt's angle in
degrees), which the bridge's arithmetic may not (tests/physics/test_machine_independence.py).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from billiards.physics.engine.result import SimulationResult
from billiards.scene.reader import Scene
from billiards.scene.stroke import strike

# The most times a result is sampled at in one call (`simulate --times`, the library's
# Result.positions, .velocities, .spins and to_dict): a minute of play at 1 kHz is
# 60,000; 16 balls' spins at this many times are 38 MB, the closed forms' working
# arrays a few times that.
MAX_TIMES = 100_000


def strokes_json(scene: Scene) -> list[dict[str, Any]]:
    """What each struck ball (`cue = {...}`) left the cue with: its velocity on the cloth,
    its spin and its squirt angle (degrees, + = to the left of the cue's line)."""
    strokes = []
    for ball in scene.balls:
        if ball.stroke is None:
            continue
        struck = strike(ball.stroke, ball.mass, scene.radius)
        sin_a, cos_a = struck.squirt
        strokes.append(
            {
                "ball": ball.id,
                "velocity": list(struck.velocity),
                "spin": list(struck.spin),
                "squirt": math.degrees(math.atan2(sin_a, cos_a)),
            }
        )
    return strokes


def result_json(
    result: SimulationResult, times: Sequence[float] | None, scene: Scene | None = None
) -> dict[str, Any]:
    """What `simulate --json` prints (and `Result.to_dict` gives): ball ids, method,
    events, drops, motion-state changes, rest time, final positions, strokes, and with
    `times` every ball's position, velocity and spin at each."""
    data: dict[str, Any] = {
        "balls": list(result.ball_ids),
        "method": result.method,
        "events": [
            {
                "t": event.time,
                "kind": event.kind,
                "balls": list(event.balls),
                "impact_speed": event.impact_speed,
                # The pocket of a drop, or of the jaw a cushion contact struck.
                **({"pocket": event.pocket} if event.pocket is not None else {}),
            }
            for event in result.events
        ],
        "pocketed": [
            {"ball": drop.ball, "pocket": drop.pocket, "t": drop.time} for drop in result.pocketed
        ],
        "transitions": [
            {"t": change.time, "ball": change.ball, "state": change.state}
            for change in result.transitions
        ],
        "rest_time": result.rest_time,
        "complete": result.complete,
        "stopped_by": result.stopped_by,
        "steps": result.steps,
        "final_positions": result.final_positions.tolist(),
        "strokes": [] if scene is None else strokes_json(scene),
    }
    if times:
        at = np.array(times)
        positions = result.positions_at(at)
        velocities = result.velocities_at(at)
        spins = result.spins_at(at)
        data["samples"] = [
            {
                "t": t,
                "positions": sample.tolist(),
                "velocities": velocity.tolist(),
                "spins": spin.tolist(),
            }
            for t, sample, velocity, spin in zip(times, positions, velocities, spins, strict=True)
        ]
    return data
