"""How large and how small a scene's numbers may be: the bounds the reader enforces.

Every number a scene file gives is finite, and of a size the engine runs finitely with:
speeds (and squares of speeds, and sums of those, in the contact-time polynomials) far
from overflow, sizes far above the engine's absolute tolerances (1e-9 m), times whose
rounding moves a ball by less than those tolerances. Each bound carries the reason it
is where it is; docs/scene_bounds.md is their table (tests/test_scene_bounds.py checks
that the page names every bound, and draws scenes at and just past each one).

A floor above billiards.scene.tables, whose TableReader it reads numbers with.
"""

from __future__ import annotations

from dataclasses import dataclass

from billiards.scene.tables import TableReader

DOCS = "docs/scene_bounds.md"


@dataclass(frozen=True)
class Bound:
    """A number's range, [low, high] (low excluded if low_open), its unit and why."""

    low: float
    high: float
    unit: str
    reason: str
    low_open: bool = False

    def expected(self) -> str:
        """What the one-line error says was expected."""
        return f"a number in {self.range_text()}"

    def range_text(self) -> str:
        """'[low, high] unit (see the docs page)'."""
        opening = "(" if self.low_open else "["
        unit = f" {self.unit}" if self.unit else ""
        return f"{opening}{self.low:g}, {self.high:g}]{unit} (see {DOCS})"


# The fastest ball: a professional break sends the cue ball at 10-12 m/s; the suite
# proves runs sound at 1,000 m/s (tests/physics/test_physical_facts.py), ~80 times that.
MAX_SPEED = 1000.0  # m/s
# A cue tip on the ball's edge gives it a spin whose surface speed is 5/2 of its speed.
MAX_SURFACE_SPEED = 2.5 * MAX_SPEED  # m/s, |spin| * radius
MAX_TIME = 3600.0  # s

_FRICTION = Bound(
    0.0,
    10.0,
    "",
    "a coefficient of friction: cloth, cushion and ball ones are 0.005-0.3; "
    "above 10 nothing slides at all",
)
_MASS = Bound(
    0.001,
    1000.0,
    "kg",
    "pool balls weigh 0.16-0.17 kg and cues 0.5-0.6 kg; within [1 g, 1 t] no ratio of "
    "two masses exceeds 1e6, so an impulse between them keeps its digits",
)

# By the file's key path; `ball.` keys hold for every [[ball]], `camera.` for every shot.
BOUNDS: dict[str, Bound] = {
    "table.length": Bound(
        0.0,
        100.0,
        "m",
        "the largest real table (snooker) is 3.6 m long; also above the ball's "
        "diameter (the ball must fit)",
        low_open=True,
    ),
    "table.width": Bound(
        0.0,
        100.0,
        "m",
        "as the length: 100 m keeps a position's rounding (1.4e-14 m) far below the "
        "engine's 1e-9 m tolerance",
        low_open=True,
    ),
    "balls.radius": Bound(
        0.001,
        1.0,
        "m",
        "pool balls are 26-31 mm; the engine's contact tolerances are absolute (1e-9 m "
        "overlap, 1e-13 m pushes), a millionth of a 1 mm ball at most",
    ),
    "balls.mass": _MASS,
    "ball.mass": _MASS,
    "ball.velocity": Bound(
        0.0,
        MAX_SPEED,
        "m/s",
        "the speed |velocity|: a break's cue ball goes 10-12 m/s, ~80 times less; 1e160 "
        "m/s overflows the squares of speeds the contact times are solved from",
    ),
    "ball.spin": Bound(
        0.0,
        MAX_SURFACE_SPEED,
        "m/s",
        "the surface speed |spin| * radius: 5/2 of the fastest speed, what a cue tip "
        "on the ball's edge gives a ball at that speed",
    ),
    "ball.cue.speed": Bound(
        0.0,
        MAX_SPEED / 2,
        "m/s",
        "a cue at most doubles its speed into the ball's (TP A-30), so the struck ball "
        "stays within the ball's speed bound; a break's cue moves at 8-12 m/s",
        low_open=True,
    ),
    "ball.cue.mass": _MASS,
    "ball.cue.end_mass": _MASS,
    "rack.gap": Bound(
        0.0,
        1.0,
        "m",
        "a racked ball's neighbours are touching or 0.1 mm apart; a metre between "
        "them is no rack (and every ball must still lie on the table)",
    ),
    "physics.gravity": Bound(
        0.0,
        100.0,
        "m/s^2",
        "ten times the Earth's 9.81 m/s^2; 0 is allowed (nothing slows: the run ends at max_time)",
    ),
    "physics.rolling_friction": _FRICTION,
    "physics.sliding_friction": _FRICTION,
    "physics.spinning_friction": _FRICTION,
    "physics.cushion_friction": _FRICTION,
    "physics.ball_friction_a": _FRICTION,
    "physics.ball_friction_b": _FRICTION,
    "physics.cushion_restitution_speed": Bound(
        0.01,
        MAX_SPEED,
        "m/s",
        "mathavan2010_ev's v_c, the normal speed at which its e_e has fallen to e_0 / "
        "sqrt(2) (4.15 m/s fitted to the paper's rebounds): any v_c > 0 runs finite, but "
        "below 1 cm/s every rebound of 1 m/s or more is dead (e_e < 1e-4 e_0), and at "
        "the fastest ball's speed a break's 10 m/s rebound is within 5e-9 of e_0 (the "
        "law mathavan2010)",
    ),
    "physics.ball_friction_c": Bound(
        0.0,
        1000.0,
        "s/m",
        "the decay of ball-ball friction with slip speed (1.088 s/m measured); at "
        "1000 s/m it is gone at a mm/s of slip",
    ),
    "simulation.dt": Bound(
        1e-6,
        1.0,
        "s",
        "the fixed step (1/240 s by default): a microsecond step already takes the "
        "naive method 1e6 steps a second of play; a step over 1 s samples nothing",
    ),
    "simulation.max_time": Bound(
        1e-6,
        MAX_TIME,
        "s",
        "an hour (a break rests within a minute); a time's rounding at an hour "
        "(4.5e-13 s) moves the fastest ball by 4.5e-10 m, within the 1e-9 m tolerance; "
        "at least the shortest step (and dt no longer than max_time)",
    ),
    "render.lead": Bound(
        0.0,
        60.0,
        "s",
        "film before the shot (0.5 s by default): a minute of still frames is plenty; "
        "more makes a film of frames that never ends",
    ),
    "render.tail": Bound(
        0.0,
        60.0,
        "s",
        "film after the last ball stops (1 s by default), as the lead",
    ),
    "camera.start": Bound(
        -60.0,
        MAX_TIME,
        "s",
        "a shot's start in simulation time: from the earliest lead to the latest max_time",
    ),
    "camera.eye": Bound(
        -1000.0,
        1000.0,
        "m",
        "each coordinate: a kilometre from the table shows it as a speck; far "
        "beyond, the view's matrices lose the table to rounding",
    ),
    "camera.target": Bound(
        -1000.0,
        1000.0,
        "m",
        "each coordinate, as the eye",
    ),
    "camera.orbit": Bound(
        -3600.0,
        3600.0,
        "degrees/s",
        "ten turns a second: faster than any frame rate can show (the orbit preset "
        "turns 6 degrees/s)",
    ),
    "camera.ease": Bound(
        0.001,
        60.0,
        "s",
        "how long an ease between shots takes (1 s by default): shorter than a "
        'millisecond is a cut (use transition = "cut"), longer than a minute never ends',
    ),
}


def bound_of(path: str, key: str) -> Bound:
    """The bound of `key` in the table at `path` ("ball[2].cue" -> "ball.cue.key")."""
    return BOUNDS[".".join([*(part.split("[")[0] for part in path.split(".") if part), key])]


def bounded(reader: TableReader, key: str, default: float) -> float:
    """reader.number(key, default) within the key's bound (one line naming it if not)."""
    bound = bound_of(reader.path, key)
    return reader.number(
        key,
        default,
        low=bound.low,
        high=bound.high,
        low_open=bound.low_open,
        what=bound.expected(),
    )


def length_within(
    reader: TableReader, key: str, vector: tuple[float, ...], scale: float, what: str
) -> None:
    """Refuse a vector whose length times `scale` exceeds the key's bound (`what` names
    that product: a speed, a spin's surface speed); squares and sums only, the same on
    every machine, and inf (refused), not an error, where a square overflows."""
    bound = bound_of(reader.path, key)
    square = sum(v * v for v in vector) * (scale * scale)
    if not square <= bound.high * bound.high:
        expected = f"{what} at most {bound.high:g} {bound.unit} (see {DOCS})"
        raise reader.fail(key, list(vector), expected)
