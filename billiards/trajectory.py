"""A break recorded at a frame rate: the only thing physics and rendering share.

Positions are ball centres in metres (z = radius: balls stay on the cloth).
Orientations are unit quaternions (x, y, z, w), the order pyrr uses; a ball's
quaternion q turns body-frame vectors into world-frame ones, v_world = q v_body q*.
At t = 0 every ball has the identity orientation.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

EVENT_KINDS = ("ball", "cushion")


@dataclass(frozen=True)
class Event:
    """A contact that changed velocities, at its exact time."""

    time: float  # s
    kind: str  # "ball" or "cushion"
    balls: tuple[str, ...]  # ids: two for "ball", one for "cushion"
    impact_speed: float  # m/s, the approach speed along the contact normal


class RecordedMotion(Protocol):
    """What a simulation result offers for recording (billiards.physics.result)."""

    ball_ids: tuple[str, ...]
    radius: float
    rest_time: float
    events: tuple[Event, ...]

    def positions_at(self, times: FloatArray) -> FloatArray:
        """Ball centres (T x N x 2) at the given times, evaluated exactly."""
        ...

    def path_breaks(self) -> FloatArray:
        """Sorted times at which any ball's path may bend (its contacts, or the steps)."""
        ...


@dataclass(frozen=True)
class Trajectory:
    ball_ids: tuple[str, ...]
    radius: float  # m
    table_size: tuple[float, float]  # (length, width) in m
    times: FloatArray  # (F,) s, evenly spaced at fps
    positions: FloatArray  # (F, N, 3) m
    orientations: FloatArray  # (F, N, 4) quaternions (x, y, z, w)
    events: tuple[Event, ...]
    rest_time: float  # s, when the last ball stopped (or max_time)

    @property
    def fps(self) -> float:
        if len(self.times) < 2:
            return 0.0
        return 1.0 / float(self.times[1] - self.times[0])

    def save(self, path: str | Path) -> None:
        np.savez_compressed(
            path,
            ball_ids=np.array(self.ball_ids),
            radius=self.radius,
            table_size=np.array(self.table_size),
            times=self.times,
            positions=self.positions,
            orientations=self.orientations,
            event_times=np.array([e.time for e in self.events], dtype=np.float64),
            event_kinds=np.array([e.kind for e in self.events], dtype=str),
            event_balls=np.array([",".join(e.balls) for e in self.events], dtype=str),
            event_speeds=np.array([e.impact_speed for e in self.events], dtype=np.float64),
            rest_time=self.rest_time,
        )

    @classmethod
    def load(cls, path: str | Path) -> Trajectory:
        with np.load(path) as data:
            events = tuple(
                Event(float(t), str(kind), tuple(str(balls).split(",")), float(speed))
                for t, kind, balls, speed in zip(
                    data["event_times"],
                    data["event_kinds"],
                    data["event_balls"],
                    data["event_speeds"],
                    strict=True,
                )
            )
            size = data["table_size"]
            return cls(
                ball_ids=tuple(str(i) for i in data["ball_ids"]),
                radius=float(data["radius"]),
                table_size=(float(size[0]), float(size[1])),
                times=data["times"],
                positions=data["positions"],
                orientations=data["orientations"],
                events=events,
                rest_time=float(data["rest_time"]),
            )
