"""A cue that strikes: the ball's velocity and spin from a stroke (`[[ball]] cue = {...}`).

Alciatore's instantaneous cue-tip model, "Effects of cue tip offset, cue weight, and
cue speed on cue ball speed and spin" (technical proof TP A-30), with the cue
elevated as pooltool applies it (physics/resolve/stick_ball/instantaneous_point), and
squirt from the cue's end mass (TP A-31). The cue, of mass M, moves at speed V along
its axis

    c = cos(elevation) d - sin(elevation) z,   d = (cos(direction), sin(direction), 0)

and meets the ball where its axis passes the ball's centre at the offset
R (side s + height u) in the plane across the cue (s = d x z the shooter's right,
u = sin(elevation) d + cos(elevation) z the cue's "up"): the existing `tip` when the
cue is level. The impulse F acts along c (a tip that does not grip sideways) and is
elastic (A-30's e = 1), so, with b^2 = R^2 (side^2 + height^2) the squared distance
of the cue's axis from the centre and I = 2/5 m R^2,

    v = F / m = 2 V / (1 + m/M + (5 / (2 R^2)) b^2)                  (TP A-30)
    w = Q x F c / I = (5 v / (2 R)) (side (cos(el) z + sin(el) d) + height (z x d))

An elevated cue drives the ball into the cloth at v sin(elevation): the table takes
that away through the ball's centre (its impulse is vertical at the contact point, so
it turns nothing) and the ball slides off at v cos(elevation) along d, with a spin
axis out of the table's plane when the side offset and the elevation are both
non-zero: massé, the slip has a part across d and the slide curves (a parabola,
billiards.physics.spin.motion).

Squirt (TP A-31): the tip's end mass m_e is pushed aside by an off-centre hit, so the
ball leaves at an angle a away from the side struck,

    tan a = (5/2) x sqrt(1 - x^2) / (1 + m/m_e + (5/2) (1 - x^2)),   x = side,

and the whole strike (velocity and spin) is turned by a about the vertical, as if the
cue had been aimed a away (pooltool turns the velocity alone, which leaves a natural-roll
stroke with english slipping; turning both keeps it rolling).

A real bed returns part of the downward speed: with the ball-table restitution e_t
(pooltool's default, 0.5) the ball leaves the cloth at e_t v sin(elevation) and rises
h = (e_t v sin(el))^2 / (2 g). A hop lower than a radius keeps the ball's centre below
the top of any ball it meets (it cannot pass over one) and is left out, as it always
was: the ball stays on the cloth. A stroke whose hop would reach a radius is a jump shot
(`jumps`, `jump_height`, `JUMP_LIMIT`): its scene's run lets balls fly (issue 45:
billiards.simulation gives the physics each ball's drive_down, and the compiled loop's
bed.jump_launch takes this Strike's velocity, spin and drive_down to the ball's launch
off the bed, then flies it: billiards.physics.compiled.airborne).

The bottom floor, beside billiards.rules.pocket_rule: the scene reader checks strokes with
it and fills each struck ball's velocity and spin from it, standard library only. It
uses only arithmetic IEEE 754 fixes (+ - * / and sqrt, in written order; its sine and
cosine are polynomials below), so a stroke gives the same bits on every machine
(tests/physics/test_machine_independence.py reads this file).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from billiards.rules import seed

# A hop that would lift the ball by this many radii or more is a jump (see above).
JUMP_LIMIT = 1.0

_DEGREE = 3.141592653589793 / 180.0  # rad per degree, one rounding


def sin_cos_degrees(angle: float) -> tuple[float, float]:
    """(sin, cos) of `angle` in degrees from + - * / only, the same bits everywhere.

    Reduced to [0, 45] degrees exactly (a remainder by 360 is exact, but for a negative
    angle Python then adds 360, one rounding; subtracting a multiple of 90 from a
    number at least that multiple is exact by Sterbenz's lemma), then Taylor series to
    x^17 / 17! and x^18 / 18! in Horner form (|x| <= pi/4: the first term left out is
    below 2e-19). Within 1e-15 of libm's on [0, 90] degrees (tests/test_cue_strike.py);
    0, 90, 180 and 270 degrees give exact 0 and 1."""
    turn = angle % 360.0  # in [0, 360], 360 only for a negative angle within an ulp of 0
    quadrant = int(turn // 90.0)
    rest = turn - 90.0 * quadrant
    swapped = rest > 45.0
    if swapped:
        rest = 90.0 - rest  # exact: 45 < rest < 90
    x = rest * _DEGREE
    x2 = x * x
    sine = 1.0
    cosine = 1.0
    for n in (17, 15, 13, 11, 9, 7, 5, 3):  # sin x = x (1 - x^2/(2*3) (1 - x^2/(4*5) ...))
        sine = 1.0 - x2 / float(n * (n - 1)) * sine
    for n in (18, 16, 14, 12, 10, 8, 6, 4, 2):  # cos x = 1 - x^2/(1*2) (1 - x^2/(3*4) ...)
        cosine = 1.0 - x2 / float(n * (n - 1)) * cosine
    sine = x * sine
    if swapped:
        sine, cosine = cosine, sine
    # 0.0 - y, not -y: a zero stays +0.0.
    return (
        (sine, cosine),
        (cosine, 0.0 - sine),
        (0.0 - sine, 0.0 - cosine),
        (0.0 - cosine, sine),
    )[quadrant % 4]


@dataclass(frozen=True)
class Stroke:
    """A cue's stroke on one ball, as the scene gives it."""

    speed: float  # m/s, the cue's speed at impact
    direction: float = 0.0  # degrees in the table's plane from +x, counterclockwise
    elevation: float = 0.0  # degrees above the cloth, in [0, 90)
    tip: tuple[float, float] = (0.0, 0.0)  # (side, height) / R across the cue's axis
    mass: float = seed.STICK_MASS  # kg, the cue's
    end_mass: float = seed.STICK_END_MASS  # kg, the tip end's effective mass (squirt)


@dataclass(frozen=True)
class Strike:
    """What a stroke gives the ball on the cloth."""

    velocity: tuple[float, float]  # m/s, on the cloth
    spin: tuple[float, float, float]  # rad/s, world axes, z up
    ball_speed: float  # m/s, |v| along the cue's axis just after the impulse (TP A-30)
    squirt: tuple[float, float]  # (sin a, cos a): the ball's path turned by a, + = left
    drive_down: float  # m/s, the speed at which the cue drives the ball into the cloth


def strike(stroke: Stroke, ball_mass: float, radius: float) -> Strike:
    """The ball's velocity and spin after the cue's impulse and the table's (see the
    module's docstring for the laws and their sources)."""
    side, height = stroke.tip
    offset2 = side * side + height * height  # b^2 / R^2
    speed = 2.0 * stroke.speed / (1.0 + ball_mass / stroke.mass + 2.5 * offset2)  # TP A-30
    sin_el, cos_el = sin_cos_degrees(stroke.elevation)
    sin_dir, cos_dir = sin_cos_degrees(stroke.direction)
    # Squirt (TP A-31): tan a = (5/2) x sqrt(1 - x^2) / (1 + m/m_e + (5/2)(1 - x^2)).
    across = 1.0 - side * side
    rise = 2.5 * side * math.sqrt(across)
    run = 1.0 + ball_mass / stroke.end_mass + 2.5 * across
    tan_a = rise / run  # run >= 1: no overflow for any end mass
    secant = math.sqrt(1.0 + tan_a * tan_a)
    sin_a, cos_a = tan_a / secant, 1.0 / secant
    # The ball's direction d: the cue's, turned by a (left for a hit right of centre).
    dx = cos_dir * cos_a - sin_dir * sin_a
    dy = sin_dir * cos_a + cos_dir * sin_a
    along_x, along_y = speed * dx, speed * dy  # v d, the impulse's level part over m / cos
    velocity = (along_x * cos_el, along_y * cos_el)  # the table took v sin(el) away
    scale = 5.0 / (2.0 * radius)
    # w = (5 / (2R)) (height (z x v d) + side v (cos(el) z + sin(el) d)); with |v_level| =
    # v cos(el) the vertical part is written as `tip_spin` writes it, so that a level
    # stroke gives its spin to the bit (tests/test_cue_strike.py).
    by_height = scale * height
    by_side = scale * side
    tilt = by_side * sin_el
    level_speed = math.sqrt(velocity[0] * velocity[0] + velocity[1] * velocity[1])
    spin = (
        -along_y * by_height + along_x * tilt,
        along_x * by_height + along_y * tilt,
        level_speed * by_side,
    )
    return Strike(
        velocity=velocity,
        spin=spin,
        ball_speed=speed,
        squirt=(sin_a, cos_a),
        drive_down=speed * sin_el,
    )


def jumps(
    drive_down: float,
    gravity: float,
    radius: float,
    restitution: float = seed.TABLE_RESTITUTION,
) -> bool:
    """Whether a ball driven into the bed at `drive_down` jumps: it would rise a radius
    or more (JUMP_LIMIT), so it flies (issue 45; billiards.physics.compiled.airborne)."""
    return jump_height(drive_down, gravity, restitution) >= JUMP_LIMIT * radius


def jump_height(
    drive_down: float, gravity: float, restitution: float = seed.TABLE_RESTITUTION
) -> float:
    """m: how high the ball would rise off the cloth, driven into it at `drive_down`,
    if the bed returned `restitution` of that speed (its e_t: seed.TABLE_RESTITUTION
    unless the scene's physics.table_restitution)."""
    rebound = restitution * drive_down
    if rebound == 0:
        return 0.0
    return rebound * rebound / (2.0 * gravity) if gravity > 0 else math.inf
