"""The contact event: what the physics reports of each contact that changed velocities."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Event:
    """A contact that changed velocities, at its exact time."""

    time: float  # s
    kind: str  # "ball", "cushion" (a jaw is a cushion's end) or "pocket"
    balls: tuple[str, ...]  # ids: two for "ball", one for "cushion" and "pocket"
    impact_speed: float  # m/s, the approach speed along the contact normal
    # The pocket's name (billiards.physics.pockets.POCKET_NAMES) for a "pocket" event
    # and for a "cushion" event at one of its jaws; None otherwise.
    pocket: str | None = None


@dataclass(frozen=True)
class Transition:
    """A ball's change of motion state (spin model), at its exact time."""

    time: float  # s
    ball: str  # id
    state: str  # "sliding", "rolling", "spinning" or "rest"
