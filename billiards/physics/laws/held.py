"""Held contacts: a ball pressed by its own slip into what it touches (a cushion, a
jaw, a touching neighbour) at no normal speed relative to it (docs/touching.md, 6).

A sliding ball's friction follows its slip u = v + R (-w_y, w_x), so a slip with a part
along the normal `into` drives the ball into the holder, whose normal force would turn
the slip for as long as that lasts (not closed form). These laws jump to where it ends,
the slip's normal part gone, and none raises the energy:

- hold: the ball turns in place against the holder (its normal velocity the holder's,
  V_n; the cloth takes the slip's normal part through the spin). Momentum is kept;
- push: a sliding front ball of a pair moving together pushes the other: both take a
  cloth impulse C_k along the normal (dv = C / m, ds = 5/2 C / m) and a plastic normal
  impulse, leaving at V = sum m_k (v_k - 2/5 s_k) / (7/5 sum m_k) with no normal slip;
- wedge: a ball held twice at one instant turns in place until its whole slip is gone
  (held by each in turn, its slip would shrink without end at one instant).
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.numerics.arithmetic import dot, length, norm
from billiards.physics.numerics.arrays import BoolArray, FloatArray


def hold(
    velocity: FloatArray, spin: FloatArray, into: FloatArray, holder_speed: float, radius: float
) -> tuple[FloatArray, FloatArray]:
    """A ball (velocity (2,), spin (3,)) held by what it presses into along `into`,
    moving at `holder_speed` along it: (velocity', spin') with no normal slip."""
    along = np.array([-into[1], into[0]])  # z x into; the slip's spin part is -R w.along
    held_velocity = velocity + (holder_speed - float(dot(velocity, into))) * into
    held_spin = np.array(spin, dtype=np.float64)
    held_spin[:2] = spin[:2] + (holder_speed / radius - float(dot(spin[:2], along))) * along
    return held_velocity, held_spin


def push(
    velocities: FloatArray, spins: FloatArray, masses: FloatArray, into: FloatArray, radius: float
) -> tuple[FloatArray, FloatArray] | None:
    """Two touching balls (rows of 2), the first pressed by its slip along `into` into the
    second: (velocities', spins') at one normal speed with no normal slip, or None
    where the contact impulse would pull."""
    along = np.array([-into[1], into[0]])
    normal_speeds = dot(velocities, into)  # broadcasts: each row against `into`
    # The spin's part of each slip along `into`: -R w.along.
    spin_slips = -radius * dot(spins[:, :2], along)
    # Cloth impulses C_k = 2/5 m_k (-V - s_k) leave u_k = V + s_k' = 0, and momentum
    # m1 v1 + m2 v2 + C_1 + C_2 = (m1 + m2) V fixes V.
    rolled = masses * (normal_speeds - 0.4 * spin_slips)
    common = (rolled[0] + rolled[1]) / (1.4 * (masses[0] + masses[1]))
    # The contact's impulse on the first, m1 (v1 - 2/5 s1 - 7/5 V), must push it back.
    if rolled[0] - 1.4 * masses[0] * common < 0:
        return None
    pushed = velocities + (common - normal_speeds)[:, None] * into
    turned = np.array(spins, dtype=np.float64)
    turned[:, :2] = spins[:, :2] + ((common / radius) - dot(spins[:, :2], along))[:, None] * along
    return pushed, turned


def wedge(velocity: FloatArray, spin: FloatArray, radius: float) -> FloatArray:
    """The spin (3,) of a ball (velocity (2,)) with no slip left: w_xy = z x v / R."""
    wedged = np.array(spin, dtype=np.float64)
    wedged[0], wedged[1] = -velocity[1] / radius, velocity[0] / radius
    return wedged


def part(
    velocities: FloatArray,
    spins: FloatArray,
    masses: FloatArray,
    normal: FloatArray,
    payer: int,
    radius: float,
    apart: float,
) -> tuple[FloatArray, FloatArray]:
    """Two touching balls (rows of 2; `normal` from the second to the first) moving
    together, pressed though no slip drives one into the other (a rolling ball slowing
    into one sliding along the tangent): the pair parts at `apart` along the normal (an
    internal impulse, momentum kept, costing at most 1/2 mu apart^2, mu the reduced
    mass), paid by the cloth's friction on the sliding `payer`: an impulse c against its
    slip u (dv = -c/m u_hat, du = -7/2 c/m u_hat) dissipating c |u| - 7/4 c^2 / m, the
    least that pays (a slip too small ends, and pays what it can). The energy never
    rises. Returns (velocities', spins')."""
    parted = np.array(velocities, dtype=np.float64)
    turned = np.array(spins, dtype=np.float64)
    mass = float(masses[payer])
    reduced = float(masses[0] * masses[1] / (masses[0] + masses[1]))
    slip = _slips(parted, turned, radius)[payer]
    slip_speed = length(slip[0], slip[1])
    # c from 7/4 c^2 / m - c |u| + E = 0 (the smaller root), E the most parting can cost,
    # with a margin of 1e-9 against rounding; c = 2/7 m |u| where the slip cannot pay.
    cost = 0.5 * reduced * apart * apart * (1.0 + 1e-9)
    discriminant = slip_speed * slip_speed - 7.0 * cost / mass
    if discriminant < 0:
        apart = math.sqrt(2.0 * mass * slip_speed * slip_speed / (7.0 * reduced)) / (1.0 + 1e-6)
        discriminant = 0.0
    paid = (slip_speed - math.sqrt(discriminant)) * mass / 3.5
    if slip_speed > 0:
        change = (paid / mass / slip_speed) * slip  # dv = c/m u_hat, taken away
        parted[payer] = parted[payer] - change
        # du = 7/2 dv: the spin's part of the slip, R (-w_y, w_x), takes 5/2 dv.
        turned[payer, 0] = turned[payer, 0] - 2.5 * change[1] / radius
        turned[payer, 1] = turned[payer, 1] + 2.5 * change[0] / radius
    parting = float(dot(parted[0] - parted[1], normal))
    if parting < apart:
        impulse = reduced * (apart - parting)
        parted[0] = parted[0] + (impulse / float(masses[0])) * normal
        parted[1] = parted[1] - (impulse / float(masses[1])) * normal
    return parted, turned


def payer_of(velocities: FloatArray, spins: FloatArray, sliding: BoolArray, radius: float) -> int:
    """The row (of 2) that pays for `part`: the sliding one, or the faster slipping."""
    if not (sliding[0] and sliding[1]):
        return 0 if sliding[0] else 1
    slips = norm(_slips(velocities, spins, radius))
    return 0 if slips[0] >= slips[1] else 1


def _slips(velocities: FloatArray, spins: FloatArray, radius: float) -> FloatArray:
    """Each row's slip, the velocity of its contact with the cloth: v + R (-w_y, w_x)."""
    return np.stack(
        (velocities[:, 0] - radius * spins[:, 1], velocities[:, 1] + radius * spins[:, 0]), axis=1
    )
