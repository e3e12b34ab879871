"""Entries that run rows of inputs through the airborne kernels, one row an item, for the
tests and the machine-independence digest (an inner kernel has no wrapper for Python;
one call for thousands of rows costs one crossing into the compiled code).

Each takes a C-contiguous float64 array (N, k), its columns as the docstring lists, and
returns an array (N, m).
"""

from __future__ import annotations

import numpy as np

from billiards.physics.compiled.airborne.ball_ball import (
    frictionless_impulse_3d,
    line_of_centres_3d,
)
from billiards.physics.compiled.airborne.bed import bed_frictional, jump_launch
from billiards.physics.compiled.airborne.bounces import (
    bounce_count,
    bounce_sequence,
    settle_speed,
)
from billiards.physics.compiled.airborne.contacts import (
    ball_contact_time,
    cushion_contact_in_flight,
    pair_quartic,
)
from billiards.physics.compiled.airborne.flight import (
    flight_position,
    flight_velocity,
    landing_time,
)
from billiards.physics.compiled.jit import entry


@entry
def flights(rows: np.ndarray) -> np.ndarray:
    """Columns p (3), v (3), g, t -> p(t) (3), v(t) (3)."""
    out = np.empty((len(rows), 6))
    for index in range(len(rows)):
        row = rows[index]
        position, velocity = (row[0], row[1], row[2]), (row[3], row[4], row[5])
        at = flight_position(position, velocity, row[6], row[7])
        moving = flight_velocity(velocity, row[6], row[7])
        out[index, 0], out[index, 1], out[index, 2] = at
        out[index, 3], out[index, 4], out[index, 5] = moving
    return out


@entry
def landings(rows: np.ndarray) -> np.ndarray:
    """Columns z - R, v_z, g -> the landing time."""
    out = np.empty(len(rows))
    for index in range(len(rows)):
        out[index] = landing_time(rows[index, 0], rows[index, 1], rows[index, 2])
    return out


@entry
def bed_impacts(rows: np.ndarray) -> np.ndarray:
    """Columns v (3), w (3), R, e_t, mu_t -> v' (3), w' (3) (bed_frictional)."""
    out = np.empty((len(rows), 6))
    for index in range(len(rows)):
        row = rows[index]
        velocity, spin = (row[0], row[1], row[2]), (row[3], row[4], row[5])
        after, turned = bed_frictional(velocity, spin, row[6], row[7], row[8])
        out[index, 0], out[index, 1], out[index, 2] = after
        out[index, 3], out[index, 4], out[index, 5] = turned
    return out


@entry
def jumps(rows: np.ndarray) -> np.ndarray:
    """Columns v_xy (2), w (3), drive_down, R, e_t, mu_t -> v (3), w (3) (jump_launch)."""
    out = np.empty((len(rows), 6))
    for index in range(len(rows)):
        row = rows[index]
        spin = (row[2], row[3], row[4])
        after, turned = jump_launch((row[0], row[1]), spin, row[5], row[6], row[7], row[8])
        out[index, 0], out[index, 1], out[index, 2] = after
        out[index, 3], out[index, 4], out[index, 5] = turned
    return out


@entry
def bounce_counts(rows: np.ndarray) -> np.ndarray:
    """Columns landing speed, e_t, g, settle height -> the number of flights."""
    out = np.empty(len(rows), dtype=np.int64)
    for index in range(len(rows)):
        row = rows[index]
        out[index] = bounce_count(row[0], row[1], settle_speed(row[3], row[2]))
    return out


@entry
def bounce_sequences(rows: np.ndarray) -> np.ndarray:
    """Columns v (3), w (3), R, e_t, mu_t, g, settle height -> flights, air time,
    carried (2), v (3), w (3) at the last landing (bounce_sequence)."""
    out = np.empty((len(rows), 10))
    for index in range(len(rows)):
        row = rows[index]
        velocity, spin = (row[0], row[1], row[2]), (row[3], row[4], row[5])
        laws = (row[6], row[7], row[8])
        lowest_launch = settle_speed(row[10], row[9])
        count, air, carried, after, turned = bounce_sequence(
            velocity, spin, laws, row[9], lowest_launch
        )
        out[index, 0], out[index, 1] = count, air
        out[index, 2], out[index, 3] = carried
        out[index, 4], out[index, 5], out[index, 6] = after
        out[index, 7], out[index, 8], out[index, 9] = turned
    return out


@entry
def ball_contacts(rows: np.ndarray, bernstein: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Columns p1, v1, a1, p2, v2, a2 (3 each), R, size, horizon, parting (0 or 1) ->
    the contact time and the quartic's five coefficients, lowest_launch power first."""
    out = np.empty((len(rows), 6))
    for index in range(len(rows)):
        row = rows[index]
        first = ((row[0], row[1], row[2]), (row[3], row[4], row[5]), (row[6], row[7], row[8]))
        second = (
            (row[9], row[10], row[11]),
            (row[12], row[13], row[14]),
            (row[15], row[16], row[17]),
        )
        sizes = (row[18], row[19])
        parting = row[21] != 0
        out[index, 0] = ball_contact_time(first, second, sizes, row[20], parting, bernstein)
        quartic, _ = pair_quartic(first, second, row[18])
        for power in range(5):
            out[index, 1 + power] = quartic[power]
    return out


@entry
def cushion_contacts(rows: np.ndarray, bernstein: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Columns across, its rate, z, v_z, R, h, g, horizon -> the time and its kind
    (contacts.FACE, NOSE, OVER_THE_RAIL; NO_CONTACT)."""
    out = np.empty((len(rows), 2))
    for index in range(len(rows)):
        row = rows[index]
        shape = (row[4], row[5], row[6])
        time, kind = cushion_contact_in_flight(
            (row[0], row[1]), (row[2], row[3]), shape, row[7], bernstein
        )
        out[index, 0], out[index, 1] = time, kind
    return out


@entry
def ball_impacts(rows: np.ndarray) -> np.ndarray:
    """Columns p1 (3), p2 (3), v1 (3), m1, v2 (3), m2, e -> v1' (3), v2' (3), approach
    (frictionless_impulse_3d along line_of_centres_3d)."""
    out = np.empty((len(rows), 7))
    for index in range(len(rows)):
        row = rows[index]
        normal = line_of_centres_3d((row[0], row[1], row[2]), (row[3], row[4], row[5]))
        v1, v2 = (row[6], row[7], row[8]), (row[10], row[11], row[12])
        first, second, approach = frictionless_impulse_3d(normal, v1, row[9], v2, row[13], row[14])
        out[index, 0], out[index, 1], out[index, 2] = first
        out[index, 3], out[index, 4], out[index, 5] = second
        out[index, 6] = approach
    return out
