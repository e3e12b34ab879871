"""The compiled laws over rows of contacts, for Python: what the tests hold against
the numpy laws and the benchmarks time (each row one contact through the dispatch)."""

from __future__ import annotations

import numpy as np

from billiards.physics.compiled.jit import entry
from billiards.physics.compiled.laws import CushionNumbers
from billiards.physics.compiled.laws.dispatch import ball_law, cushion_law


@entry
def cushion_rows(
    law_id: int,
    velocities: np.ndarray,
    spins: np.ndarray,
    into: np.ndarray,
    masses: np.ndarray,
    constants: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """cushion_law on k balls: velocities (k, 2), spins (k, 3), unit normals into the
    rubber (k, 2), masses (k,), constants (k, 7) a row's CushionNumbers in their order ->
    (velocities', spins', approach speeds)."""
    count = len(velocities)
    new_velocities, new_spins = np.empty((count, 2)), np.empty((count, 3))
    approaches = np.empty(count)
    for row in range(count):
        numbers = CushionNumbers(
            radius=constants[row, 0],
            retention=constants[row, 1],
            cushion_restitution=constants[row, 2],
            cushion_friction=constants[row, 3],
            cushion_height=constants[row, 4],
            sliding_friction=constants[row, 5],
            cushion_restitution_speed=constants[row, 6],
        )
        velocity, spin, approach = cushion_law(
            law_id,
            (velocities[row, 0], velocities[row, 1]),
            (spins[row, 0], spins[row, 1], spins[row, 2]),
            (into[row, 0], into[row, 1]),
            masses[row],
            numbers,
        )
        new_velocities[row, 0], new_velocities[row, 1] = velocity
        new_spins[row, 0], new_spins[row, 1], new_spins[row, 2] = spin
        approaches[row] = approach
    return new_velocities, new_spins, approaches


@entry
def ball_rows(
    law_id: int,
    normals: np.ndarray,
    velocities: np.ndarray,
    spins: np.ndarray,
    masses: np.ndarray,
    restitutions: np.ndarray,
    radii: np.ndarray,
    ball_frictions: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ball_law on k pairs: unit normals from ball 2 to ball 1 (k, 2), velocities
    (k, 2, 2), spins (k, 2, 3), masses (k, 2), restitutions (k,), radii (k,), ball
    frictions (a, b, c) (k, 3) -> (velocities', spins', approach speeds)."""
    count = len(normals)
    new_velocities, new_spins = np.empty((count, 2, 2)), np.empty((count, 2, 3))
    approaches = np.empty(count)
    for row in range(count):
        v1, v2, w1, w2, approach = ball_law(
            law_id,
            (normals[row, 0], normals[row, 1]),
            (
                (velocities[row, 0, 0], velocities[row, 0, 1]),
                (velocities[row, 1, 0], velocities[row, 1, 1]),
                (spins[row, 0, 0], spins[row, 0, 1], spins[row, 0, 2]),
                (spins[row, 1, 0], spins[row, 1, 1], spins[row, 1, 2]),
            ),
            (
                masses[row, 0],
                masses[row, 1],
                restitutions[row],
                radii[row],
                (ball_frictions[row, 0], ball_frictions[row, 1], ball_frictions[row, 2]),
            ),
        )
        new_velocities[row, 0, 0], new_velocities[row, 0, 1] = v1
        new_velocities[row, 1, 0], new_velocities[row, 1, 1] = v2
        new_spins[row, 0, 0], new_spins[row, 0, 1], new_spins[row, 0, 2] = w1
        new_spins[row, 1, 0], new_spins[row, 1, 1], new_spins[row, 1, 2] = w2
        approaches[row] = approach
    return new_velocities, new_spins, approaches
