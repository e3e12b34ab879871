"""Scene files: TOML -> frozen, validated dataclasses.

Every key is optional; the defaults are the seed report's break (the README's model section). A bad
file raises SceneError with one line naming the key, the value and what was
expected.

The bottom floor: imports nothing of the physics or the renderer. The [render] table
and [[camera]] shots are read here too, into `Scene.render` (their types and checks are
billiards.scene.render_table'), so the whole file is read in one place.
"""

from __future__ import annotations

import importlib.resources
import math
import tomllib
import weakref
from collections.abc import Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from billiards.rules import seed
from billiards.rules.pocket_rule import corner_pocket_of, pocket_problem
from billiards.scene.bounds import bounded, length_within
from billiards.scene.render_table import RenderSettings, parse_render_settings
from billiards.scene.stroke import JUMP_LIMIT, Stroke, jump_height, strike
from billiards.scene.tables import SceneError, TableReader, shown

# Object-ball ids of the rack, row by row from the apex (an 8-ball rack: 1 at the
# apex, 8 in the middle of the third row, a solid and a stripe in the back corners).
RACK_ORDER = ("1", "9", "2", "10", "8", "3", "11", "7", "14", "4", "5", "13", "15", "6", "12")


# The names [simulation] method may take: the file format's, so that the reader needs
# no physics. billiards.physics.METHODS implements exactly these (tests/test_floors.py).
METHODS = ("exact", "event", "naive")
# The motion models, ball laws and cushion laws [physics] may name: the physics'
# registries (billiards.physics.engine.motion_law.MOTION_LAWS, billiards.physics.laws.BALL_LAWS
# and CUSHION_LAWS) implement exactly these (tests/test_registries.py).
MODELS = ("rolling", "spin")
BALL_MODELS = ("frictionless", "frictional")
CUSHION_MODELS = ("mirror", "han2005", "mathavan2010", "mathavan2010_ev")
# The cushion laws that need the spin model (and a nose between the equator and the top).
GRIPPING_CUSHIONS = ("han2005", "mathavan2010", "mathavan2010_ev")
# The integrated ones, and their own defaults of (cushion_restitution, cushion_friction).
IMPACT_CUSHIONS = {
    "mathavan2010": (seed.MATHAVAN_RESTITUTION, seed.MATHAVAN_FRICTION),
    "mathavan2010_ev": (seed.MATHAVAN_EV_RESTITUTION, seed.MATHAVAN_FRICTION),
}


# Every default is the seed's (billiards.rules.seed, which the physics' Setup reads too).
@dataclass(frozen=True)
class Table:
    length: float = seed.TABLE_SIZE[0]  # m between cushion noses, along x
    width: float = seed.TABLE_SIZE[1]  # m, along y
    cushion_retention: float = seed.RETENTION  # share of kinetic energy a cushion keeps
    # Six pockets (docs/explanation/pockets.md); off by default: the seed's table has none.
    pockets: bool = False
    # WPA specifications' narrowest mouths (4.5 in, 5 in), between the points where
    # the cushion noses end; each nose ends in a jaw rounded to jaw_radius.
    corner_pocket_width: float = seed.CORNER_POCKET_WIDTH  # m
    side_pocket_width: float = seed.SIDE_POCKET_WIDTH  # m
    jaw_radius: float = seed.JAW_RADIUS  # m


@dataclass(frozen=True)
class Physics:
    gravity: float = seed.GRAVITY  # m/s^2
    rolling_friction: float = seed.ROLLING_FRICTION  # mu: balls slow at mu * g
    ball_restitution: float = seed.RESTITUTION  # 1 = elastic ball-ball contacts
    # The bed's e_t for a ball driven into it or landing on it (a jump: issue 45).
    table_restitution: float = seed.TABLE_RESTITUTION
    # Balls may leave the cloth by contacts, not only by a jump (issue 45): a flying ball
    # striking one on its upper half drives it into the bed, which throws it up, and
    # every elevated stroke drives its ball into the bed (spin model).
    airborne: bool = False
    model: str = "rolling"  # "rolling" (the seed) | "spin" (sliding, rolling, spinning)
    sliding_friction: float = seed.SLIDING_FRICTION  # mu_s, the spin model's sliding balls
    # mu_sp, a plain number: vertical spin decays at 5 mu_sp g / (2r) rad/s^2. The
    # default is pooltool's 4/9 R at R = 0.0286 m, fixed: it does not follow the radius.
    spinning_friction: float = seed.SPINNING_FRICTION
    # "mirror" (the seed's law) | "han2005" | "mathavan2010" | "mathavan2010_ev" (spin
    # model; docs/validation.md)
    cushion_model: str = "mirror"
    # han2005's e (mathavan2010's e_e: its default is seed.MATHAVAN_RESTITUTION, 0.98)
    cushion_restitution: float = seed.CUSHION_RESTITUTION
    # han2005's mu between ball and cushion (mathavan2010's mu_w: seed.MATHAVAN_FRICTION)
    cushion_friction: float = seed.CUSHION_FRICTION
    cushion_height: float = seed.CUSHION_HEIGHT  # m, the nose's height: 63.5% of 2 r
    # mathavan2010_ev's v_c: e_e = cushion_restitution / sqrt(1 + (v_n / v_c)^4)
    cushion_restitution_speed: float = seed.MATHAVAN_EV_SPEED  # m/s
    # "frictionless" (the seed's law) | "frictional" (spin model: throw, docs/explanation/collisions.md)
    ball_model: str = "frictionless"
    # The frictional law's mu = a + b exp(-c s) at the contact point's slip speed s (m/s).
    ball_friction_a: float = seed.BALL_FRICTION_A
    ball_friction_b: float = seed.BALL_FRICTION_B
    ball_friction_c: float = seed.BALL_FRICTION_C  # s/m


@dataclass(frozen=True)
class Ball:
    id: str
    position: tuple[float, float]  # m, centre; origin at a cushion-nose corner
    velocity: tuple[float, float] = (0.0, 0.0)  # m/s
    mass: float = seed.MASS  # kg
    spin: tuple[float, float, float] | None = None  # rad/s, world axes (spin model)
    tip: tuple[float, float] | None = None  # cue tip (side, height) / r (spin model)
    # The file's `cue = {...}`: a stroke, which gave `velocity` and `spin` (spin model;
    # billiards.scene.stroke).
    stroke: Stroke | None = None


@dataclass(frozen=True)
class Simulation:
    method: str = "exact"  # "exact" | "event" | "naive"
    dt: float = seed.DT  # s, the fixed step of "exact" and "naive"
    max_time: float = seed.MAX_TIME  # s
    max_events: int = seed.MAX_EVENTS  # guard against inelastic collapse in a frozen cluster


@dataclass(frozen=True)
class Scene:
    """A scene file, read and checked: the table, the physics, the balls, how to
    simulate and how to film. `billiards.load_scene` (or `run`, `vary`) makes one from a
    shipped name, a file or a dict of tables. It is frozen: change it with
    `dataclasses.replace`, and every function that takes it checks it again as its file
    would be checked (a ball off the table or overlapping another is a SceneError);
    `billiards.scene_tables(scene)` gives its tables back.

        >>> import dataclasses
        >>> scene = billiards.load_scene("pocket_shot")
        >>> cue = dataclasses.replace(scene.balls[0], velocity=(2.0, 0.0))
        >>> faster = dataclasses.replace(scene, balls=(cue, *scene.balls[1:]))
        >>> billiards.run(faster).rest_time > 0
        True
    """

    table: Table = field(default_factory=Table)
    """[table]: length and width (m), cushion retention, pockets."""
    physics: Physics = field(default_factory=Physics)
    """[physics]: gravity, frictions, restitutions, the motion model and the laws."""
    radius: float = seed.RADIUS
    """[balls] radius, m: one radius for every ball."""
    balls: tuple[Ball, ...] = ()
    """Every ball (a rack's too), in the order of every per-ball array: `id`,
    `position` (m), `velocity` (m/s), `mass` (kg), `spin`, `tip`, `stroke`."""
    simulation: Simulation = field(default_factory=Simulation)
    """[simulation]: method, dt, max_time, max_events."""
    render: RenderSettings = field(default_factory=RenderSettings)
    """The file's [render] table and [[camera]] shots (billiards.scene.render_table)."""
    source: str = "<defaults>"
    """Where the scene came from (a shipped name, a path, "<dict>"), for messages."""

    @property
    def ball_ids(self) -> tuple[str, ...]:
        return tuple(ball.id for ball in self.balls)


# --- the scene ---------------------------------------------------------------------------


def default_scene_path() -> Path:
    """The seed break that ships with the package."""
    return Path(str(importlib.resources.files("billiards.assets") / "scenes" / "break.toml"))


def shipped_scene_names() -> list[str]:
    """The scenes that ship with the package, by name (`break`, `hard_break`, ...)."""
    return sorted(path.stem for path in default_scene_path().parent.glob("*.toml"))


def find_scene(name_or_path: str | Path) -> Path:
    """A scene file: the path if it exists, else a shipped scene's name (with or
    without .toml). Anything else is a SceneError listing the shipped names."""
    path = Path(name_or_path)
    if _exists(path):
        return path
    shipped = default_scene_path().parent / f"{path.name.removesuffix('.toml')}.toml"
    if path.parent == Path(".") and _exists(shipped):
        return shipped
    names = ", ".join(shipped_scene_names())
    raise SceneError(f"{name_or_path}: no such scene file, nor a shipped scene ({names})")


def _exists(path: Path) -> bool:
    """Whether the path names something; a name the system cannot look up (too long, a
    NUL byte) names nothing."""
    try:
        return path.exists()
    except (OSError, ValueError):
        return False


def load_scene(path: str | Path | None = None) -> Scene:
    """Read a scene file or shipped scene by name (the seed break when path is None)."""
    data, source = read_scene_tables(path)
    return scene_from_dict(data, source)


def read_scene_tables(path: str | Path | None = None) -> tuple[dict[str, Any], str]:
    """A scene file's (or shipped scene's) TOML tables, unchecked, and the name errors
    give it (the seed break when path is None); SceneError if it cannot be read."""
    file = find_scene(path) if path is not None else default_scene_path()
    source = str(path) if path is not None else file.name
    try:
        text = file.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"{source}: no such scene file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise SceneError(f"{source}: cannot read the scene file ({error})") from None
    return _toml(text, source), source


def parse_scene(text: str, source: str = "<scene>") -> Scene:
    """Parse TOML text into a validated Scene."""
    return scene_from_dict(_toml(text, source), source)


def _toml(text: str, source: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SceneError(f"{source}: TOML syntax error: {error}") from None


def scene_from_dict(data: dict[str, Any], source: str = "<scene>") -> Scene:
    """A scene file's tables checked and read, table by table in the file format's
    order (the first bad key is the one said, and the site's key reference follows it)."""
    root = TableReader(data, "", source)
    table, table_reader = _read_table(root)
    physics = _read_physics(root)
    reader = root.table("balls")
    radius = bounded(reader, "radius", Scene.radius)
    default_mass = bounded(reader, "mass", Ball.mass)
    reader.finish()
    _check_ball_size(table, table_reader, physics, radius)
    # Explicit balls first (the cue ball leads the seed break), then the rack.
    balls = [
        (_read_ball(reader, physics, radius, default_mass), reader.path)
        for reader in root.tables("ball")
    ]
    balls += _racked_balls(root, table, radius, default_mass, seed_break=not balls)
    simulation = _read_simulation(root)
    render = parse_render_settings(root)
    root.finish()
    _check_balls(balls, table, radius, source)
    _check_none_in_a_pocket(balls, table, source)
    scene = Scene(
        table=table,
        physics=physics,
        radius=radius,
        balls=tuple(ball for ball, _ in balls),
        simulation=simulation,
        render=render,
        source=source,
    )
    _mark_read(scene)
    return scene


# The scenes the reader made, by identity, while they live: check_scene takes them as
# read instead of reading their tables again for every run of a batch. (By identity: a
# WeakSet compares by equality, and keeps one entry for two equal scenes.)
_READ: dict[int, weakref.ref[Scene]] = {}


def _mark_read(scene: Scene) -> None:
    key = id(scene)

    def forget(dead: weakref.ref[Scene]) -> None:
        if _READ.get(key) is dead:
            del _READ[key]

    _READ[key] = weakref.ref(scene, forget)


def _was_read(scene: Scene) -> bool:
    kept = _READ.get(id(scene))
    return kept is not None and kept() is scene


def with_render(scene: Scene, render: RenderSettings) -> Scene:
    """The scene with other film settings, as read if it was (check_scene leaves the
    render settings to the film, which checks the numbers it is made with)."""
    changed = replace(scene, render=render)
    if _was_read(scene):
        _mark_read(changed)
    return changed


def _read_table(root: TableReader) -> tuple[Table, TableReader]:
    """[table], and its reader: the pockets are checked against the balls' radius later."""
    reader = root.table("table")
    table = Table(
        length=bounded(reader, "length", Table.length),
        width=bounded(reader, "width", Table.width),
        cushion_retention=reader.number(
            "cushion_retention", Table.cushion_retention, low=0.0, high=1.0
        ),
        pockets=reader.boolean("pockets", Table.pockets),
        corner_pocket_width=reader.number(
            "corner_pocket_width", Table.corner_pocket_width, low=0.0, low_open=True
        ),
        side_pocket_width=reader.number(
            "side_pocket_width", Table.side_pocket_width, low=0.0, low_open=True
        ),
        jaw_radius=reader.number("jaw_radius", Table.jaw_radius, low=0.0),
    )
    reader.finish()
    return table, reader


def _read_physics(root: TableReader) -> Physics:
    """[physics]: the integrated cushion laws bring their own restitution and friction."""
    reader = root.table("physics")
    cushion_model = reader.string("cushion_model", Physics.cushion_model, CUSHION_MODELS)
    restitution, friction = IMPACT_CUSHIONS.get(
        cushion_model, (Physics.cushion_restitution, Physics.cushion_friction)
    )
    physics = Physics(
        gravity=bounded(reader, "gravity", Physics.gravity),
        rolling_friction=bounded(reader, "rolling_friction", Physics.rolling_friction),
        ball_restitution=reader.number(
            "ball_restitution", Physics.ball_restitution, low=0.0, high=1.0
        ),
        table_restitution=reader.number(
            "table_restitution", Physics.table_restitution, low=0.0, high=1.0
        ),
        airborne=reader.boolean("airborne", Physics.airborne),
        model=reader.string("model", Physics.model, MODELS),
        sliding_friction=bounded(reader, "sliding_friction", Physics.sliding_friction),
        spinning_friction=bounded(reader, "spinning_friction", Physics.spinning_friction),
        cushion_model=cushion_model,
        cushion_restitution=reader.number("cushion_restitution", restitution, low=0.0, high=1.0),
        cushion_friction=bounded(reader, "cushion_friction", friction),
        cushion_height=reader.number(
            "cushion_height", Physics.cushion_height, low=0.0, low_open=True
        ),
        cushion_restitution_speed=bounded(
            reader, "cushion_restitution_speed", Physics.cushion_restitution_speed
        ),
        ball_model=reader.string("ball_model", Physics.ball_model, BALL_MODELS),
        ball_friction_a=bounded(reader, "ball_friction_a", Physics.ball_friction_a),
        ball_friction_b=bounded(reader, "ball_friction_b", Physics.ball_friction_b),
        ball_friction_c=bounded(reader, "ball_friction_c", Physics.ball_friction_c),
    )
    if physics.cushion_model in GRIPPING_CUSHIONS and physics.model != "spin":
        raise reader.fail("cushion_model", physics.cushion_model, 'physics.model = "spin" first')
    if physics.ball_model == "frictional" and physics.model != "spin":
        raise reader.fail("ball_model", "frictional", 'physics.model = "spin" first')
    if physics.airborne and physics.model != "spin":
        raise reader.fail("airborne", True, 'physics.model = "spin" first')
    if physics.airborne and not physics.gravity > 0:
        raise SceneError(
            f"{reader.source}: physics.gravity = {physics.gravity:g}: expected > 0 m/s^2 "
            f"with physics.airborne = true (a ball in the air would never land)"
        )
    reader.finish()
    return physics


def _check_ball_size(
    table: Table, table_reader: TableReader, physics: Physics, radius: float
) -> None:
    """The balls' radius against the cushions' nose, the table and its pockets."""
    source = table_reader.source
    gripping = physics.cushion_model in GRIPPING_CUSHIONS
    if gripping and not radius < physics.cushion_height < 2 * radius:
        raise SceneError(
            f"{source}: physics.cushion_height = {physics.cushion_height:g}: expected a "
            f"cushion nose above the ball's equator and below its top ({radius:g} to "
            f"{2 * radius:g} m)"
        )
    if physics.cushion_model in IMPACT_CUSHIONS:
        # The impact ends only if the cushion always slows the ball's normal speed
        # (billiards.physics.laws.mathavan2010).
        sin_t = physics.cushion_height / radius - 1.0
        cos_t = math.sqrt(1.0 - sin_t * sin_t)
        mu_w, mu_s = physics.cushion_friction, physics.sliding_friction
        if not cos_t > mu_w * sin_t + mu_s * (sin_t + mu_w * cos_t):
            raise SceneError(
                f"{source}: physics.cushion_friction = {mu_w:g}: expected "
                f"{physics.cushion_model}'s cushion and cloth frictions to let the cushion "
                f"stop the ball (cos t > mu_w sin t + mu_s (sin t + mu_w cos t), sin t = "
                f"cushion_height / radius - 1; here sliding_friction = {mu_s:g})"
            )
    if 2 * radius >= min(table.length, table.width):
        raise SceneError(
            f"{source}: balls.radius = {radius:g}: expected a ball that fits on the table "
            f"(diameter below {min(table.length, table.width):g} m)"
        )
    if table.pockets:
        problem = pocket_problem(
            (table.length, table.width),
            radius,
            table.corner_pocket_width,
            table.side_pocket_width,
            table.jaw_radius,
        )
        if problem is not None:
            raise table_reader.fail(*problem)


def _read_ball(reader: TableReader, physics: Physics, radius: float, default_mass: float) -> Ball:
    """One [[ball]]: its place, and its motion as given or as a cue's stroke leaves it."""
    ball_id = reader.raw("id")
    if ball_id is None:
        raise reader.missing("id", "a unique string")
    if not isinstance(ball_id, str) or not ball_id:
        raise reader.fail("id", ball_id, "a non-empty string")
    if not reader.has("position"):
        raise reader.missing("position", "[x, y] in m")
    position = reader.vector("position", (0.0, 0.0))
    velocity = reader.vector("velocity", (0.0, 0.0))
    length_within(reader, "velocity", velocity, 1.0, "a speed |velocity|")
    mass = bounded(reader, "mass", default_mass)
    spin: tuple[float, ...] | None = None
    tip = stroke = None
    if reader.has("cue"):
        stroke = _stroke(reader, physics, mass, radius)
        struck = strike(stroke, mass, radius)
        velocity, spin = struck.velocity, struck.spin
    if reader.has("spin"):
        if physics.model != "spin":
            raise reader.fail("spin", reader.raw("spin"), 'physics.model = "spin" first')
        if reader.has("tip"):
            raise reader.fail("spin", reader.raw("spin"), "spin or tip, not both")
        spin = reader.vector("spin", (0.0, 0.0, 0.0), size=3)
        length_within(reader, "spin", spin, radius, "a surface speed |spin| * radius")
    if reader.has("tip"):
        if physics.model != "spin":
            raise reader.fail("tip", reader.raw("tip"), 'physics.model = "spin" first')
        tip = reader.vector("tip", (0.0, 0.0))
        if tip[0] * tip[0] + tip[1] * tip[1] > 1:  # + - * only: the same on every machine
            raise reader.fail("tip", list(tip), "a point on the ball: side^2 + height^2 <= 1")
    reader.finish()
    return Ball(
        id=ball_id,
        position=(position[0], position[1]),
        velocity=(velocity[0], velocity[1]),
        mass=mass,
        spin=None if spin is None else (spin[0], spin[1], spin[2]),
        tip=None if tip is None else (tip[0], tip[1]),
        stroke=stroke,
    )


def _racked_balls(
    root: TableReader, table: Table, radius: float, default_mass: float, *, seed_break: bool
) -> list[tuple[Ball, str]]:
    """[rack]'s 15 balls, each with where it came from; with `seed_break` (no [[ball]])
    and no [rack], the seed's break on this table, so a file can change only physics."""
    balls: list[tuple[Ball, str]] = []
    if seed_break and not root.has("rack"):
        # The cue ball from the head spot at 3 m/s into a rack on the foot spot.
        seed_tables = seed_break_tables(table)
        cue = seed_tables["ball"][0]
        balls.append(
            (
                Ball(
                    id="cue",
                    position=tuple(cue["position"]),
                    velocity=tuple(cue["velocity"]),
                    mass=cue["mass"],
                ),
                "the seed's cue ball",
            )
        )
        rack = seed_tables["rack"]
        for ball_id, position in zip(
            RACK_ORDER, rack_positions(rack["apex"], radius, rack["gap"]), strict=True
        ):
            balls.append((Ball(ball_id, position, mass=default_mass), "the seed's rack"))
    if root.has("rack"):
        reader = root.table("rack")
        apex = reader.vector("apex", seed.foot_spot((table.length, table.width)))
        gap = bounded(reader, "gap", seed.RACK_GAP)
        reader.finish()
        for ball_id, position in zip(RACK_ORDER, rack_positions(apex, radius, gap), strict=True):
            balls.append((Ball(ball_id, position, mass=default_mass), "rack"))
    return balls


def _read_simulation(root: TableReader) -> Simulation:
    """[simulation]: the method, its step and the run's limits."""
    reader = root.table("simulation")
    simulation = Simulation(
        method=reader.string("method", Simulation.method, METHODS),
        dt=bounded(reader, "dt", Simulation.dt),
        max_time=bounded(reader, "max_time", Simulation.max_time),
        max_events=reader.integer("max_events", Simulation.max_events, low=1),
    )
    if simulation.dt > simulation.max_time:  # a naive run would take no step at all
        raise reader.fail(
            "dt", simulation.dt, f"a step no longer than max_time ({simulation.max_time:g} s)"
        )
    reader.finish()
    return simulation


def _check_none_in_a_pocket(balls: list[tuple[Ball, str]], table: Table, source: str) -> None:
    """On a table with pockets, no ball may start inside a corner pocket's mouth."""
    if not table.pockets:
        return
    for ball, where in balls:
        pocket = corner_pocket_of(
            (table.length, table.width),
            table.corner_pocket_width,
            table.jaw_radius,
            ball.position,
        )
        if pocket is not None:
            x, y = ball.position
            raise SceneError(
                f'{source}: {where} (id "{ball.id}") position = [{x:g}, {y:g}]: expected a '
                f"centre on the table, not already in the {pocket} pocket"
            )


def check_scene(scene: Scene) -> Scene:
    """A Scene made or changed in Python, checked as its file would be: written back to
    its tables (`scene_tables_of`) and read again, so a ball off the table or two balls
    overlapping are the reader's one-line SceneError. Returns the scene itself if
    nothing differs, else the scene as read (its numbers as floats), with the given
    scene's name and render settings: those are not checked here (render_setting_problem
    checks the numbers a film is made with)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene = {shown(scene)}: expected a billiards.Scene")
    if _was_read(scene):
        return scene
    checked = scene_from_dict(scene_tables_of(scene), scene.source)
    for given, read in zip(scene.balls, checked.balls, strict=True):
        if given.stroke is not None and (given.velocity, given.spin) != (
            read.velocity,
            read.spin,
        ):
            raise SceneError(
                f'{scene.source}: ball (id "{given.id}") velocity = {list(given.velocity)}: '
                "expected the velocity and spin its stroke gives (a struck ball takes both "
                "from `stroke`; change the stroke, or set stroke=None)"
            )
    checked = replace(checked, render=scene.render)
    return scene if checked == scene else checked  # the same object when nothing changed


def scene_tables_of(scene: Scene) -> dict[str, Any]:
    """A Scene's TOML tables (its [render] and [[camera]] tables left out), which the
    reader turns back into the same scene: every ball explicit (a rack's balls
    included), a struck ball by its stroke. TypeError, one line, for a part that is not
    the dataclass it should be."""
    parts: dict[str, tuple[object, type[Table | Physics | Simulation]]] = {
        "table": (scene.table, Table),
        "physics": (scene.physics, Physics),
        "simulation": (scene.simulation, Simulation),
    }
    data: dict[str, Any] = {}
    for name, (part, kind) in parts.items():
        if not isinstance(part, kind):
            raise TypeError(
                f"scene.{name} = {shown(part)}: expected a billiards.scene.reader.{kind.__name__}"
            )
        data[name] = {item.name: _plain(getattr(part, item.name)) for item in fields(kind)}
    data["balls"] = {"radius": _plain(scene.radius)}
    if isinstance(scene.balls, str) or not isinstance(scene.balls, Sequence):
        raise TypeError(f"scene.balls = {shown(scene.balls)}: expected a tuple of Balls")
    if not scene.balls:  # the reader would fill in the seed break
        raise SceneError(f"{scene.source}: balls = (): expected at least one ball")
    data["ball"] = [_ball_table(ball, index) for index, ball in enumerate(scene.balls)]
    return data


def _ball_table(ball: Ball, index: int) -> dict[str, Any]:
    if not isinstance(ball, Ball):
        raise TypeError(
            f"scene.balls[{index}] = {shown(ball)}: expected a billiards.scene.reader.Ball"
        )
    table: dict[str, Any] = {
        "id": ball.id,
        "position": _plain(ball.position),
        "mass": _plain(ball.mass),
    }
    if ball.stroke is not None:
        if not isinstance(ball.stroke, Stroke):
            raise TypeError(
                f"scene.balls[{index}].stroke = {shown(ball.stroke)}: expected a Stroke or None"
            )
        table["cue"] = {
            item.name: _plain(getattr(ball.stroke, item.name)) for item in fields(Stroke)
        }
        return table
    table["velocity"] = _plain(ball.velocity)
    for name in ("spin", "tip"):
        if getattr(ball, name) is not None:
            table[name] = _plain(getattr(ball, name))
    return table


def _plain(value: Any) -> Any:
    """A value as TOML would give it: tuples (and numpy arrays) as lists, numpy
    numbers as Python's; anything else as it is, for the reader to judge."""
    if isinstance(value, tuple | list):
        return [_plain(item) for item in value]
    if type(value).__module__ == "numpy":  # an array or a numpy number (numpy not imported)
        return value.tolist()
    return value


def _stroke(reader: TableReader, physics: Physics, mass: float, radius: float) -> Stroke:
    """A [[ball]]'s `cue = {...}` table: the stroke, checked (one line per bad value)."""
    if physics.model != "spin":
        raise reader.fail("cue", reader.raw("cue"), 'physics.model = "spin" first')
    for given in ("velocity", "spin", "tip"):
        if reader.has(given):
            raise reader.fail("cue", reader.raw("cue"), f"a stroke or a {given}, not both")
    cue = reader.table("cue")
    if not cue.has("speed"):
        raise cue.missing("speed", "the cue's speed in m/s, a number > 0")
    speed = bounded(cue, "speed", 0.0)
    direction = cue.number("direction", Stroke.direction, what="degrees, a finite number")
    in_range = "degrees in [0, 90) (0: a level cue; 90 and more drive the ball through the bed)"
    elevation = cue.number("elevation", Stroke.elevation, low=0.0, what=in_range)
    if not elevation < 90:
        raise cue.fail("elevation", cue.raw("elevation"), in_range)
    side, height = cue.vector("tip", Stroke.tip)
    if side * side + height * height > 1:  # + - * only: the same on every machine
        raise cue.fail("tip", [side, height], "a point on the ball: side^2 + height^2 <= 1")
    stroke = Stroke(
        speed=speed,
        direction=direction,
        elevation=elevation,
        tip=(side, height),
        mass=bounded(cue, "mass", Stroke.mass),
        end_mass=bounded(cue, "end_mass", Stroke.end_mass),
    )
    cue.finish()
    drive_down = strike(stroke, mass, radius).drive_down
    hop = jump_height(drive_down, physics.gravity, physics.table_restitution)
    if hop >= JUMP_LIMIT * radius and physics.gravity == 0:
        # Without gravity a lifted ball never comes down (issue 45's bad input): the
        # same strokes as the jump refusal below, named by the key that makes them so.
        raise SceneError(
            f"{reader.source}: physics.gravity = 0: expected > 0 m/s^2 for a stroke that "
            f"lifts the ball ({cue.path}.elevation = {elevation} drives it into the bed, "
            f"which throws it up; without gravity it would never land)"
        )
    return stroke


def seed_break_tables(table: Table) -> dict[str, Any]:
    """The [[ball]] and [rack] tables of the seed's break on this table, which a file
    with neither gets: the cue ball from the head spot at 3 m/s into a rack on the
    foot spot."""
    size = (table.length, table.width)
    return {
        "ball": [
            {
                "id": "cue",
                "position": list(seed.head_spot(size)),
                "velocity": [seed.CUE_SPEED, 0.0],
                "mass": seed.CUE_MASS,
            }
        ],
        "rack": {"apex": list(seed.foot_spot(size)), "gap": seed.RACK_GAP},
    }


def rack_positions(apex: Sequence[float], radius: float, gap: float) -> list[tuple[float, float]]:
    """Centres of the 15-ball triangle: apex first, rows growing towards +x."""
    spacing = 2 * radius + gap
    row_step = spacing * math.sqrt(3) / 2
    positions = []
    for row in range(5):
        for place in range(row + 1):
            positions.append((apex[0] + row * row_step, apex[1] + (place - row / 2) * spacing))
    return positions


def _check_balls(balls: list[tuple[Ball, str]], table: Table, radius: float, source: str) -> None:
    if not balls:
        raise SceneError(f"{source}: no balls: expected a [rack] table or at least one [[ball]]")
    seen: dict[str, str] = {}
    for ball, where in balls:
        if ball.id in seen:
            raise SceneError(
                f'{source}: {where}.id = "{ball.id}": expected a unique id '
                f"(already used by {seen[ball.id]})"
            )
        seen[ball.id] = where
        x, y = ball.position
        if not (radius <= x <= table.length - radius and radius <= y <= table.width - radius):
            raise SceneError(
                f'{source}: {where} (id "{ball.id}") position = [{x:g}, {y:g}]: expected a centre '
                f"inside the cushions, x in [{radius:g}, {table.length - radius:g}] and "
                f"y in [{radius:g}, {table.width - radius:g}]"
            )
    # Touching balls (a frozen rack) are allowed; overlap beyond rounding is not.
    limit = 2 * radius * (1 - 1e-12)
    for index, (ball, where) in enumerate(balls):
        for other, _ in balls[index + 1 :]:
            dx, dy = ball.position[0] - other.position[0], ball.position[1] - other.position[1]
            distance = math.sqrt(dx * dx + dy * dy)  # not math.dist: libm's bits vary
            if distance < limit:
                raise SceneError(
                    f'{source}: {where} (id "{ball.id}") position = '
                    f"[{ball.position[0]:g}, {ball.position[1]:g}]: expected no overlap, but it is "
                    f'{distance:.6g} m from ball "{other.id}" (closer than 2r = {2 * radius:g} m)'
                )
