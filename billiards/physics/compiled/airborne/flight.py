"""A ball in the air: its centre on a parabola, its spin constant (no air drag, no
Magnus force: pooltool's airborne state, physics/evolve `_evolve_airborne_state`).

    p(t) = p0 + v0 t + (0, 0, -g t^2 / 2),   v(t) = v0 + (0, 0, -g t),   w(t) = w0

z is up, the cloth the plane z = 0: a ball lies on it with its centre at height R.
"""

from __future__ import annotations

import math

from billiards.physics.compiled.jit import kernel

Vector3 = tuple[float, float, float]


@kernel
def flight_position(position: Vector3, velocity: Vector3, gravity: float, time: float) -> Vector3:
    """p(t) = p0 + v0 t + (0, 0, -g t^2 / 2): the centre `time` s after the launch."""
    drop = 0.5 * gravity * (time * time)
    return (
        position[0] + velocity[0] * time,
        position[1] + velocity[1] * time,
        (position[2] + velocity[2] * time) - drop,
    )


@kernel
def flight_velocity(velocity: Vector3, gravity: float, time: float) -> Vector3:
    """v(t) = v0 + (0, 0, -g t)."""
    return (velocity[0], velocity[1], velocity[2] - gravity * time)


@kernel
def landing_time(height: float, rise_speed: float, gravity: float) -> float:
    """Seconds until the centre is back at height R: the later root of

        (z0 - R) + v_z t - (g / 2) t^2 = 0,   height = z0 - R >= 0, rise_speed = v_z,

    in the stable form (no cancellation; Numerical Recipes 5.6): q = -(b + sign(b)
    sqrt(b^2 - 4ac)) / 2 with a = -g/2, b = v_z, c = z0 - R, and the roots q/a and c/q.
    Rising (b >= 0) the later root is q/a = (v_z + sqrt(v_z^2 + 2 g c)) / g; falling it
    is c/q = 2c / (sqrt(...) - v_z). 0 for a ball on the cloth not rising; without
    gravity inf unless it falls (then c / -v_z)."""
    if not gravity > 0:
        return height / (0.0 - rise_speed) if rise_speed < 0 else math.inf
    if height == 0 and not rise_speed > 0:
        return 0.0
    a = -0.5 * gravity
    discriminant = rise_speed * rise_speed - 4.0 * a * height
    root = math.sqrt(discriminant)
    if rise_speed >= 0:
        q = -0.5 * (rise_speed + root)
        return q / a
    q = -0.5 * (rise_speed - root)
    return height / q


@kernel
def apex_height(rise_speed: float, gravity: float) -> float:
    """How far the centre rises above its launch: v_z^2 / (2 g) (0 when falling)."""
    if not rise_speed > 0:
        return 0.0
    return rise_speed * rise_speed / (2.0 * gravity)
