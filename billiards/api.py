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
import math
import numbers
import os
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
    MAX_SIDE,
    PICTURE_FORMATS,
    draw_top_view,
    sample_path_bends,
    save_picture,
)
from billiards.record.result_json import MAX_TIMES, result_json
from billiards.record.window import film_trajectory, motion_end
from billiards.scene.bounds import BOUNDS
from billiards.scene.reader import (
    METHODS,
    Scene,
    SceneError,
    check_scene,
    read_scene_tables,
    scene_from_dict,
    scene_tables_of,
    shipped_scene_names,
    with_render,
)
from billiards.scene.reader import load_scene as _load_scene_file
from billiards.scene.render_table import RenderSettings, render_setting_problem
from billiards.scene.tables import shown
from billiards.simulation import SimulationResult, simulate_batch, simulate_scene

FloatArray = npt.NDArray[np.float64]

# What names a scene: a shipped scene's name ("break"), a TOML file's path, the file's
# tables as a dict (scene_tables' kind), or a Scene already read. None: the seed break.
SceneSource = str | os.PathLike[str] | Mapping[str, Any] | Scene | None
SOURCE_HELP = "a shipped scene's name, a TOML file's path, a dict of its tables or a Scene"

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
    or a Scene (made or changed in Python, say with `dataclasses.replace`: checked as
    its file would be); None is the seed break.

        >>> scene = billiards.load_scene("newtons_cradle")
        >>> scene.ball_ids
        ('cue', '1', '2', '3', '4', '5')
        >>> billiards.load_scene({"table": {"cushion_retention": 1.5}})
        Traceback (most recent call last):
        ...
        billiards.scene.tables.SceneError: <dict>: table.cushion_retention = 1.5: expected a number in [0, 1]
    """
    return _loaded(source, "source")


def _loaded(source: object, argument: str) -> Scene:
    """The scene `source` names (see SceneSource), checked; TypeError naming `argument`
    for anything else."""
    if isinstance(source, Scene):
        return check_scene(source)
    if isinstance(source, Mapping):
        return scene_from_dict(copy.deepcopy(dict(source)), "<dict>")
    if source is None or isinstance(source, str | os.PathLike):
        return _load_scene_file(None if source is None else os.fspath(source))
    raise TypeError(f"{argument} = {shown(source)}: expected {SOURCE_HELP}")


def scene_tables(source: SceneSource = None) -> dict[str, Any]:
    """A scene file's TOML tables as a plain dict (a copy, unchecked): edit it and pass
    it to `load_scene` or `run`, which check it as they would the file. A Scene gives
    its tables with every ball written out (its [render] tables left out).

        >>> tables = billiards.scene_tables("break")
        >>> tables["physics"]["rolling_friction"] = 0.02
        >>> billiards.load_scene(tables).physics.rolling_friction
        0.02
    """
    if isinstance(source, Scene):
        return scene_tables_of(check_scene(source))
    if isinstance(source, Mapping):
        return copy.deepcopy(dict(source))
    if source is None or isinstance(source, str | os.PathLike):
        return read_scene_tables(None if source is None else os.fspath(source))[0]
    raise TypeError(f"source = {shown(source)}: expected {SOURCE_HELP}")


def vary(source: SceneSource, values: Mapping[str, float]) -> Scene:
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
    from billiards.sweep.variations import VaryError, check_key, scene_data_of

    if not isinstance(values, Mapping):
        raise TypeError(
            f"values = {shown(values)}: expected a dict of scene keys and numbers, "
            'e.g. {"ball.cue.velocity": 5.0}'
        )
    scene = _loaded(source, "source")
    tables = scene_tables_of(scene) if isinstance(source, Scene) else scene_tables(source)
    scene_data = scene_data_of(tables, scene.source)
    changes: list[tuple[str, float]] = []
    try:
        for key, value in values.items():
            if not isinstance(key, str):
                raise TypeError(f"values: key {shown(key)}: expected a scene key as a string")
            check_key(scene_data, key)
            changes.append((key, _number(f"values[{key!r}]", value, SceneError)))
    except VaryError as error:
        raise SceneError(str(error).removeprefix("--vary ")) from None
    # The tables hold no [render]: the scene keeps its own film settings.
    return with_render(scene_data.build(scene_data.with_values(changes)), scene.render)


def _number(argument: str, value: object, error: type[ValueError] = ValueError) -> float:
    """A finite real number (an int, a float, a numpy scalar), as a float; `error`
    naming `argument` otherwise."""
    if (
        isinstance(value, bool)
        or not isinstance(value, numbers.Real)
        or not math.isfinite(float(value))
    ):
        raise error(f"{argument} = {shown(value)}: expected a finite number")
    return float(value)


@dataclass(frozen=True)
class BallState:
    """One ball's state at one time (world axes, z up; m, m/s, rad/s)."""

    position: tuple[float, float]
    """(x, y), m: the centre, from the corner where the cushion noses x = 0 and y = 0 meet."""
    velocity: tuple[float, float]
    """(vx, vy), m/s."""
    spin: tuple[float, float, float]
    """(wx, wy, wz), rad/s; a rolling ball's is z x v / r."""


@dataclass(frozen=True, eq=False)
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

    def __eq__(self, other: object) -> bool:
        """The same time, balls and numbers, bit for bit."""
        if not isinstance(other, State):
            return NotImplemented
        return (self.time, self.ball_ids) == (other.time, other.ball_ids) and all(
            _same_bits(getattr(self, name), getattr(other, name))
            for name in ("positions", "velocities", "spins")
        )

    def __hash__(self) -> int:
        return hash((self.time, self.ball_ids))


def _same_bits(a: FloatArray, b: FloatArray) -> bool:
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


@dataclass(frozen=True, eq=False)
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
        """Every ball's position, velocity and spin at `time` (s, from 0), exactly
        (closed form for the exact method); after a contact at that very time; after
        the rest time, the state at rest. For many times: `positions(times)`, ...

            >>> result = billiards.run("newtons_cradle")
            >>> result.state_at(0.0).ball("cue").velocity
            (2.0, 0.0)
        """
        if isinstance(time, np.ndarray | list | tuple):
            raise TypeError(
                f"time = {shown(time)}: expected one time in s; for many, "
                "Result.positions(times), .velocities(times) or .spins(times)"
            )
        time = _number("time", time)
        if time < 0:
            raise ValueError(f"time = {time:g}: expected a time in s from 0")
        times = np.array([time], dtype=np.float64)
        return State(
            time=time,
            ball_ids=self.ball_ids,
            positions=self.simulation.positions_at(times)[0],
            velocities=self.simulation.velocities_at(times)[0],
            spins=self.simulation.spins_at(times)[0],
        )

    def positions(self, times: npt.ArrayLike) -> FloatArray:
        """Every ball's centre at each of `times` (s, from 0; a number or an array of
        any shape): an array of shape times' + (N, 2), m, balls in `ball_ids` order.
        Exact, as `state_at`; after the rest time, where each ball rests.

            >>> result = billiards.run("newtons_cradle")
            >>> result.positions([0.0, 0.5, 1.0]).shape
            (3, 6, 2)
        """
        at = _times(times)
        return self.simulation.positions_at(at.reshape(-1)).reshape(*at.shape, -1, 2)

    def heights(self, times: npt.ArrayLike) -> FloatArray:
        """Every ball's centre height above the cloth at each of `times`: shape times' +
        (N,), m; the radius on the cloth, a parabola where a jump flies a ball.

            >>> result = billiards.run("jump_shot")
            >>> bool(result.heights(0.1)[0] > 3 * result.scene.radius)
            True
        """
        at = _times(times)
        return self.simulation.heights_at(at.reshape(-1)).reshape(*at.shape, -1)

    def velocities(self, times: npt.ArrayLike) -> FloatArray:
        """Every ball's velocity at each of `times`: shape times' + (N, 2), m/s."""
        at = _times(times)
        return self.simulation.velocities_at(at.reshape(-1)).reshape(*at.shape, -1, 2)

    def spins(self, times: npt.ArrayLike) -> FloatArray:
        """Every ball's spin at each of `times`: shape times' + (N, 3), rad/s, world
        axes (a rolling ball's is z x v / r)."""
        at = _times(times)
        return self.simulation.spins_at(at.reshape(-1)).reshape(*at.shape, -1, 3)

    def to_dict(self, times: npt.ArrayLike | None = None) -> dict[str, Any]:
        """The result as JSON values, what `billiards-simulate --json` prints (with
        `times`, what `--times` adds: "samples", each ball's position, velocity and
        spin at each time): `json.dumps(result.to_dict())` is that line.

            >>> data = billiards.run("pocket_shot").to_dict(times=[0.5])
            >>> data["pocketed"]
            [{'ball': '1', 'pocket': 'foot-left', 't': 0.494...}]
            >>> sorted(data["samples"][0])
            ['positions', 'spins', 't', 'velocities']
        """
        at = None if times is None else [float(t) for t in _times(times).reshape(-1)]
        return result_json(self.simulation, at, self.scene)

    def __eq__(self, other: object) -> bool:
        """The same scene run the same way to the same bits: events, drops, rest time
        and final positions."""
        if not isinstance(other, Result):
            return NotImplemented
        mine, theirs = self.simulation, other.simulation
        return (
            self.scene == other.scene
            and (mine.method, mine.dt, mine.rest_time, mine.stopped_by)
            == (theirs.method, theirs.dt, theirs.rest_time, theirs.stopped_by)
            and mine.events == theirs.events
            and mine.pocketed == theirs.pocketed
            and _same_bits(mine.final_positions, theirs.final_positions)
        )

    def __hash__(self) -> int:
        return hash((self.simulation.method, self.rest_time, len(self.events)))

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


def _times(times: npt.ArrayLike) -> FloatArray:
    """Times in s as a float array (any shape), each finite and from 0, at most
    MAX_TIMES of them; a one-line TypeError or ValueError naming `times` otherwise."""
    try:
        array = np.asarray(times)
    except (ValueError, TypeError):  # a ragged list, say
        array = np.asarray(None)
    if array.dtype.kind not in "iuf":
        raise TypeError(f"times = {shown(times)}: expected a number or an array of numbers (s)")
    if array.size > MAX_TIMES:
        raise ValueError(
            f"times: {array.size:,} of them: expected at most {MAX_TIMES:,} a call "
            "(split them, or sample more sparsely)"
        )
    array = array.astype(np.float64)
    bad = ~np.isfinite(array) | (array < 0)
    if bad.any():
        first = array[bad].reshape(-1)[0]
        raise ValueError(f"times: {first:g}: expected finite times in s from 0")
    return array


def _result_of(result: object, argument: str) -> Result:
    """A Result as it is, or the Result of running what names a scene."""
    if isinstance(result, Result):
        return result
    if result is None or isinstance(result, str | os.PathLike | Mapping | Scene):
        return run(result)
    raise TypeError(f"{argument} = {shown(result)}: expected a Result, or {SOURCE_HELP}")


def run(scene: SceneSource = None, method: str | None = None, dt: float | None = None) -> Result:
    """Simulate a scene to rest. `method` ("exact", "event" or "naive") and `dt` (the
    naive method's step, s) default to the scene's [simulation] table.

        >>> result = billiards.run("break")
        >>> len(result.ball_ids), result.complete
        (16, True)
    """
    _check_method(method)
    step = _step(dt)
    loaded = _loaded(scene, "scene")
    if step is not None and step > loaded.simulation.max_time:
        raise SceneError(
            f"dt = {step:g}: expected a step no longer than {loaded.source}'s max_time "
            f"({loaded.simulation.max_time:g} s)"
        )
    return Result(loaded, simulate_scene(loaded, method, step))


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
    step = _step(dt)
    if isinstance(scenes, str | os.PathLike | Mapping | Scene) or not isinstance(scenes, Iterable):
        raise TypeError(
            f"scenes = {shown(scenes)}: expected a list (or any iterable) of scenes, "
            f"each {SOURCE_HELP}; for one scene, run()"
        )
    return _run_many(scenes, method, step)


def _run_many(
    scenes: Iterable[SceneSource], method: str | None, dt: float | None
) -> Iterator[Result | Exception]:
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
        return _loaded(source, "scene")
    except (SceneError, TypeError) as error:  # this scene's outcome, not the batch's
        return error


def _check_method(method: str | None) -> None:
    if method is not None and method not in METHODS:
        choices = ", ".join(f'"{name}"' for name in METHODS)
        raise SceneError(f"method = {shown(method)}: expected one of {choices}")


def _step(dt: object) -> float | None:
    """The naive method's step `dt`, within [simulation] dt's bound, or None."""
    if dt is None:
        return None
    bound = BOUNDS["simulation.dt"]
    step = _number("dt", dt, SceneError)
    if not bound.low <= step <= bound.high:
        raise SceneError(f"dt = {step:g}: expected seconds in {bound.range_text()}")
    return step


def plot_top_view(
    result: Result | SceneSource, path: str | Path | None = None, width: int = DEFAULT_WIDTH
) -> Image.Image:
    """The shot from above (what `billiards-plot` draws): the table, each ball's path,
    its contacts, start and rest positions. `result`: a Result, or a scene to run
    first. Saved to `path` (.png, .jpg or .webp) when one is given; returned as a
    Pillow image either way."""
    if isinstance(width, bool) or not isinstance(width, numbers.Integral):
        raise TypeError(f"width = {shown(width)}: expected a whole number of px")
    if not 64 <= width <= MAX_SIDE:
        raise SceneError(f"width = {width}: expected 64 to {MAX_SIDE} px")
    if path is not None:
        _check_picture_path(path)
    result = _result_of(result, "result")
    scene = result.scene
    trajectory = sample_path_bends(result.simulation, (scene.table.length, scene.table.width))
    image = draw_top_view(trajectory, width, Path(scene.source).name)
    if path is not None:
        save_picture(image, path)
    return image


def _check_picture_path(path: object) -> None:
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"path = {shown(path)}: expected a file name (str or Path)")
    if Path(path).suffix.lower() not in PICTURE_FORMATS:
        endings = ", ".join(PICTURE_FORMATS)
        raise ValueError(f"path = {shown(path)}: expected a picture file named {endings}")


def render_film(
    result: Result | SceneSource,
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

    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"path = {shown(path)}: expected a file name (str or Path)")
    if Path(path).suffix.lower() != ".mp4":
        raise ValueError(f"path = {shown(path)}: expected a film file named .mp4")
    if sound is not None and not isinstance(sound, bool):
        raise TypeError(f"sound = {shown(sound)}: expected True, False or None")
    result = _result_of(result, "result")
    settings = _render_settings(
        result.scene.render, width=width, height=height, fps=fps, quality=quality
    )
    if sound is not None:
        settings = replace(settings, sound=sound)
    trajectory = film_trajectory(result.simulation, settings)
    return film(trajectory, settings, path, progress=sys.stderr if progress else None).path


def render_still(
    result: Result | SceneSource,
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

    _check_picture_path(path)
    time = _number("time", time)
    result = _result_of(result, "result")
    settings = _render_settings(result.scene.render, width=width, height=height)
    # The film's span (render --frame's): to the tail after the last ball's centre stops.
    start, end = -settings.lead, motion_end(result.simulation) + settings.tail
    if not start <= time <= end:
        raise SceneError(
            f"time = {time:g}: expected a time in s within the film, {start:g} to {end:g}"
        )
    trajectory = film_trajectory(result.simulation, settings, time)
    return save_still(still(trajectory, settings, time), path)


def _render_settings(base: RenderSettings, **given: float | None) -> RenderSettings:
    """The scene's render settings with the given numbers on top, each checked by the
    one check of [render] numbers."""
    changes: dict[str, Any] = {}
    for key, value in given.items():
        if value is None:
            continue
        expected = render_setting_problem(key, _number(key, value, SceneError))
        if expected is not None:
            raise SceneError(f"{key} = {shown(value)}: expected {expected}")
        changes[key] = value
    return replace(base, **changes)
