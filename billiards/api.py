"""billiards as a library: load a scene, vary it, simulate it, look at the result.

The functions here are what `import billiards` offers (`billiards.run`, ...); they
call the same code as the commands (the scene reader, billiards.simulation, the top
view, the film), so a result in a notebook is bit for bit the command's. Bad input
raises `SceneError` (a ValueError) whose message is the one line a command prints:
it names the key, the value and what was expected.

    >>> import billiards
    >>> result = billiards.run("pocket_shot")
    >>> result
    <billiards.Result pocket_shot: 2 balls, exact, 1 ball and 4 cushion contacts, pocketed: 1 (foot-left); at rest at 8.416 s>
    >>> [(event.kind, event.balls) for event in result.events[:2]]
    [('ball', ('cue', '1')), ('pocket', ('1',))]
"""

from __future__ import annotations

import copy
import io
import itertools
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from PIL import Image

from billiards.physics.engine.events import Event
from billiards.physics.engine.result import Pocketing
from billiards.pictures.top_view import (
    DEFAULT_WIDTH,
    draw_top_view,
    sample_path_bends,
    save_picture,
)
from billiards.record.window import film_trajectory
from billiards.scene.reader import (
    METHODS,
    Scene,
    SceneError,
    read_scene_tables,
    scene_from_dict,
    shipped_scene_names,
)
from billiards.scene.reader import load_scene as _load_scene_file
from billiards.scene.render_table import RenderSettings, render_setting_problem
from billiards.simulation import SimulationResult, simulate_batch, simulate_scene

FloatArray = npt.NDArray[np.float64]

# What names a scene: a shipped scene's name ("break"), a TOML file's path, the file's
# tables as a dict (scene_tables' kind), or a Scene already read. None: the seed break.
SceneSource = str | Path | Mapping[str, Any] | Scene | None

# The width of the top view a notebook shows for a Result (px).
NOTEBOOK_WIDTH = 800


def shipped_scenes() -> list[str]:
    """The names of the scenes that ship with the package.

    >>> "break" in billiards.shipped_scenes()
    True
    """
    return shipped_scene_names()


def load_scene(source: SceneSource = None) -> Scene:
    """Read and check a scene: a shipped name, a TOML file's path, a dict of its tables,
    or a Scene (returned as it is); None is the seed break.

        >>> scene = billiards.load_scene("newtons_cradle")
        >>> scene.ball_ids
        ('cue', '1', '2', '3', '4', '5')
        >>> billiards.load_scene({"table": {"cushion_retention": 1.5}})
        Traceback (most recent call last):
        ...
        billiards.scene.tables.SceneError: <dict>: table.cushion_retention = 1.5: expected a number in [0, 1]
    """
    if isinstance(source, Scene):
        return source
    if isinstance(source, Mapping):
        return scene_from_dict(copy.deepcopy(dict(source)), "<dict>")
    return _load_scene_file(source)


def scene_tables(source: str | Path | None = None) -> dict[str, Any]:
    """A scene file's TOML tables as a plain dict (a copy, unchecked): edit it and pass
    it to `load_scene` or `run`, which check it as they would the file.

        >>> tables = billiards.scene_tables("break")
        >>> tables["physics"]["rolling_friction"] = 0.02
        >>> billiards.load_scene(tables).physics.rolling_friction
        0.02
    """
    return read_scene_tables(source)[0]


def vary(source: str | Path | None, values: Mapping[str, float]) -> Scene:
    """A scene with some of its numbers changed, named as `billiards-sweep --vary` names
    them: `physics.rolling_friction`, `rack.gap`, `rack.apex.x`, `ball.cue.position.y`,
    `ball.cue.velocity` (the speed, keeping the direction), `ball.cue.cue.speed` (a
    stroke's), ... The result is checked as a file would be.

        >>> scene = billiards.vary("break", {"ball.cue.velocity": 5.0})
        >>> scene.balls[0].velocity
        (5.0, 0.0)
        >>> billiards.vary("break", {"physics.rolling_fiction": 0.02})
        Traceback (most recent call last):
        ...
        billiards.scene.tables.SceneError: physics.rolling_fiction: unknown key in break (did you mean "physics.rolling_friction"?); expected a path such as physics.rolling_friction, rack.gap or ball.cue.position.y
    """
    # The sweep's own reading of keys: one way to name a scene's number everywhere.
    from billiards.sweep.variations import VaryError, check_key, load_scene_data

    scene_data = load_scene_data(None if source is None else str(source))
    try:
        for key in values:
            check_key(scene_data, key)
    except VaryError as error:
        raise SceneError(str(error).removeprefix("--vary ")) from None
    return scene_data.build(scene_data.with_values(list(values.items())))


@dataclass(frozen=True)
class BallState:
    """One ball's state at one time (world axes, z up; m, m/s, rad/s)."""

    position: tuple[float, float]
    """(x, y), m: the centre, from the corner where the cushion noses x = 0 and y = 0 meet."""
    velocity: tuple[float, float]
    """(vx, vy), m/s."""
    spin: tuple[float, float, float]
    """(wx, wy, wz), rad/s; a rolling ball's is z x v / r."""


@dataclass(frozen=True)
class State:
    """Every ball's state at one time, in `ball_ids` order. A pocketed ball stays where
    it dropped, at rest."""

    time: float
    """s."""
    ball_ids: tuple[str, ...]
    """The balls' ids, in the arrays' order."""
    positions: FloatArray
    """(N, 2), m."""
    velocities: FloatArray
    """(N, 2), m/s."""
    spins: FloatArray
    """(N, 3), rad/s; a rolling ball's is z x v / r."""

    def ball(self, ball_id: str) -> BallState:
        """One ball's state, by id (KeyError naming the ids if there is no such ball)."""
        if ball_id not in self.ball_ids:
            raise KeyError(f"{ball_id!r}: no such ball (the balls: {', '.join(self.ball_ids)})")
        index = self.ball_ids.index(ball_id)
        x, y = (float(value) for value in self.positions[index])
        vx, vy = (float(value) for value in self.velocities[index])
        wx, wy, wz = (float(value) for value in self.spins[index])
        return BallState((x, y), (vx, vy), (wx, wy, wz))


@dataclass(frozen=True)
class Result:
    """A simulated scene: the scene, and what billiards.simulation returned for it
    (`simulation`, the object the commands use), with the questions people ask of it.

    In a notebook a Result shows itself as its top view; `repr` is a one-line summary.
    """

    scene: Scene
    """The scene that ran (its tables read and checked)."""
    simulation: SimulationResult
    """What billiards.simulation.simulate_scene returned: the motion, evaluable at any
    time (`positions_at`, `velocities_at`, `spins_at` over arrays of times)."""

    @property
    def ball_ids(self) -> tuple[str, ...]:
        """The balls' ids, in the order of every per-ball array."""
        return self.simulation.ball_ids

    @property
    def events(self) -> tuple[Event, ...]:
        """Every contact that changed velocities, in time order: `time` (s), `kind`
        ("ball", "cushion" or "pocket"), `balls` (ids), `impact_speed` (m/s), `pocket`."""
        return self.simulation.events

    @property
    def pocketed(self) -> tuple[Pocketing, ...]:
        """The balls that dropped, in order: `ball` (id), `pocket` (name), `time` (s)."""
        return self.simulation.pocketed

    @property
    def rest_time(self) -> float:
        """When the last ball stopped (s), or when the run was stopped."""
        return self.simulation.rest_time

    @property
    def complete(self) -> bool:
        """Whether every ball came to rest by itself (not stopped by max_time or
        max_events: then `stopped_by` says which)."""
        return self.simulation.complete

    @property
    def stopped_by(self) -> str | None:
        """None, or "max_time" or "max_events" when that stopped the run first."""
        return self.simulation.stopped_by

    @property
    def final_positions(self) -> FloatArray:
        """Every ball's centre (N, 2), m, at the rest time; a pocketed ball's is where
        it dropped."""
        return self.simulation.final_positions

    def state_at(self, time: float) -> State:
        """Every ball's position, velocity and spin at `time` (s), exactly (closed form
        for the exact method); after a contact at that very time.

            >>> result = billiards.run("newtons_cradle")
            >>> result.state_at(0.0).ball("cue").velocity
            (2.0, 0.0)
        """
        times = np.array([time], dtype=np.float64)
        return State(
            time=time,
            ball_ids=self.ball_ids,
            positions=self.simulation.positions_at(times)[0],
            velocities=self.simulation.velocities_at(times)[0],
            spins=self.simulation.spins_at(times)[0],
        )

    def summary(self) -> str:
        """One line: the scene, its balls, contacts, drops and rest time."""
        counts = {kind: 0 for kind in ("ball", "cushion")}
        for event in self.events:
            if event.kind in counts:
                counts[event.kind] += 1
        ending = (
            f"at rest at {self.rest_time:.3f} s"
            if self.complete
            else f"stopped by {self.stopped_by} at {self.rest_time:.3f} s"
        )
        dropped = ", ".join(f"{drop.ball} ({drop.pocket})" for drop in self.pocketed)
        return (
            f"{Path(self.scene.source).name}: {len(self.ball_ids)} balls, "
            f"{self.simulation.method}, {counts['ball']} ball and {counts['cushion']} "
            f"cushion contacts, pocketed: {dropped or 'none'}; {ending}"
        )

    def __repr__(self) -> str:
        return f"<billiards.Result {self.summary()}>"

    def _repr_png_(self) -> bytes:
        """The top view, for Jupyter and IPython."""
        buffer = io.BytesIO()
        plot_top_view(self, width=NOTEBOOK_WIDTH).save(buffer, format="PNG")
        return buffer.getvalue()


def run(scene: SceneSource = None, method: str | None = None, dt: float | None = None) -> Result:
    """Simulate a scene to rest. `method` ("exact", "event" or "naive") and `dt` (the
    naive method's step, s) default to the scene's [simulation] table.

        >>> result = billiards.run("break")
        >>> len(result.ball_ids), result.complete
        (16, True)
    """
    _check_method(method)
    loaded = load_scene(scene)
    return Result(loaded, simulate_scene(loaded, method, dt))


def run_many(
    scenes: Iterable[SceneSource], method: str | None = None, dt: float | None = None
) -> Iterator[Result | Exception]:
    """Simulate many scenes together (the batch engine the sweeps use), yielding in
    order each one's Result, bit for bit what `run` gives it alone, or the exception
    that stopped it (a scene the reader refuses, or a run that failed): one failure
    stops no other. Lazy: it holds a few hundred runs at a time, so `scenes` may be a
    generator of any length.

        >>> scenes = [billiards.vary("break", {"ball.cue.velocity": v}) for v in (2.0, 4.0)]
        >>> [round(r.rest_time, 2) for r in billiards.run_many(scenes)]
        [9.36, 8.74]
        >>> [type(r).__name__ for r in billiards.run_many(["bank_shot", "no_such_scene"])]
        ['Result', 'SceneError']
    """
    _check_method(method)
    held, ran = itertools.tee(_loaded_or_error(scene) for scene in scenes)
    results = simulate_batch((item for item in ran if isinstance(item, Scene)), method, dt)
    for item in held:
        if isinstance(item, Exception):
            yield item
        else:
            outcome = next(results)
            yield outcome if isinstance(outcome, Exception) else Result(item, outcome)


def _loaded_or_error(source: SceneSource) -> Scene | Exception:
    try:
        return load_scene(source)
    except SceneError as error:  # this scene's outcome, not the batch's
        return error


def _check_method(method: str | None) -> None:
    if method is not None and method not in METHODS:
        choices = ", ".join(f'"{name}"' for name in METHODS)
        raise SceneError(f"method = {method!r}: expected one of {choices}")


def plot_top_view(
    result: Result, path: str | Path | None = None, width: int = DEFAULT_WIDTH
) -> Image.Image:
    """The shot from above (what `billiards-plot` draws): the table, each ball's path,
    its contacts, start and rest positions. Saved to `path` (.png, .jpg or .webp) when
    one is given; returned as a Pillow image either way."""
    if width < 64:
        raise SceneError(f"width = {width}: expected at least 64 px")
    scene = result.scene
    trajectory = sample_path_bends(result.simulation, (scene.table.length, scene.table.width))
    image = draw_top_view(trajectory, width, Path(scene.source).name)
    if path is not None:
        save_picture(image, path)
    return image


def render_film(
    result: Result,
    path: str | Path,
    *,
    width: int | None = None,
    height: int | None = None,
    fps: float | None = None,
    quality: int | None = None,
    sound: bool | None = None,
    progress: bool = False,
) -> Path:
    """Render the shot to an MP4 film at `path`, as `billiards-render` does: the scene's
    [render] and [[camera]] tables, with these settings on top (each checked as the
    [render] key of that name). Needs OpenGL (Mesa's EGL on a headless machine). The file
    is written whole or not at all. `progress`: a progress bar on stderr."""
    import sys

    from billiards.render.film import render_film as film

    settings = _render_settings(
        result.scene.render, width=width, height=height, fps=fps, quality=quality
    )
    if sound is not None:
        settings = replace(settings, sound=sound)
    trajectory = film_trajectory(result.simulation, settings)
    return film(trajectory, settings, path, progress=sys.stderr if progress else None).path


def render_still(
    result: Result,
    time: float,
    path: str | Path,
    *,
    width: int | None = None,
    height: int | None = None,
) -> Path:
    """Render one frame of the film, at simulation time `time` (s), to a picture
    (.png, .jpg). Needs OpenGL, as `render_film` does."""
    from billiards.render.film import render_still as still
    from billiards.render.film import save_still

    settings = _render_settings(result.scene.render, width=width, height=height)
    start, end = -settings.lead, result.rest_time + settings.tail
    if not start <= time <= end:
        raise SceneError(
            f"time = {time:g}: expected a time in s within the film, {start:g} to {end:g}"
        )
    trajectory = film_trajectory(result.simulation, settings, time)
    return save_still(still(trajectory, settings, time), path)


def _render_settings(base: RenderSettings, **numbers: float | None) -> RenderSettings:
    """The scene's render settings with the given numbers on top, each checked by the
    one check of [render] numbers."""
    changes: dict[str, Any] = {}
    for key, value in numbers.items():
        if value is None:
            continue
        expected = render_setting_problem(key, value)
        if expected is not None:
            raise SceneError(f"{key} = {value:g}: expected {expected}")
        changes[key] = value
    return replace(base, **changes)
