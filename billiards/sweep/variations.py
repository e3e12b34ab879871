"""`--vary KEY=SPEC`: which scene numbers a sweep changes, and how each run draws them.

A key is a scene number's path, as in the file (`physics.rolling_friction`,
`rack.gap`, `rack.apex.x`) or by ball (`ball.cue.position.y`, `ball.5.mass`,
`ball.cue.velocity` = the speed, keeping the direction; a struck ball's stroke:
`ball.cue.cue.speed`, `.direction`, `.elevation`, `.tip.side`, `.tip.height`, `.mass`,
`.end_mass`). The scene is kept as its
TOML tables (a `SceneData`) and each run's values are written into a copy, which the
scene reader then validates: a value that makes a bad scene fails that run alone.

Specs: `a:b` uniform in [a, b), `m~s` normal, and grids `a:b:n` (n points from a to b)
or `a,b,c` (a single number fixes the key). Run i's random draws come from a generator
seeded by (seed, i) alone, so no run depends on how runs are batched or spread.
"""

from __future__ import annotations

import copy
import dataclasses
import difflib
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from billiards.rules import seed
from billiards.scene.bounds import BOUNDS, DOCS
from billiards.scene.reader import (
    RACK_ORDER,
    Physics,
    Scene,
    Simulation,
    Table,
    rack_positions,
    read_scene_tables,
    scene_from_dict,
    seed_break_tables,
)
from billiards.scene.tables import keys_read
from billiards.sweep import draws


class VaryError(ValueError):
    """A --vary or --nudge a person must fix; str() is one line."""


# --- the scene as TOML tables ------------------------------------------------------------


@dataclass(frozen=True)
class SceneData:
    """A scene file's tables, with the seed's implicit cue ball and rack written out
    (so `ball.cue` and `rack.gap` exist to vary), and the scene they make."""

    data: dict[str, Any]
    scene: Scene

    @property
    def source(self) -> str:
        return self.scene.source

    def with_values(self, values: Sequence[tuple[str, float]]) -> dict[str, Any]:
        """A copy of the tables with each key set to its value (in order)."""
        data = copy.deepcopy(self.data)
        if any(_rack_ball(data, key) for key, _ in values):
            # Rack balls have no tables of their own: after any rack.* values, the
            # rack becomes 15 explicit balls at the same places, in the same order.
            for key, value in values:
                if key.startswith("rack."):
                    _set(data, key, value)
            _explode_rack(data)
            values = [(key, value) for key, value in values if not key.startswith("rack.")]
        for key, value in values:
            _set(data, key, value)
        return data

    def build(self, data: dict[str, Any]) -> Scene:
        return scene_from_dict(data, self.source)


def load_scene_data(name_or_path: str | None) -> SceneData:
    """Read a scene file (or a shipped scene by name) as tables; SceneError if bad."""
    return scene_data_of(*read_scene_tables(name_or_path))


def scene_data_of(data: dict[str, Any], source: str) -> SceneData:
    """A scene's tables (a file's, or a dict of them) as SceneData; SceneError if bad.
    The tables are the caller's to give away: they are kept and changed."""
    scene = scene_from_dict(copy.deepcopy(data), source)  # validates the file as it is
    if "ball" not in data and "rack" not in data:
        data.update(seed_break_tables(scene.table))  # what the reader did, written out
    # A sweep draws no film: its runs need no [render] or [[camera]] tables (checked
    # just above), nor a [render] table_mesh to be found wherever a run is built.
    for key in ("render", "camera"):
        data.pop(key, None)
    return SceneData(data, scene)


def _rack_ball(data: dict[str, Any], key: str) -> bool:
    parts = key.split(".")
    return parts[0] == "ball" and "rack" in data and _ball_table(data, parts[1]) is None


def _explode_rack(data: dict[str, Any]) -> None:
    rack = data.pop("rack")
    apex = rack.get("apex", _foot_spot(data))
    radius = data.get("balls", {}).get("radius", Scene.radius)
    positions = rack_positions(apex, radius, rack.get("gap", seed.RACK_GAP))
    data.setdefault("ball", []).extend(
        {"id": ball_id, "position": list(position)}
        for ball_id, position in zip(RACK_ORDER, positions, strict=True)
    )


def _ball_table(data: dict[str, Any], ball_id: str) -> dict[str, Any] | None:
    for table in data.get("ball", []):
        if isinstance(table, dict) and table.get("id") == ball_id:
            return table
    return None


# Where each ball key lives in a [[ball]] table: (array key, index), or the speed.
_BALL_KEYS: dict[str, tuple[str, int | None]] = {
    "position.x": ("position", 0),
    "position.y": ("position", 1),
    "velocity.x": ("velocity", 0),
    "velocity.y": ("velocity", 1),
    "velocity": ("velocity", None),
    "mass": ("mass", None),
}
_SPIN_KEYS: dict[str, tuple[str, int | None]] = {
    "spin.x": ("spin", 0),
    "spin.y": ("spin", 1),
    "spin.z": ("spin", 2),
    "tip.side": ("tip", 0),
    "tip.height": ("tip", 1),
}
# A stroke's keys (`cue = {...}`, the spin model): ball.<id>.cue.speed and the rest.
_CUE_KEYS: dict[str, tuple[str, int | None]] = {
    "cue.speed": ("speed", None),
    "cue.direction": ("direction", None),
    "cue.elevation": ("elevation", None),
    "cue.tip.side": ("tip", 0),
    "cue.tip.height": ("tip", 1),
    "cue.mass": ("mass", None),
    "cue.end_mass": ("end_mass", None),
}
_VECTOR_DEFAULTS = {
    "position": [0.0, 0.0],
    "velocity": [0.0, 0.0],
    "spin": [0.0, 0.0, 0.0],
    "tip": [0.0, 0.0],
}


def _set(data: dict[str, Any], key: str, value: float) -> None:
    section, _, rest = key.partition(".")
    if section == "ball":
        ball_id, _, field = rest.partition(".")
        table = _ball_table(data, ball_id)
        assert table is not None  # keys are checked before any run
        if field in _CUE_KEYS:
            _set_stroke(table["cue"], field, value)
            return
        name, index = {**_BALL_KEYS, **_SPIN_KEYS}[field]
        if name == "mass":
            table["mass"] = value
        elif field == "velocity":  # the speed: the same direction, scaled
            vx, vy = table.get("velocity", [0.0, 0.0])
            speed = math.sqrt(vx * vx + vy * vy)  # not hypot: libm's bits vary by machine
            table["velocity"] = [vx / speed * value, vy / speed * value]
        else:
            vector = list(table.get(name) or _VECTOR_DEFAULTS[name])
            vector[index or 0] = value
            table[name] = vector
    elif section == "rack" and rest.startswith("apex."):
        rack = data["rack"]
        apex = list(rack.get("apex", _foot_spot(data)))
        apex["xy".index(rest[-1])] = value
        rack["apex"] = apex
    else:
        # max_events is read as a whole number; every other key as a float.
        number: float = round(value) if key == "simulation.max_events" else value
        data.setdefault(section, {})[rest] = number


def _set_stroke(cue: dict[str, Any], field: str, value: float) -> None:
    name, index = _CUE_KEYS[field]
    if index is None:
        cue[name] = value
    else:
        tip = list(cue.get("tip") or _VECTOR_DEFAULTS["tip"])
        tip[index] = value
        cue["tip"] = tip


def _foot_spot(data: dict[str, Any]) -> list[float]:
    table = data.get("table", {})
    return list(
        seed.foot_spot((table.get("length", Table.length), table.get("width", Table.width)))
    )


# --- which keys exist -------------------------------------------------------------------


def scene_keys(scene_data: SceneData) -> tuple[dict[str, str], dict[str, str]]:
    """The scene's numeric keys, and its other (non-numeric) keys, each with what it is."""
    numeric: dict[str, str] = {}
    other: dict[str, str] = {}
    for section, kind in (("table", Table), ("physics", Physics), ("simulation", Simulation)):
        for item in dataclasses.fields(kind):
            key = f"{section}.{item.name}"
            if item.type in ("float", "int"):
                numeric[key] = str(item.type)
            else:
                other[key] = "string"
    numeric["balls.radius"] = numeric["balls.mass"] = "float"
    if "rack" in scene_data.data:
        for key in ("rack.gap", "rack.apex.x", "rack.apex.y"):
            numeric[key] = "float"
    spin_model = scene_data.scene.physics.model == "spin"
    explicit = {
        table.get("id")
        for table in scene_data.data.get("ball", [])
        if isinstance(table, dict) and table.get("id")
    }
    for ball in scene_data.scene.balls:
        if ball.stroke is not None:  # struck: the stroke's keys, not a velocity or spin
            for field in (*_CUE_KEYS, "position.x", "position.y", "mass"):
                numeric[f"ball.{ball.id}.{field}"] = "float"
            other[f"ball.{ball.id}.id"] = "string"
            continue
        for field in _BALL_KEYS:
            numeric[f"ball.{ball.id}.{field}"] = "float"
        if spin_model and ball.id in explicit:
            for field in _SPIN_KEYS:
                if (ball.spin is None) == field.startswith("tip."):
                    numeric[f"ball.{ball.id}.{field}"] = "float"
        other[f"ball.{ball.id}.id"] = "string"
    return numeric, other


def check_key(scene_data: SceneData, key: str) -> None:
    """VaryError unless `key` is a numeric key of the scene that can be varied."""
    numeric, other = scene_keys(scene_data)
    if key in other:
        raise VaryError(
            f"--vary {key}: not a numeric key (it holds a {other[key]}); expected a key "
            "that holds a number"
        )
    if key not in numeric:
        near = difflib.get_close_matches(key, sorted(numeric), n=1, cutoff=0.6)
        hint = f' (did you mean "{near[0]}"?)' if near else ""
        raise VaryError(
            f"--vary {key}: unknown key in {scene_data.source}{hint}; expected a path such as "
            "physics.rolling_friction, rack.gap or ball.cue.position.y"
        )
    parts = key.split(".")
    if parts[0] == "ball" and parts[-1] == "velocity":
        ball = next(ball for ball in scene_data.scene.balls if ball.id == parts[1])
        if ball.velocity == (0.0, 0.0):
            raise VaryError(
                f"--vary {key}: ball {parts[1]!r} is at rest, so its speed has no direction; "
                f"expected ball.{parts[1]}.velocity.x or .y"
            )


# --- specs -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Variation:
    """One --vary: a key, and either a distribution (uniform, normal) or grid points."""

    key: str
    spec: str
    kind: str  # "uniform" | "normal" | "grid"
    a: float = 0.0  # uniform: low; normal: mean
    b: float = 0.0  # uniform: high; normal: standard deviation
    points: tuple[float, ...] = ()  # grid

    def draw(self, rng: np.random.Generator) -> float:
        if self.kind == "uniform":
            return draws.uniform(rng, self.a, self.b)
        return draws.normal(rng, self.a, self.b)


SPEC_HELP = "a:b (uniform), m~s (normal), a:b:n or a,b,c (a grid)"

# The most runs one sweep makes: hard_break runs at 130-170 a second on 2 cores, so a
# million is 2-3 hours there and a runs.csv of about 0.6 GB; more is several sweeps
# (each its own --seed). Memory does not grow with the runs (billiards.sweep.records).
MAX_RUNS = 1_000_000


def parse_vary(text: str) -> Variation:
    """`KEY=SPEC` -> a Variation (the key is checked against a scene later)."""
    key, equals, spec = text.partition("=")
    key, spec = key.strip(), spec.strip()
    if not equals or not key:
        raise VaryError(
            f"--vary {text}: expected KEY=SPEC, e.g. physics.rolling_friction=0.01:0.02"
        )

    def fail(why: str) -> VaryError:
        return VaryError(f"--vary {key}={spec}: {why}; expected {SPEC_HELP}")

    def numbers(parts: Sequence[str]) -> list[float]:
        try:
            values = [float(part) for part in parts]
        except ValueError:
            raise fail("not a number") from None
        if not all(math.isfinite(value) for value in values):
            raise fail("not a finite number")
        return values

    if "~" in spec:
        mean, deviation = numbers(spec.split("~"))
        if deviation < 0:
            raise fail("a negative standard deviation")
        return Variation(key, spec, "normal", a=mean, b=deviation)
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) == 2:
            low, high = numbers(parts)
            if not low < high:
                raise fail("the range is empty (a:b needs a < b)")
            return Variation(key, spec, "uniform", a=low, b=high)
        if len(parts) == 3:
            low, high = numbers(parts[:2])
            count = parts[2].strip()
            if not count.isdigit() or int(count) < 2:
                raise fail(f"{count!r} grid points (a:b:n needs a whole n >= 2)")
            if int(count) > MAX_RUNS:
                raise fail(f"{int(count):,} grid points (a sweep runs at most {MAX_RUNS:,})")
            grid = np.linspace(low, high, int(count))
            return Variation(key, spec, "grid", points=tuple(float(v) for v in grid))
        raise fail("too many colons")
    return Variation(key, spec, "grid", points=tuple(numbers(spec.split(","))))


@dataclass(frozen=True)
class Variations:
    """Every --vary of a sweep, and run i's values: grid point i mod (grid size), the
    first grid key changing slowest, and fresh draws from (seed, i) for the rest."""

    items: tuple[Variation, ...]
    seed: int

    @property
    def grid_size(self) -> int:
        return math.prod(len(item.points) for item in self.items if item.kind == "grid")

    def values(self, run: int) -> list[tuple[str, float]]:
        grid = [item.points for item in self.items if item.kind == "grid"]
        point = iter(_grid_point(grid, run % self.grid_size) if grid else ())
        rng = np.random.default_rng([self.seed, run])
        return [
            (item.key, next(point) if item.kind == "grid" else item.draw(rng))
            for item in self.items
        ]


def _grid_point(grid: Sequence[Sequence[float]], index: int) -> tuple[float, ...]:
    # The product's index-th point without listing the product (it may be large).
    point = []
    for axis in reversed(grid):
        index, place = divmod(index, len(axis))
        point.append(axis[place])
    return tuple(reversed(point))


def check_variations(scene_data: SceneData, items: Sequence[Variation]) -> None:
    """VaryError for an unknown, non-numeric or repeated key, or a range that reaches
    past the key's bound, checked before any run."""
    seen: set[str] = set()
    for item in items:
        check_key(scene_data, item.key)
        if item.key in seen:
            raise VaryError(f"--vary {item.key}: given twice; expected each key once")
        seen.add(item.key)
    check_ranges(scene_data, items)


# How far a normal spec (m~s) reaches for its range to be checked: m - 4 s to m + 4 s
# holds all but 6 in 100,000 draws.
NORMAL_REACH = 4.0


@dataclass(frozen=True)
class KeyRange:
    """The values a scene key accepts: [low, high] (low excluded if low_open, high if
    high_open), and how a message says it."""

    low: float
    high: float
    expected: str
    low_open: bool = False
    high_open: bool = False

    def holds(self, value: float) -> bool:
        above = value > self.low if self.low_open else value >= self.low
        below = value < self.high if self.high_open else value <= self.high
        return above and below


def check_ranges(scene_data: SceneData, items: Sequence[Variation]) -> None:
    """VaryError for a spec whose values reach past its key's bound (the reader's, for
    the scene as it is): a uniform's ends, a grid's least and greatest points, a
    normal's mean +- NORMAL_REACH deviations. A run whose values are in bounds may
    still fail (two balls overlap, say): that run alone."""
    ranges = key_ranges(scene_data)
    resized = any(item.key.startswith(("table.", "balls.radius")) for item in items)
    for item in items:
        bound = ranges.get(_range_key(item.key))
        if bound is None or (resized and (".position." in item.key or ".apex." in item.key)):
            continue  # a position's bound moves with the table's size and the radius
        if item.kind == "uniform":
            low, high, what = item.a, item.b, "reaches"
        elif item.kind == "normal":
            reach = NORMAL_REACH * item.b
            low, high = item.a - reach, item.a + reach
            what = f"reaches (mean +- {NORMAL_REACH:g} deviations)"
        else:
            low, high, what = min(item.points), max(item.points), "reaches"
        outside = [value for value in (low, high) if not bound.holds(value)]
        if outside:
            raise VaryError(
                f"--vary {item.key}={item.spec}: {what} {outside[0]:g}, outside the key's "
                f"bound; expected {bound.expected}"
            )


def _range_key(key: str) -> str:
    """A --vary key as key_ranges names it: a ball's keys without its id."""
    parts = key.split(".")
    if parts[0] == "ball":
        return ".".join(["ball[]", *parts[2:]])
    return key


def key_ranges(scene_data: SceneData) -> dict[str, KeyRange]:
    """Every numeric key's range in this scene: the reader's own, recorded as it reads
    the scene's tables, and the ones it checks otherwise (a ball's place on the table,
    its speed, a tip on the ball)."""
    with keys_read() as found:
        scene = scene_from_dict(copy.deepcopy(scene_data.data), scene_data.source)
    ranges: dict[str, KeyRange] = {}
    for read in found:
        if read.low is not None or read.high is not None:
            ranges[read.path] = KeyRange(
                -math.inf if read.low is None else read.low,
                math.inf if read.high is None else read.high,
                read.expected,
                low_open=read.low_open,
            )
    radius, length, width = scene.radius, scene.table.length, scene.table.width
    for axis, size in (("x", length), ("y", width)):
        expected = f"a centre inside the cushions, {axis} in [{radius:g}, {size - radius:g}] m"
        inside = KeyRange(radius, size - radius, expected)
        ranges[f"ball[].position.{axis}"] = ranges[f"rack.apex.{axis}"] = inside
    speed = BOUNDS["ball.velocity"]
    ranges["ball[].velocity"] = KeyRange(0.0, speed.high, speed.expected())
    component = f"a number in [{-speed.high:g}, {speed.high:g}] m/s (see {DOCS})"
    for axis in "xy":
        ranges[f"ball[].velocity.{axis}"] = KeyRange(-speed.high, speed.high, component)
    surface = BOUNDS["ball.spin"].high / radius
    for axis in "xyz":
        ranges[f"ball[].spin.{axis}"] = KeyRange(
            -surface, surface, f"a number in [{-surface:g}, {surface:g}] rad/s (see {DOCS})"
        )
    for name in ("tip.side", "tip.height", "cue.tip.side", "cue.tip.height"):
        ranges[f"ball[].{name}"] = KeyRange(-1.0, 1.0, "a number in [-1, 1] (a point on the ball)")
    ranges["ball[].cue.elevation"] = KeyRange(
        0.0,
        90.0,
        "degrees in [0, 90) (0: a level cue; 90 and more drive the ball through the bed)",
        high_open=True,
    )
    return ranges
