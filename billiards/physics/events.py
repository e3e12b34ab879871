"""The contact event: what the physics reports of each contact that changed velocities."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Event:
    """A contact that changed velocities, at its exact time."""

    time: float  # s
    kind: str  # "ball" or "cushion"
    balls: tuple[str, ...]  # ids: two for "ball", one for "cushion"
    impact_speed: float  # m/s, the approach speed along the contact normal


@dataclass(frozen=True)
class Transition:
    """A ball's change of motion state (spin model), at its exact time."""

    time: float  # s
    ball: str  # id
    state: str  # "sliding", "rolling", "spinning" or "rest"
