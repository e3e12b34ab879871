"""The contact event: what the physics reports of each contact that changed velocities."""

from __future__ import annotations

from collections.abc import Iterable
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


def events_named(
    contacts: Iterable[tuple[float, str, tuple[int, ...], float, str | None]],
    ball_ids: tuple[str, ...],
) -> tuple[Event, ...]:
    """The logged contacts (time, kind, balls by index, impact speed, pocket) as Events,
    balls named by id, built in bulk: each event's fields straight into its __dict__
    (the frozen dataclass's __init__ was most of a batch's packaging)."""
    named: dict[tuple[int, ...], tuple[str, ...]] = {}
    made: list[Event] = []
    append = made.append
    for time, kind, balls, speed, pocket in contacts:
        ids = named.get(balls)
        if ids is None:
            ids = named[balls] = tuple([ball_ids[ball] for ball in balls])
        event = _new(Event)
        event.__dict__.update(time=time, kind=kind, balls=ids, impact_speed=speed, pocket=pocket)
        append(event)
    return tuple(made)


_new = object.__new__
