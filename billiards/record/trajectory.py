"""A break recorded at a frame rate: the only thing physics and rendering share; its
file format (.npz) and reading it back between samples.

Positions are ball centres in metres (z = radius: balls stay on the cloth).
Orientations are unit quaternions (billiards.record.quaternions: x, y, z, w, body to world).
At t = 0 every ball has the identity orientation. `ball_state` reads the balls back
at any time between the recorded samples.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

from billiards.physics.engine.events import Event
from billiards.record import quaternions
from billiards.record.pocket_shapes import PocketShapes
from billiards.scene.render_table import (
    RenderSettings,
    parse_render_settings,
    settings_from_record,
    settings_record,
)
from billiards.scene.tables import TableReader

if TYPE_CHECKING:  # the renderer loads the trajectory, never the physics' geometry
    from billiards.physics.pockets import PocketTable

FloatArray = npt.NDArray[np.float64]


class RecordedMotion(Protocol):
    """What a simulation result offers for recording (billiards.physics.SimulationResult)."""

    @property
    def ball_ids(self) -> tuple[str, ...]: ...
    @property
    def radius(self) -> float: ...
    @property
    def table_size(self) -> tuple[float, float]: ...
    @property
    def rest_time(self) -> float: ...
    @property
    def events(self) -> tuple[Event, ...]: ...
    @property
    def model(self) -> str:
        """The motion model that ran: "rolling" or "spin" (physics.motion_law.MOTION_LAWS)."""
        ...

    @property
    def pockets(self) -> PocketTable | None:
        """The table's pockets (None: a table without pockets, drawn without holes)."""
        ...

    @property
    def curved_paths(self) -> bool:
        """Whether paths curve between the path breaks (a drawing needs samples there)."""
        ...

    def positions_at(self, times: FloatArray) -> FloatArray:
        """Ball centres (T x N x 2) at the given times, evaluated exactly."""
        ...

    def path_breaks(self) -> FloatArray:
        """Sorted times at which any ball's path may bend (its contacts, or the steps)."""
        ...

    def spins_at(self, times: FloatArray) -> FloatArray:
        """Angular velocities (T x N x 3), world axes; a rolling ball's is z x v / r."""
        ...


@dataclass(frozen=True)
class CueStrike:
    """The stroke that sets the film going, for drawing the cue: at t = 0 its tip meets
    `ball` and the ball leaves. From the scene's `cue = {...}` (billiards.scene.stroke's
    line, elevation and tip), or, for a cue ball given a velocity, a level cue along
    that velocity (its `tip`, else the centre) at the speed that gives it."""

    ball: str
    direction: float  # degrees from +x, counterclockwise: the cue's line on the cloth
    elevation: float  # degrees above the cloth
    tip: tuple[float, float]  # (side, height) / r where the cue's axis meets the ball
    speed: float  # m/s, the cue's at the strike


def first_contact_time(events: Sequence[Event]) -> float | None:
    """s, simulation time of the first ball-ball contact (None if balls never touch)."""
    return next((e.time for e in events if e.kind == "ball"), None)


def last_motion(trajectory: Trajectory) -> float:
    """s, the last recorded time a ball's centre still moves (a ball that only spins in
    place does not count): the film's last visible motion, where its ending is timed."""
    positions = trajectory.positions
    if len(positions) < 2:
        return float(trajectory.times[0]) if len(positions) else 0.0
    moved = np.any(np.abs(np.diff(positions, axis=0)) > 1e-9, axis=(1, 2))
    if not moved.any():
        return float(trajectory.times[0])
    return float(trajectory.times[int(np.flatnonzero(moved)[-1]) + 1])


@dataclass(frozen=True)
class Trajectory:
    ball_ids: tuple[str, ...]
    radius: float  # m
    table_size: tuple[float, float]  # (length, width) in m
    times: FloatArray  # (F,) s, increasing; evenly spaced at fps when recorded for a film
    positions: FloatArray  # (F, N, 3) m
    orientations: FloatArray  # (F, N, 4) quaternions (x, y, z, w)
    events: tuple[Event, ...]
    rest_time: float  # s, when the last ball stopped (or max_time)
    # The scene it came from, so that a saved trajectory renders like that scene: its
    # file name and its render settings, as the scene reader read and checked them
    # (None: not saved from a scene).
    scene_source: str = ""
    render_settings: RenderSettings | None = None
    # The pockets the physics had (None: a table without pockets, drawn without holes).
    pockets: PocketShapes | None = None
    # The cue's stroke at t = 0 (None: no ball is struck; the film draws no cue).
    strike: CueStrike | None = None

    @property
    def fps(self) -> float:
        """Samples per second, from the first two (meaningful for evenly spaced times)."""
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
            event_pockets=np.array([e.pocket or "" for e in self.events], dtype=str),
            rest_time=self.rest_time,
            scene=np.array(json.dumps(self._scene_record())),
            **_pocket_arrays(self.pockets),
            **_strike_arrays(self.strike),
        )

    def _scene_record(self) -> dict[str, Any]:
        settings = self.render_settings
        record = None if settings is None else settings_record(settings)
        return {"source": self.scene_source, "render_settings": record}

    @classmethod
    def load(cls, path: str | Path) -> Trajectory:
        """A saved trajectory; ValueError (or KeyError) if the file is not one, and
        SceneError for an older file whose [render] tables are bad."""
        with np.load(path) as data:
            count = len(data["event_times"])
            pockets = data["event_pockets"] if "event_pockets" in data else [""] * count
            events = tuple(
                Event(
                    time=float(t),
                    kind=str(kind),
                    balls=tuple(str(balls).split(",")),
                    impact_speed=float(speed),
                    pocket=pocket or None,
                )
                for t, kind, balls, speed, pocket in zip(
                    data["event_times"],
                    data["event_kinds"],
                    data["event_balls"],
                    data["event_speeds"],
                    (str(name) for name in pockets),
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
                pockets=_pockets_of(data),
                strike=_strike_of(data),
                **_scene_of(data),
            )


def _pocket_arrays(pockets: PocketShapes | None) -> dict[str, Any]:
    if pockets is None:
        return {}
    return {
        "pocket_names": np.array(pockets.names),
        "pocket_holes": pockets.holes,
        "pocket_mouths": pockets.mouths,
        "pocket_jaws": pockets.jaws,
        "pocket_jaw_radius": pockets.jaw_radius,
    }


def _pockets_of(data: Any) -> PocketShapes | None:
    if "pocket_names" not in data:
        return None
    return PocketShapes(
        names=tuple(str(name) for name in data["pocket_names"]),
        holes=data["pocket_holes"],
        mouths=data["pocket_mouths"],
        jaws=data["pocket_jaws"],
        jaw_radius=float(data["pocket_jaw_radius"]),
    )


def _strike_arrays(strike: CueStrike | None) -> dict[str, Any]:
    if strike is None:
        return {}
    numbers = (strike.direction, strike.elevation, *strike.tip, strike.speed)
    return {"strike_ball": np.array(strike.ball), "strike": np.array(numbers, dtype=np.float64)}


def _strike_of(data: Any) -> CueStrike | None:
    if "strike_ball" not in data:  # no stroke, or saved before strikes were kept
        return None
    direction, elevation, side, height, speed = (float(v) for v in data["strike"])
    return CueStrike(
        ball=str(data["strike_ball"]),
        direction=direction,
        elevation=elevation,
        tip=(side, height),
        speed=speed,
    )


def _scene_of(data: Any) -> dict[str, Any]:
    """The scene fields of a saved trajectory (none in files from before they existed)."""
    if "scene" not in data:
        return {}
    scene = json.loads(str(data["scene"]))
    source = str(scene["source"])
    if "render_settings" in scene:
        record = scene["render_settings"]
        settings = None if record is None else settings_from_record(record)
    else:
        # Saved before the settings were typed: the scene's [render] and [[camera]]
        # tables as its file had them, read as the scene reader reads them.
        tables = TableReader(scene["render"], "", source)
        settings = parse_render_settings(tables)
        tables.finish()
    return {"scene_source": source, "render_settings": settings}


def ball_state(trajectory: Trajectory, time: float) -> tuple[FloatArray, FloatArray]:
    """Ball centres (N x 3) and orientations (N x 4) at a simulation time.

    Exact at the recorded samples; between them, centres are interpolated linearly and
    orientations by normalised linear interpolation (both far below a pixel at film
    frame rates). Clamped to the recorded span.
    """
    times = trajectory.times
    if time <= times[0]:
        return trajectory.positions[0], trajectory.orientations[0]
    if time >= times[-1]:
        return trajectory.positions[-1], trajectory.orientations[-1]
    index = int(np.searchsorted(times, time, side="right")) - 1
    t0, t1 = float(times[index]), float(times[index + 1])
    if time == t0:
        return trajectory.positions[index], trajectory.orientations[index]
    weight = (time - t0) / (t1 - t0)
    p0, p1 = trajectory.positions[index], trajectory.positions[index + 1]
    q0, q1 = trajectory.orientations[index], trajectory.orientations[index + 1]
    return p0 * (1 - weight) + p1 * weight, quaternions.blend(q0, q1, weight)
