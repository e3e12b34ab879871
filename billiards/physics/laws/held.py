"""Held contacts: a ball pressed by its own slip into what it touches (a cushion, a
jaw, a touching neighbour) at no normal speed relative to it (docs/touching.md,
section 6).

A sliding ball's friction a = -mu_s g u_hat follows its slip u = v + R (-w_y, w_x), so
a slip with a part -u_n along the unit normal `into` (towards the holder) drives the
ball into it. A rigid holder answers with a normal force for as long as that lasts,
which turns the slip and is not closed form. Both laws here jump to where that ends,
the slip's normal part gone (u_n = 0), so the ball's own acceleration no longer
presses it, and neither raises the energy:

- hold: the ball turns in place against the holder (its normal velocity stays the
  holder's, V_n, and the cloth's friction takes the slip's normal part through the
  spin alone). Momentum is unchanged; the energy falls when |V_n| <= |s_n|, s_n the
  spin's part of the slip (always at a cushion or a jaw, V_n = 0);
- push: a ball running into the neighbour it touches (the front ball of a pair moving
  together, sliding and so slowing faster than its follower): the pair ends its pushed
  phase at once, moving on together at one normal speed with neither ball's slip left
  along the normal: each ball takes a cloth friction impulse C_k along the normal (the
  classic slide-to-roll split, dv = C / m, ds = 5/2 C / m) and the two a plastic normal
  impulse; momentum fixes the speed, V = sum m_k (v_k - 2/5 s_k) / (7/5 sum m_k), the
  pair's own rolling speed. The energy falls; the pair's momentum changes by C_1 + C_2,
  from the cloth;
- wedge: a ball held twice at one instant (between a cushion and a neighbour, or two
  neighbours) turns in place until its whole slip is gone: it rolls at its velocity.
  Holding it by each in turn would only shrink the slip by the cosine between the
  normals each time, at one instant, without end.
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
    moving at `holder_speed` along it: its normal velocity becomes the holder's, and
    its spin the one that leaves no normal slip. Returns (velocity', spin')."""
    along = np.array([-into[1], into[0]])  # z x into; the slip's spin part is -R w.along
    held_velocity = velocity + (holder_speed - float(dot(velocity, into))) * into
    held_spin = np.array(spin, dtype=np.float64)
    held_spin[:2] = spin[:2] + (holder_speed / radius - float(dot(spin[:2], along))) * along
    return held_velocity, held_spin


def push(
    velocities: FloatArray, spins: FloatArray, masses: FloatArray, into: FloatArray, radius: float
) -> tuple[FloatArray, FloatArray] | None:
    """Two touching balls (rows of velocities (2, 2), spins (2, 3), masses (2,)), the first
    pressed by its slip along `into` (from the first to the second) into the second,
    which it pushes: both leave at the one normal speed V with no normal slip, the
    tangential parts as they were. Returns (velocities', spins'), or None where the
    first would not press the second (the contact impulse would pull)."""
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
    wedged[0] = -velocity[1] / radius
    wedged[1] = velocity[0] / radius
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
    """Two touching balls (rows of velocities (2, 2), spins (2, 3), masses (2,); `normal`
    from the second to the first) moving together, which their accelerations press
    although no slip of theirs drives one into the other: a rolling ball slowing (mu_r g)
    into one that slides along the pair's tangent. The real pushed phase (the slider's
    friction, turned by the push, drives both) is not closed form; this jumps over it in
    steps: the pair parts at `apart` along the normal (an internal impulse J, momentum
    kept, costing 1/2 mu (apart^2 - w_n^2) <= 1/2 mu apart^2 of energy, mu the reduced
    mass), paid by the cloth's friction on the sliding `payer` row: an impulse c against
    its slip u at its contact with the cloth (dv = -c/m u_hat, du = -7/2 c/m u_hat), which
    dissipates c |u| - 7/4 c^2 / m. c is the least that pays; a slip too small to pay
    ends (c = 2/7 m |u|) and the pair parts as fast as that pays for. The energy never
    rises; the pair's momentum changes by the cloth's impulse. Returns (velocities',
    spins')."""
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
    """The row (of 2) that pays for `part`: the sliding ball, or of two the one that
    slips faster (the first on a tie)."""
    if not (sliding[0] and sliding[1]):
        return 0 if sliding[0] else 1
    slips = norm(_slips(velocities, spins, radius))
    return 0 if slips[0] >= slips[1] else 1


def _slips(velocities: FloatArray, spins: FloatArray, radius: float) -> FloatArray:
    """Each row's slip, the velocity of its contact with the cloth: v + R (-w_y, w_x)."""
    return np.stack(
        (velocities[:, 0] - radius * spins[:, 1], velocities[:, 1] + radius * spins[:, 0]), axis=1
    )
