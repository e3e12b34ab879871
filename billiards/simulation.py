"""The bridge from a scene to the physics: a scene's numbers become a Setup, and run.

It sits above both the scene reader and the physics, which know nothing of each other.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.result import SimulationResult
from billiards.physics.setup import Setup
from billiards.physics.stepper import run
from billiards.scene import Scene


def setup_from_scene(scene: Scene) -> Setup:
    return Setup(
        positions=np.array([ball.position for ball in scene.balls], dtype=np.float64),
        velocities=np.array([ball.velocity for ball in scene.balls], dtype=np.float64),
        masses=np.array([ball.mass for ball in scene.balls], dtype=np.float64),
        radius=scene.radius,
        table_size=(scene.table.length, scene.table.width),
        decel=scene.physics.rolling_friction * scene.physics.gravity,
        restitution=scene.physics.ball_restitution,
        retention=scene.table.cushion_retention,
        max_time=scene.simulation.max_time,
        max_events=scene.simulation.max_events,
    )


def simulate_scene(
    scene: Scene, method: str | None = None, dt: float | None = None
) -> SimulationResult:
    """Simulate a scene to rest (or max_time). method and dt default to the scene's."""
    return run(
        setup_from_scene(scene),
        scene.ball_ids,
        method or scene.simulation.method,
        dt if dt is not None else scene.simulation.dt,
    )
