"""The bed's bounce: a ball meeting the cloth from above, and the jump stroke.

An instantaneous impact at the contact point c = (0, 0, -R) below the centre. The
normal impulse is vertical, through the centre (it turns nothing); with the ball-table
restitution e_t (pooltool's e_t, 0.5 by default: Dr. Dave's figure)

    v_z' = -e_t v_z,   J_n = (1 + e_t) m |v_z|.

Frictionless: that is all (pooltool's frictionless_inelastic). Frictional (Alciatore's
TP A-14, "Ball-table impact with friction", as pooltool's frictional_inelastic applies
it): the contact slips at u = v_xy + w x (0, 0, -R) = (v_x - R w_y, v_y + R w_x), and a
friction impulse F = -f m u_hat acts at c. For a solid sphere (I = 2/5 m R^2) it changes
the slip by (1/m + R^2/I) F = (7/2) F / m along u_hat, so the impulse that ends the slip
is 2/7 m |u|, and Coulomb's law bounds it by mu_t J_n:

    f = min(mu_t (1 + e_t) |v_z|, (2/7) |u|)                              (TP A-14)
    v_xy' = v_xy - f u_hat,   w' = w + (5 / (2R)) f (z x u_hat)

(the arm's torque c x F over I). Friction never reverses the slip (f <= 2/7 |u|), so the
energy never rises: it loses f (|u| - (7/4) f) m to friction, (1 - e_t^2) m v_z^2 / 2 to
the bed.
"""

from __future__ import annotations

import math

from billiards.physics.compiled.airborne.flight import Vector3
from billiards.physics.compiled.arithmetic import py_min
from billiards.physics.compiled.jit import kernel

Vector2 = tuple[float, float]


@kernel
def bed_frictionless(velocity: Vector3, spin: Vector3, restitution: float) -> Vector3:
    """v_z' = -e_t v_z for a ball coming down (v_z < 0); the rest passes, as does a ball
    not coming down (v_z >= 0: no impact)."""
    if not velocity[2] < 0:
        return velocity
    return (velocity[0], velocity[1], (0.0 - restitution) * velocity[2])


@kernel
def bed_frictional(
    velocity: Vector3, spin: Vector3, radius: float, restitution: float, friction: float
) -> tuple[Vector3, Vector3]:
    """Velocity and spin just after the bed's impact with friction mu_t (the module's
    docstring: TP A-14). Without slip or friction, the frictionless law to the bit."""
    bounced = bed_frictionless(velocity, spin, restitution)
    vx, vy, vz = velocity
    if not vz < 0:
        return bounced, spin
    slip_x = vx - radius * spin[1]  # u = v + w x (0, 0, -R)
    slip_y = vy + radius * spin[0]
    slip = math.sqrt(slip_x * slip_x + slip_y * slip_y)
    bound = friction * ((1.0 + restitution) * (0.0 - vz))
    if not (slip > 0 and bound > 0):
        return bounced, spin
    share = py_min(bound, (2.0 / 7.0) * slip) / slip  # f / |u|
    turn = 2.5 * share / radius  # (5 / (2R)) f / |u|
    after = (vx - share * slip_x, vy - share * slip_y, bounced[2])
    # z x u_hat = (-u_y, u_x, 0) / |u|: the friction turns w_xy only.
    turned = (spin[0] - turn * slip_y, spin[1] + turn * slip_x, spin[2])
    return after, turned


@kernel
def jump_launch(
    cloth_velocity: Vector2,
    spin: Vector3,
    drive_down: float,
    radius: float,
    restitution: float,
    friction: float,
) -> tuple[Vector3, Vector3]:
    """The ball's velocity and spin as it leaves the bed after an elevated cue's strike.

    The cue's impulse (TP A-30, with squirt, TP A-31: billiards.scene.stroke.strike)
    leaves the ball moving at v along the cue's axis: v cos(el) d on the cloth (the
    Strike's velocity) and drive_down = v sin(el) into it; the bed then takes that
    vertical speed as any impact (bed_frictional; friction 0: bed_frictionless), so the
    ball leaves at e_t v sin(el) (pooltool's 3D instantaneous_point strike followed by
    its ball-table law). drive_down 0 (a level cue): no impact, the ball stays on the
    cloth with the strike's velocity and spin to the bit."""
    velocity = (cloth_velocity[0], cloth_velocity[1], 0.0 - drive_down)
    if not drive_down > 0:
        return (cloth_velocity[0], cloth_velocity[1], 0.0), spin
    return bed_frictional(velocity, spin, radius, restitution, friction)
