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
  together, sliding and so slowing faster than its follower): the cloth's friction
  impulse J along the normal (the classic slide-to-roll split, dv = J / m, ds = 5/2 J / m)
  and a plastic normal impulse between the two, sized so that u_n = 0 after both. The
  pair moves on together at the common normal speed a rigid pair would reach (within a
  few per cent of integrating the pushed phase); the energy falls (m u_n^2 / 6 for equal
  masses); the pair's momentum changes by J, from the cloth;
- wedge: a ball held twice at one instant (between a cushion and a neighbour, or two
  neighbours) turns in place until its whole slip is gone: it rolls at its velocity.
  Holding it by each in turn would only shrink the slip by the cosine between the
  normals each time, at one instant, without end.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.arithmetic import dot
from billiards.physics.motion import FloatArray


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
    velocity: FloatArray,
    spin: FloatArray,
    mass: float,
    other: FloatArray,
    other_mass: float,
    into: FloatArray,
    radius: float,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A sliding ball (velocity, spin, mass) pressed along `into` into a neighbour
    (velocity `other`, `other_mass`) it pushes: (velocity', spin', other's velocity')."""
    along = np.array([-into[1], into[0]])
    normal_speed = float(dot(velocity, into))
    slip = normal_speed - radius * float(dot(spin[:2], along))  # u_n, below zero here
    apart = normal_speed - float(dot(other, into))  # rounding-level
    share = other_mass / (mass + other_mass)
    # u_n + 7/2 J/m - share (apart + J/m) = 0: the cloth's impulse per unit mass.
    cloth = (share * apart - slip) / (3.5 - share)
    velocity = velocity + cloth * into
    spin = np.array(spin, dtype=np.float64)
    spin[:2] = spin[:2] - (2.5 * cloth / radius) * along
    # The plastic part: both leave at one normal speed, momentum between them kept.
    closing = apart + cloth
    return velocity - (share * closing) * into, spin, other + (closing - share * closing) * into


def wedge(velocity: FloatArray, spin: FloatArray, radius: float) -> FloatArray:
    """The spin (3,) of a ball (velocity (2,)) with no slip left: w_xy = z x v / R."""
    wedged = np.array(spin, dtype=np.float64)
    wedged[0] = -velocity[1] / radius
    wedged[1] = velocity[0] / radius
    return wedged
