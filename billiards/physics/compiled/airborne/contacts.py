"""Contact times in 3D for a ball in the air (its centre a parabola, flight.py).

With a ball: two centres on uniformly accelerated paths, p_i(t) = p_i + v_i t + a_i t^2
/ 2 (a flying ball's a = (0, 0, -g); one on the cloth has z = R and the spin model's
constant acceleration in the plane), are d(t) = D + W t + K t^2 apart, D = p1 - p2, W =
v1 - v2, K = (a1 - a2) / 2, so contact is the first time the quartic

    f(t) = |d(t)|^2 - (2R)^2 = K.K t^4 + 2 W.K t^3 + (W.W + 2 D.K) t^2 + 2 D.W t + D.D - 4R^2

falls to zero: the rolling model's separation quartic (rolling.contact_times.
separation_quartic) with a third term in each dot product, added last (x, y, then z:
with z's terms 0 it is the plane's quartic to the bit), and its root found as every
contact's is (compiled.roots.first_downward_root: the Bernstein certificate, Newton to
rounding from the positive side).

With a cushion: the cushion is the region beyond the wall's plane and below its nose,
at the cushion height h; a ball's centre touches it on the face (its distance across the
wall's plane R, below h), on the nose (within R of the nose's line, above h: a cylinder
along the wall), or it passes over the nose line (across = 0, higher than h + R) and
leaves the table. In flight `across` (the centre's distance from the wall's plane, into
the table) is linear in t and z a parabola, so the face and the crossing are linear roots
and the nose the quartic

    across(t)^2 + (z(t) - h)^2 - R^2 = 0

(the same separation quartic, in the plane across the wall). The first of these in time
is the contact: a nose root below h comes after the face's, a crossing under h + R after
the nose's (the Minkowski sum of the cushion and the ball is entered first through them).
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.airborne.flight import Vector3
from billiards.physics.compiled.arithmetic import np_maximum
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.roots import EPS, first_downward_root

Quartic = tuple[float, float, float, float, float]
Path3 = tuple[Vector3, Vector3, Vector3]  # (position, velocity, acceleration)

NO_CONTACT, FACE, NOSE, OVER_THE_RAIL = 0, 1, 2, 3  # what a flying ball meets at a wall


@kernel
def separation_quartic(
    gap: Vector3, closing: Vector3, curving: Vector3, reach_squared: float
) -> tuple[Quartic, float]:
    """|D + W t + K t^2|^2 - reach^2 by powers of t, lowest first, and |W|^2: gap D,
    closing W, curving K (separation_quartic's order, z's terms added last)."""
    dx, dy, dz = gap
    wx, wy, wz = closing
    kx, ky, kz = curving
    speed_squared = (wx * wx + wy * wy) + wz * wz
    quartic = (
        ((dx * dx + dy * dy) + dz * dz) - reach_squared,
        2.0 * ((dx * wx + dy * wy) + dz * wz),
        speed_squared + 2.0 * ((dx * kx + dy * ky) + dz * kz),
        2.0 * ((wx * kx + wy * ky) + wz * kz),
        (kx * kx + ky * ky) + kz * kz,
    )
    return quartic, speed_squared


@kernel
def flying_path(position: Vector3, velocity: Vector3, gravity: float) -> Path3:
    """A ball in the air as a path: acceleration (0, 0, -g)."""
    return position, velocity, (0.0, 0.0, 0.0 - gravity)


@kernel
def cloth_path(
    position: tuple[float, float],
    velocity: tuple[float, float],
    acceleration: tuple[float, float],
    radius: float,
) -> Path3:
    """A ball on the cloth (the spin model's state: constant acceleration in the plane)
    as a path in 3D: its centre at height R."""
    return (
        (position[0], position[1], radius),
        (velocity[0], velocity[1], 0.0),
        (acceleration[0], acceleration[1], 0.0),
    )


@kernel
def pair_quartic(first: Path3, second: Path3, radius: float) -> tuple[Quartic, float]:
    """The pair's separation quartic (the module's docstring) and |W|^2, in the compiled
    rolling model's order (K = a1 / 2 - a2 / 2)."""
    (p1, v1, a1), (p2, v2, a2) = first, second
    gap = (p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2])
    closing = (v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2])
    curving = (
        a1[0] * 0.5 - a2[0] * 0.5,
        a1[1] * 0.5 - a2[1] * 0.5,
        a1[2] * 0.5 - a2[2] * 0.5,
    )
    return separation_quartic(gap, closing, curving, 4.0 * radius * radius)


@kernel
def ball_contact_time(
    first: Path3,
    second: Path3,
    sizes: tuple[float, float],
    horizon: float,
    parting: bool,
    bernstein: tuple[np.ndarray, np.ndarray],
) -> float:
    """Seconds until two balls on these paths touch, within [0, horizon] (inf if not):
    sizes = (R, the positions' size, the largest coordinate, for the rounding level of
    f'(0) as the rolling model's rounding_levels); parting: only a return counts."""
    radius, size = sizes
    quartic, speed_squared = pair_quartic(first, second, radius)
    reach = 2.0 * radius
    touching = (reach * reach) * 1e-12
    level = 32.0 * EPS * size * math.sqrt(speed_squared)
    # A flying ball's pair is no spin-model pair on the cloth: no hair's-breadth rule.
    return first_downward_root(quartic, horizon, touching, parting, level, False, bernstein)


@kernel
def nose_quartic(
    across: tuple[float, float], rise: tuple[float, float], gravity: float, nose: float
) -> tuple[Quartic, float]:
    """across(t)^2 + (z(t) - h)^2 - R^2 for a flying ball: across = (distance from the
    wall's plane, its rate), rise = (z - h, v_z); nose = R (the module's docstring)."""
    gap = (across[0], rise[0], 0.0)
    closing = (across[1], rise[1], 0.0)
    curving = (0.0, -0.5 * gravity, 0.0)
    return separation_quartic(gap, closing, curving, nose * nose)


@kernel
def linear_time(distance: float, rate: float) -> float:
    """When distance + rate t reaches 0 going down (t >= 0), inf if it does not."""
    if not rate < 0:
        return math.inf
    return np_maximum(distance, 0.0) / (0.0 - rate)


@kernel
def cushion_contact_in_flight(
    across: tuple[float, float],
    height: tuple[float, float],
    shape: tuple[float, float, float],
    horizon: float,
    bernstein: tuple[np.ndarray, np.ndarray],
) -> tuple[float, int]:
    """The first of a flying ball's face contact, nose contact and crossing over the rail
    within [0, horizon] (the module's docstring), and which (FACE, NOSE, OVER_THE_RAIL;
    NO_CONTACT with inf). across = (the centre's distance from the wall's plane, into
    the table, and its rate); height = (z, v_z); shape = (R, h, g)."""
    radius, cushion_height, gravity = shape
    z, rise_speed = height
    best, kind = math.inf, NO_CONTACT
    face = linear_time(across[0] - radius, across[1])
    if face <= horizon:
        lift = (z + rise_speed * face) - 0.5 * gravity * (face * face)
        if lift <= cushion_height:
            best, kind = face, FACE
    rise = (z - cushion_height, rise_speed)
    quartic, speed_squared = nose_quartic(across, rise, gravity, radius)
    size = abs(across[0]) + abs(rise[0]) + radius
    level = 32.0 * EPS * size * math.sqrt(speed_squared)
    window = best if best < horizon else horizon
    touching = (radius * radius) * 1e-12
    nose = first_downward_root(quartic, window, touching, False, level, False, bernstein)
    if nose < best:
        lift = (z + rise_speed * nose) - 0.5 * gravity * (nose * nose)
        if lift >= cushion_height:
            best, kind = nose, NOSE
    crossing = linear_time(across[0], across[1])
    if crossing < best and crossing <= horizon:
        best, kind = crossing, OVER_THE_RAIL
    return best, kind
