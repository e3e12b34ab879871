"""Off the cloth (issue 45): the compiled pieces a flying ball needs, each against its
closed form to rounding: the parabola, the landing root, the bed's impact (energy never
rises), the hops (heights e_t^2 apart, the air time its geometric series, the count
finite), the jump stroke (TP A-30/31 with the vertical part kept), and the 3D contact
quartics (their roots substituted back); the same bytes on every CPU target."""

from __future__ import annotations

import math
from decimal import Decimal, localcontext
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from llvmlite import binding

from billiards.physics.compiled.airborne import probe
from billiards.physics.compiled.airborne.bounces import MAX_BOUNCES, SETTLE_HEIGHT
from billiards.physics.compiled.airborne.contacts import FACE, NO_CONTACT, NOSE, OVER_THE_RAIL
from billiards.physics.compiled.roots import BERNSTEIN
from billiards.physics.laws.ball_ball import frictionless_impulse, line_of_centres
from billiards.physics.rolling.contact_times import separation_quartic
from billiards.rules import seed
from billiards.scene.stroke import Stroke, strike
from tests.physics.test_compiled import fresh_digests, host_knows

ROOT = Path(__file__).resolve().parents[2]
EPS = float(np.finfo(np.float64).eps)
R = seed.RADIUS
G = seed.GRAVITY
E_T = seed.TABLE_RESTITUTION
MU_T = seed.SLIDING_FRICTION  # pooltool's ball-table friction: the cloth's sliding mu_s
H = seed.CUSHION_HEIGHT
hard = pytest.mark.hard


def exact(value: float) -> Fraction:
    return Fraction(value)


def energy(velocity: list[float], spin: list[float]) -> Fraction:
    """Kinetic energy over mass, exactly: |v|^2 / 2 + (2/5 R^2) |w|^2 / 2."""
    moving = sum((exact(v) * exact(v) for v in velocity), Fraction(0))
    turning = sum((exact(w) * exact(w) for w in spin), Fraction(0))
    return moving / 2 + Fraction(1, 5) * exact(R) * exact(R) * turning


# --- flight -------------------------------------------------------------------------------


def test_a_flying_ball_follows_the_parabola_to_rounding() -> None:
    rng = np.random.default_rng(1)
    rows = np.column_stack([
        rng.uniform(0, 2, 2 * 500).reshape(500, 2), rng.uniform(R, 0.3, 500),
        rng.uniform(-5, 5, (500, 3)), np.full(500, G), rng.uniform(0, 0.5, 500),
    ])  # fmt: skip
    got = probe.flights(np.ascontiguousarray(rows))
    for row, out in zip(rows.tolist(), got.tolist(), strict=True):
        g, t = exact(row[6]), exact(row[7])
        drop = [Fraction(0), Fraction(0), g * t * t / 2]
        for axis in range(3):
            p = exact(row[axis]) + exact(row[3 + axis]) * t - drop[axis]
            v = exact(row[3 + axis]) - (g * t if axis == 2 else 0)
            scale = abs(row[axis]) + abs(row[3 + axis] * row[7]) + float(drop[axis])
            assert abs(exact(out[axis]) - p) <= 4 * EPS * scale
            assert abs(exact(out[3 + axis]) - v) <= 2 * EPS * (abs(row[3 + axis]) + float(g * t))


def decimal_landing(height: float, rise: float, gravity: float) -> Decimal:
    """The later root of c + b t - (g/2) t^2, to 50 digits."""
    with localcontext() as context:
        context.prec = 50
        c, b, g = Decimal(height), Decimal(rise), Decimal(gravity)
        root = (b * b + 2 * g * c).sqrt()
        # Falling, (b + root) / g cancels even in 50 digits: its equal 2c / (root - b).
        return (b + root) / g if b >= 0 else 2 * c / (root - b)


def test_the_landing_time_is_the_later_root_to_rounding() -> None:
    rng = np.random.default_rng(2)
    rows = np.column_stack([
        rng.uniform(0, 0.5, 2000) * (rng.uniform(size=2000) < 0.9),
        rng.uniform(-6, 6, 2000), rng.uniform(1, 20, 2000),
    ])  # fmt: skip
    # Where the textbook form cancels: a ball just above the cloth, falling or rising fast.
    grazes = [[1e-12, -5.0, G], [1e-9, -0.5, G], [3e-15, 7.0, G], [1e-300, -1.0, G]]
    rows = np.vstack([rows, grazes])
    times = probe.landings(np.ascontiguousarray(rows))
    for (height, rise, gravity), time in zip(rows.tolist(), times.tolist(), strict=True):
        if height == 0 and rise <= 0:
            assert time == 0.0
            continue
        assert abs(Decimal(time) - decimal_landing(height, rise, gravity)) <= Decimal(
            3 * EPS * time
        )
        # Substituted back: the centre at height R, within the rounding of its terms.
        t = exact(time)
        left = exact(height) + exact(rise) * t - exact(gravity) * t * t / 2
        assert abs(left) <= 8 * EPS * (height + abs(rise) * time + gravity * time * time)


def test_a_ball_launched_from_the_cloth_lands_after_2_vz_over_g_exactly() -> None:
    rises = [0.1, 1.0, 1.3, 2.7, 5.5]
    rows = np.array([[0.0, rise, G] for rise in rises])
    assert probe.landings(rows).tolist() == [2.0 * rise / G for rise in rises]


def test_without_gravity_a_ball_lands_only_if_it_falls() -> None:
    rows = np.array([[0.1, 1.0, 0.0], [0.1, -2.0, 0.0], [0.0, 0.0, 0.0]])
    assert probe.landings(rows).tolist() == [math.inf, 0.05, math.inf]


# --- the bed's bounce ---------------------------------------------------------------------


def random_impacts(count: int, seed_value: int, friction: float | None = None) -> np.ndarray:
    """Columns v (3), w (3), R, e_t, mu_t: balls coming down on the bed."""
    rng = np.random.default_rng(seed_value)
    frictions = rng.uniform(0, 1, count) if friction is None else np.full(count, friction)
    rolling = rng.uniform(size=count) < 0.2  # some without slip at all
    velocity = rng.uniform(-5, 5, (count, 3))
    velocity[:, 2] = -rng.uniform(1e-3, 8, count)
    spin = rng.uniform(-200, 200, (count, 3))
    spin[rolling, 0] = -velocity[rolling, 1] / R
    spin[rolling, 1] = velocity[rolling, 0] / R
    laws = np.column_stack([np.full(count, R), rng.uniform(0, 1, count), frictions])
    return np.ascontiguousarray(np.column_stack([velocity, spin, laws]))


def test_the_frictionless_bed_returns_e_t_of_the_vertical_speed_and_nothing_else() -> None:
    rows = random_impacts(1000, 3, friction=0.0)
    after = probe.bed_impacts(rows)
    assert after[:, 2].tolist() == ((0.0 - rows[:, 7]) * rows[:, 2]).tolist()
    assert after[:, [0, 1, 3, 4, 5]].tobytes() == rows[:, [0, 1, 3, 4, 5]].tobytes()


def test_energy_never_rises_at_a_bed_impact() -> None:
    rows = random_impacts(5000, 4)
    after = probe.bed_impacts(rows)
    for row, out in zip(rows.tolist(), after.tolist(), strict=True):
        before, now = energy(row[0:3], row[3:6]), energy(out[0:3], out[3:6])
        assert now <= before * (1 + Fraction(4 * EPS)), row


def test_the_bed_takes_the_vertical_speed_as_the_frictionless_law_does_with_friction() -> None:
    rows = random_impacts(1000, 5)
    assert probe.bed_impacts(rows)[:, 2].tobytes() == ((0.0 - rows[:, 7]) * rows[:, 2]).tobytes()


def slip_of(out: np.ndarray) -> np.ndarray:
    """The contact's slip u = v_xy + w x (0, 0, -R)."""
    return np.column_stack([out[:, 0] - R * out[:, 4], out[:, 1] + R * out[:, 3]])


def test_the_friction_impulse_is_coulombs_or_ends_the_slip() -> None:
    """f = min(mu_t (1 + e_t) |v_z|, 2/7 |u|) against the slip (TP A-14): the slip keeps
    its direction and shrinks by 7/2 f, to zero where the bound allows."""
    rows = random_impacts(3000, 6)
    after = probe.bed_impacts(rows)
    slip_before = slip_of(rows[:, [0, 1, 2, 3, 4, 5]])
    slip_after = slip_of(after)
    change = np.hypot(after[:, 0] - rows[:, 0], after[:, 1] - rows[:, 1])
    coulomb = rows[:, 8] * (1 + rows[:, 7]) * -rows[:, 2]
    speed = np.hypot(slip_before[:, 0], slip_before[:, 1])
    scale = np.hypot(rows[:, 0], rows[:, 1]) + R * np.hypot(rows[:, 3], rows[:, 4])
    expected = np.minimum(coulomb, 2 / 7 * speed)
    assert np.all(np.abs(change - expected) <= 1e-14 * (scale + coulomb))
    ends = coulomb > 2 / 7 * speed
    remaining = np.hypot(slip_after[:, 0], slip_after[:, 1])
    assert np.all(remaining[ends] <= 1e-14 * scale[ends])
    kept = ~ends & (speed > 1e-9)
    shrunk = np.abs(remaining[kept] - (speed[kept] - 3.5 * coulomb[kept]))
    assert np.all(shrunk <= 1e-13 * scale[kept])
    direction = np.sum(slip_after[kept] * slip_before[kept], axis=1)
    assert np.all(direction >= 0)  # never reversed


def test_the_frictional_bed_without_friction_is_the_frictionless_one_to_the_bit() -> None:
    rows = random_impacts(500, 7, friction=0.0)
    frictionless = rows.copy()
    frictionless[:, 2] = (0.0 - rows[:, 7]) * rows[:, 2]
    assert probe.bed_impacts(rows).tobytes() == frictionless[:, :6].copy().tobytes()


def test_a_ball_not_coming_down_does_not_meet_the_bed() -> None:
    rows = random_impacts(100, 8)
    rows[:, 2] = np.abs(rows[:, 2])
    rows[:10, 2] = 0.0
    assert probe.bed_impacts(rows).tobytes() == rows[:, :6].copy().tobytes()


def pooltool_frictional_table(row: list[float]) -> list[float]:
    """pooltool main's frictional_inelastic ball-table law (physics/resolve/ball_table/
    frictional_inelastic), transcribed in its own algebra: the no-slip change 2/7 (R w x
    z - v) unless the slip's is smaller, then mu (1 + e) |v_z| against the slip."""
    v, w = np.array(row[0:3]), np.array(row[3:6])
    radius, e, mu = row[6], row[7], row[8]
    z = np.array([0.0, 0.0, 1.0])
    normal = (1 + e) * -v[2]
    v_plane = np.array([v[0], v[1], 0.0])
    slip = v_plane + np.cross(w, -radius * z)
    no_slip = 2.0 / 7.0 * (radius * np.cross(w, z) - v_plane)
    sliding = mu * normal * -slip / np.linalg.norm(slip)
    if np.sum(no_slip * no_slip) <= np.sum(sliding * sliding):
        v_after = v_plane + no_slip
        w_after = w + 5.0 / 7.0 * (-w + np.cross(z, v_plane) / radius)
        w_after[2] = w[2]  # pooltool's rolling spin drops w_z: TP A-14 leaves it alone
    else:
        v_after = v_plane + sliding
        w_after = w + 2.5 / radius * np.linalg.norm(sliding) * np.cross(z, slip) / (
            np.linalg.norm(slip)
        )
    return [*v_after[:2], -e * v[2], *w_after]


def test_the_frictional_bed_is_pooltools_law_to_rounding() -> None:
    rows = random_impacts(1000, 17)
    rows = rows[np.hypot(*slip_of(rows[:, :6]).T) > 1e-6]
    for row, mine in zip(rows.tolist(), probe.bed_impacts(rows).tolist(), strict=True):
        theirs = pooltool_frictional_table(row)
        scale = math.hypot(*row[0:3]) + R * math.hypot(*row[3:6])
        assert mine[:3] == pytest.approx(theirs[:3], abs=1e-14 * scale)
        assert [R * w for w in mine[3:]] == pytest.approx(
            [R * w for w in theirs[3:]], abs=1e-13 * scale
        )


# --- the hops -----------------------------------------------------------------------------


def hop_rows(speeds: list[float], restitution: float, friction: float) -> np.ndarray:
    """bounce_sequences' rows: landing straight down at each speed, no spin."""
    return np.array([
        [0.0, 0.0, -speed, 0.0, 0.0, 0.0, R, restitution, friction, G, SETTLE_HEIGHT]
        for speed in speeds
    ])  # fmt: skip


def test_the_bounce_heights_fall_by_e_t_squared() -> None:
    velocity, spin = [0.8, -0.3, -3.0], [10.0, 40.0, 5.0]
    launches = []
    for _ in range(12):
        row = np.array([[*velocity, *spin, R, E_T, MU_T]])
        out = probe.bed_impacts(row)[0].tolist()
        launches.append(out[2])
        velocity, spin = [out[0], out[1], 0.0 - out[2]], out[3:6]
    heights = [v * v / (2 * G) for v in launches]
    for lower, upper in zip(heights[1:], heights[:-1], strict=False):
        assert abs(lower / upper - E_T * E_T) <= 4 * EPS


@pytest.mark.parametrize("restitution", [0.3, 0.5, 0.7, 0.9, 0.99])
def test_the_total_air_time_is_its_geometric_series(restitution: float) -> None:
    """Frictionless: n flights of 2 v e^k / g sum to 2 v e (1 - e^n) / (g (1 - e))."""
    speeds = np.random.default_rng(9).uniform(0.5, 12, 200).tolist()
    out = probe.bounce_sequences(hop_rows(speeds, restitution, 0.0))
    counts = probe.bounce_counts(np.array([[s, restitution, G, SETTLE_HEIGHT] for s in speeds]))
    assert out[:, 0].tolist() == counts.astype(float).tolist()
    for speed, (flights, air) in zip(speeds, out[:, :2].tolist(), strict=True):
        n = int(flights)
        e = restitution
        series = 2 * speed * e * (1 - e**n) / (G * (1 - e))
        assert abs(air - series) <= (n + 4) * 4 * EPS * series
        # n: the last launch e^n v rises the settling height, e^(n+1) v does not.
        lowest = math.sqrt(2 * G * SETTLE_HEIGHT)
        log_count = math.log(speed / lowest) / math.log(1 / e)
        if abs(log_count - round(log_count)) > 1e-9:
            assert n == math.floor(log_count)


def test_the_hopping_ends_after_finitely_many_flights() -> None:
    rows = np.array([[100.0, 0.999, G, SETTLE_HEIGHT], [100.0, 1.0, G, SETTLE_HEIGHT]])
    counts = probe.bounce_counts(rows).tolist()
    assert counts[0] < MAX_BOUNCES and counts[1] == MAX_BOUNCES  # e_t = 1: the safeguard
    assert probe.bounce_counts(np.array([[1.0, 0.0, G, SETTLE_HEIGHT]])).tolist() == [0]


def test_frictionless_hops_carry_the_ball_at_its_own_speed_and_it_settles_on_the_cloth() -> None:
    row = hop_rows([4.0], E_T, 0.0)
    row[0, 0:2] = [0.6, -0.25]
    out = probe.bounce_sequences(row)[0].tolist()
    air = out[1]
    assert out[2:4] == pytest.approx([0.6 * air, -0.25 * air], rel=1e-14)
    assert out[4:7] == [0.6, -0.25, 0.0]


def test_the_bounce_sequence_is_its_bounces_one_by_one() -> None:
    """bounce_sequence gives what landing after landing of the bed's law and the flight
    gives (frictional): the flights, their time, the way carried, the state at the end."""
    velocity, spin = [1.2, 0.4, -4.0], [30.0, -60.0, 12.0]
    row = np.array([[*velocity, *spin, R, E_T, MU_T, G, SETTLE_HEIGHT]])
    whole = probe.bounce_sequences(row)[0].tolist()
    flights, air, carried = 0, 0.0, [0.0, 0.0]
    while True:
        out = probe.bed_impacts(np.array([[*velocity, *spin, R, E_T, MU_T]]))[0].tolist()
        velocity, spin = out[0:3], out[3:6]
        if velocity[2] < math.sqrt(2.0 * G * SETTLE_HEIGHT):
            break
        flight = 2.0 * velocity[2] / G
        flights, air = flights + 1, air + flight
        carried = [carried[0] + velocity[0] * flight, carried[1] + velocity[1] * flight]
        velocity = [velocity[0], velocity[1], 0.0 - velocity[2]]
    assert whole == [flights, air, *carried, velocity[0], velocity[1], 0.0, *spin]
    assert flights == 3


def test_frictional_hops_never_gain_energy_and_end_sliding_on_the_cloth() -> None:
    rows = random_impacts(300, 10)
    rows = np.ascontiguousarray(
        np.column_stack([rows, np.full(len(rows), G), np.full(len(rows), SETTLE_HEIGHT)])
    )
    out = probe.bounce_sequences(rows)
    for row, after in zip(rows.tolist(), out.tolist(), strict=True):
        assert after[6] == 0.0
        assert energy(after[4:7], after[7:10]) <= energy(row[0:3], row[3:6])


# --- the jump stroke ----------------------------------------------------------------------


def launch_of(stroke: Stroke, friction: float) -> tuple[list[float], list[float]]:
    hit = strike(stroke, seed.CUE_MASS, R)
    row = np.array([[*hit.velocity, *hit.spin, hit.drive_down, R, E_T, friction]])
    out = probe.jumps(row)[0].tolist()
    return out[:3], out[3:]


@pytest.mark.parametrize("elevation", [5.0, 15.0, 30.0, 45.0, 60.0, 80.0])
def test_a_jump_stroke_leaves_the_bed_at_e_t_v_sin_elevation(elevation: float) -> None:
    """TP A-30 with the vertical part kept: a centre hit gives v = 2 V / (1 + m/M) along
    the cue's axis, v cos(el) on the cloth and v sin(el) into the bed, which returns e_t
    of it (frictionless bed: the level part and the spin pass)."""
    stroke = Stroke(speed=4.0, direction=30.0, elevation=elevation)
    velocity, spin = launch_of(stroke, 0.0)
    v = 2 * 4.0 / (1 + seed.CUE_MASS / Stroke.mass)
    el, direction = math.radians(elevation), math.radians(30.0)
    expected = [
        v * math.cos(el) * math.cos(direction), v * math.cos(el) * math.sin(direction),
        E_T * v * math.sin(el),
    ]  # fmt: skip
    assert velocity == pytest.approx(expected, rel=1e-14, abs=1e-14)
    assert spin == [0.0, 0.0, 0.0]


def test_a_jump_strokes_bed_friction_is_bounded_and_never_adds_energy() -> None:
    rng = np.random.default_rng(11)
    for _ in range(300):
        side, height = rng.uniform(-0.5, 0.5, 2)
        stroke = Stroke(
            speed=rng.uniform(1, 8), direction=rng.uniform(0, 360),
            elevation=rng.uniform(1, 85), tip=(side, height),
        )  # fmt: skip
        hit = strike(stroke, seed.CUE_MASS, R)
        velocity, spin = launch_of(stroke, MU_T)
        assert velocity[2] == E_T * hit.drive_down
        change = math.hypot(velocity[0] - hit.velocity[0], velocity[1] - hit.velocity[1])
        assert change <= MU_T * (1 + E_T) * hit.drive_down * (1 + 1e-14)
        before = energy([*hit.velocity, -hit.drive_down], list(hit.spin))
        assert energy(velocity, spin) <= before


def test_a_level_stroke_stays_on_the_cloth_with_its_strike_to_the_bit() -> None:
    hit = strike(Stroke(speed=3.0, direction=10.0, tip=(0.3, -0.4)), seed.CUE_MASS, R)
    velocity, spin = launch_of(Stroke(speed=3.0, direction=10.0, tip=(0.3, -0.4)), MU_T)
    assert velocity == [*hit.velocity, 0.0] and spin == list(hit.spin)


# --- contacts in 3D -----------------------------------------------------------------------


def pair_rows(count: int, seed_value: int) -> np.ndarray:
    """ball_contacts' rows: a flying ball near another, flying or on the cloth with the
    spin model's acceleration in the plane, most of them headed for it."""
    rng = np.random.default_rng(seed_value)
    rows = np.zeros((count, 22))
    rows[:, 0:2] = rng.uniform(0.3, 0.7, (count, 2))
    rows[:, 2] = rng.uniform(R, 0.25, count)
    rows[:, 8] = -G
    rows[:, 9:11] = rows[:, 0:2] + rng.uniform(-0.2, 0.2, (count, 2))
    on_cloth = rng.uniform(size=count) < 0.5
    rows[:, 11] = np.where(on_cloth, R, rng.uniform(R, 0.25, count))
    rows[:, 12:14] = rng.uniform(-2, 2, (count, 2))
    rows[:, 14] = np.where(on_cloth, 0.0, rng.uniform(-3, 3, count))
    rows[:, 15:17] = np.where(on_cloth[:, None], rng.uniform(-2, 2, (count, 2)), 0.0)
    rows[:, 17] = np.where(on_cloth, 0.0, -G)
    # The flying ball aimed at where the other is in a fifth of a second, give or take.
    rows[:, 3:6] = (rows[:, 9:12] - rows[:, 0:3]) / 0.2 + rows[:, 12:15]
    rows[:, 5] += 0.1 * G
    rows[:, 3:6] += rng.uniform(-0.25, 0.25, (count, 3))
    rows[:, 18], rows[:, 19], rows[:, 20] = R, 1.0, 0.4
    gap = rows[:, 0:3] - rows[:, 9:12]
    apart = np.sqrt(np.sum(gap * gap, axis=1)) > 2.01 * R
    return np.ascontiguousarray(rows[apart])


def exact_quartic(row: list[float]) -> list[Fraction]:
    """|d(t)|^2 - 4R^2's coefficients from the rows' numbers, exactly."""
    d = [exact(row[i]) - exact(row[9 + i]) for i in range(3)]
    w = [exact(row[3 + i]) - exact(row[12 + i]) for i in range(3)]
    k = [(exact(row[6 + i]) - exact(row[15 + i])) / 2 for i in range(3)]

    def dot(a: list[Fraction], b: list[Fraction]) -> Fraction:
        return sum((x * y for x, y in zip(a, b, strict=True)), Fraction(0))

    radius = exact(row[18])
    return [
        dot(d, d) - 4 * radius * radius, 2 * dot(d, w), dot(w, w) + 2 * dot(d, k),
        2 * dot(w, k), dot(k, k),
    ]  # fmt: skip


def gap_at(quartic: list[Fraction], t: float) -> Fraction:
    return sum((c * exact(t) ** p for p, c in enumerate(quartic)), Fraction(0))


def test_a_ball_dropped_onto_a_ball_at_rest_touches_it_at_three_radii() -> None:
    """Dropped from rest at z0 straight above a ball at rest: the centres touch when the
    upper one is at 3R, after sqrt(2 (z0 - 3R) / g)."""
    drops = [0.1, 0.2, 0.35, 0.5]
    rows = np.zeros((len(drops), 22))
    rows[:, 0:2] = rows[:, 9:11] = 0.5
    rows[:, 2], rows[:, 11], rows[:, 8] = drops, R, -G
    rows[:, 18], rows[:, 19], rows[:, 20] = R, 1.0, 1.0
    found = probe.ball_contacts(rows, BERNSTEIN)[:, 0]
    for drop, time in zip(drops, found.tolist(), strict=True):
        assert time == pytest.approx(math.sqrt(2 * (drop - 3 * R) / G), rel=1e-14)


def test_the_3d_pair_quartic_has_its_exact_coefficients_and_its_root_is_the_first_touch() -> None:
    rows = pair_rows(600, 12)
    out = probe.ball_contacts(rows, BERNSTEIN)
    met = 0
    for row, found in zip(rows.tolist(), out.tolist(), strict=True):
        quartic = exact_quartic(row)
        scale = sum(abs(float(c)) for c in quartic) + 1.0
        for mine, theirs in zip(found[1:], quartic, strict=True):
            assert abs(exact(mine) - theirs) <= 16 * EPS * scale
        time = found[0]
        if math.isinf(time):
            grid = [row[20] * n / 32 for n in range(33)]
            assert all(gap_at(quartic, t) > 0 for t in grid), row
            continue
        met += 1
        # Substituted back: zero within rounding at the root, positive just before it
        # (a picosecond: a few picometres at these speeds) and at every 32nd before.
        assert abs(float(gap_at(quartic, time))) <= 1e-15 * scale
        assert gap_at(quartic, time - 1e-12) > 0
        assert all(gap_at(quartic, time * n / 32) > 0 for n in range(32))
    assert met > 200


def test_on_the_cloth_the_3d_quartic_is_the_plane_quartic() -> None:
    """Every coefficient the plane's (rolling.contact_times.separation_quartic) to the
    bit but for a zero's sign: z's +0.0 added to a -0.0 sum gives +0.0."""
    rows = pair_rows(400, 13)
    for column in (2, 11):
        rows[:, column] = R
    for column in (5, 8, 14, 17):
        rows[:, column] = 0.0
    mine = probe.ball_contacts(rows, BERNSTEIN)[:, 1:]
    relative = np.stack(
        [
            rows[:, 0:2] - rows[:, 9:11],
            rows[:, 3:5] - rows[:, 12:14],
            rows[:, 6:8] * 0.5 - rows[:, 15:17] * 0.5,
        ],
        axis=1,
    )
    theirs, _ = separation_quartic(relative, 4.0 * R * R)
    assert mine.tolist() == theirs.tolist()
    assert (mine + 0.0).tobytes() == np.ascontiguousarray(theirs + 0.0).tobytes()


def cushion_row(across: float, rate: float, z: float, rise: float) -> list[float]:
    return [across, rate, z, rise, R, H, G, 5.0]


def test_a_flying_ball_meets_the_face_the_nose_or_clears_the_rail() -> None:
    rows = np.array([
        cushion_row(0.3, -2.0, R, 0.0),  # low and level: the face at across = R
        cushion_row(0.3, -2.0, R, 0.8),  # above the face's top at across = R: the nose
        cushion_row(0.3, -2.0, R, 2.5),  # high: over the rail
        cushion_row(0.3, 2.0, R, 1.0),  # away from the wall
    ])  # fmt: skip
    out = probe.cushion_contacts(rows, BERNSTEIN)
    assert out[:, 1].tolist() == [FACE, NOSE, OVER_THE_RAIL, NO_CONTACT]
    assert out[0, 0] == (0.3 - R) / 2.0
    assert out[2, 0] == 0.3 / 2.0 and math.isinf(out[3, 0])


def test_the_nose_contact_is_the_quartics_root_substituted_back() -> None:
    rng = np.random.default_rng(14)
    rows = np.array([
        cushion_row(rng.uniform(0.05, 0.5), -rng.uniform(0.5, 5), R, rng.uniform(0, 3))
        for _ in range(2000)
    ])  # fmt: skip
    out = probe.cushion_contacts(rows, BERNSTEIN)
    kinds = set()
    for row, (time, kind) in zip(rows.tolist(), out.tolist(), strict=True):
        kinds.add(kind)
        t = exact(time)
        across = exact(row[0]) + exact(row[1]) * t
        z = exact(row[2]) + exact(row[3]) * t - exact(G) * t * t / 2
        if kind == NOSE:
            gap = across * across + (z - exact(H)) ** 2 - exact(R) ** 2
            assert abs(float(gap)) <= 1e-14 and z >= exact(H)
            for n in range(64):  # apart before: outside the cylinder or above the face
                s = t * n / 64
                a = exact(row[0]) + exact(row[1]) * s
                h = exact(row[2]) + exact(row[3]) * s - exact(G) * s * s / 2
                assert a > exact(R) or a * a + (h - exact(H)) ** 2 > exact(R) ** 2
        elif kind == FACE:
            assert abs(float(across) - R) <= 1e-16 and z <= exact(H)
        elif kind == OVER_THE_RAIL:
            assert abs(float(across)) <= 1e-16 and z > exact(H) + exact(R)
    assert kinds == {FACE, NOSE, OVER_THE_RAIL}


def ball_impact_rows(count: int, seed_value: int) -> np.ndarray:
    """ball_impacts' rows: two touching balls at any angle in 3D, any masses."""
    rng = np.random.default_rng(seed_value)
    direction = rng.normal(size=(count, 3))
    direction /= np.sqrt(np.sum(direction * direction, axis=1))[:, None]
    first = rng.uniform(0.2, 0.8, (count, 3))
    rows = np.column_stack([
        first, first - 2 * R * direction, rng.uniform(-4, 4, (count, 3)),
        rng.uniform(0.1, 0.3, count), rng.uniform(-4, 4, (count, 3)),
        rng.uniform(0.1, 0.3, count), rng.uniform(0.5, 1, count),
    ])  # fmt: skip
    return np.ascontiguousarray(rows)


def test_a_3d_ball_contact_keeps_momentum_and_never_gains_energy() -> None:
    rows = ball_impact_rows(3000, 18)
    out = probe.ball_impacts(rows)
    approached = 0
    for row, after in zip(rows.tolist(), out.tolist(), strict=True):
        m1, m2 = exact(row[9]), exact(row[13])
        approached += after[6] > 0
        for axis in range(3):
            before = m1 * exact(row[6 + axis]) + m2 * exact(row[10 + axis])
            now = m1 * exact(after[axis]) + m2 * exact(after[3 + axis])
            size = row[9] * abs(row[6 + axis]) + row[13] * abs(row[10 + axis]) + 1.0
            assert abs(float(now - before)) <= 8 * EPS * size
        energy_before = m1 * sum((exact(v) ** 2 for v in row[6:9]), Fraction(0)) + m2 * sum(
            (exact(v) ** 2 for v in row[10:13]), Fraction(0)
        )
        energy_after = m1 * sum((exact(v) ** 2 for v in after[0:3]), Fraction(0)) + m2 * sum(
            (exact(v) ** 2 for v in after[3:6]), Fraction(0)
        )
        assert energy_after <= energy_before * (1 + Fraction(8 * EPS))
    assert approached > 1000


def test_in_the_plane_the_3d_ball_contact_is_the_plane_law() -> None:
    rows = ball_impact_rows(500, 19)
    rows[:, [2, 5]] = 0.5
    rows[:, [8, 12]] = 0.0
    rows[:, 3:5] = (
        rows[:, 0:2]
        - 2
        * R
        * (rows[:, 0:2] - rows[:, 3:5])
        / np.hypot(*(rows[:, 0:2] - rows[:, 3:5]).T)[:, None]
    )
    out = probe.ball_impacts(rows)
    for row, mine in zip(rows.tolist(), out.tolist(), strict=True):
        normal = line_of_centres(np.array(row[0:2]), np.array(row[3:5]))
        v1, v2, approach = frictionless_impulse(
            normal, np.array(row[6:8]), row[9], np.array(row[10:12]), row[13], row[14]
        )
        assert [*mine[0:2], *mine[3:5], mine[6]] == [*v1.tolist(), *v2.tolist(), approach]
        assert mine[2] == 0.0 and mine[5] == 0.0


# --- the same bits on every machine ------------------------------------------------------

# Every probe on seeded inputs, digested, from a fresh process; and how many fused
# multiply-adds the probes' code holds (an FMA rounds a * b + c once).
DIGEST = """
import hashlib, re
import numpy as np
from billiards.physics.compiled.airborne import probe
from billiards.physics.compiled.roots import BERNSTEIN
from tests.physics.test_airborne import ball_impact_rows, pair_rows, random_impacts
rng = np.random.default_rng(15)
impacts = random_impacts(500, 16)
hops = np.ascontiguousarray(np.column_stack([impacts, np.full(500, 9.81), np.full(500, 0.005)]))
outputs = [
    probe.flights(np.ascontiguousarray(rng.uniform(0.01, 3, (500, 8)))),
    probe.landings(np.ascontiguousarray(rng.uniform(0, 5, (500, 3)) - [0, 2.5, 0])),
    probe.bed_impacts(impacts),
    probe.jumps(np.ascontiguousarray(impacts[:, [0, 1, 3, 4, 5, 2, 6, 7, 8]] * [1, 1, 1, 1, 1, -1, 1, 1, 1])),
    probe.bounce_counts(np.ascontiguousarray(hops[:, [2, 7, 9, 10]] * [-1, 1, 1, 1])),
    probe.bounce_sequences(hops),
    probe.ball_contacts(pair_rows(500, 17), BERNSTEIN),
    probe.ball_impacts(ball_impact_rows(500, 20)),
    probe.cushion_contacts(np.ascontiguousarray(rng.uniform(0, 1, (500, 8)) * [0.5, -4, 0.1, 3, 0, 0, 0, 0] + [0, 0, 0.0286, 0, 0.0286, 0.036322, 9.81, 5]), BERNSTEIN),
]
print("digest", hashlib.sha256(b"".join(o.tobytes() for o in outputs)).hexdigest())
if hasattr(probe.flights, "inspect_asm"):
    entries = [probe.flights, probe.landings, probe.bed_impacts, probe.jumps, probe.bounce_counts,
               probe.bounce_sequences, probe.ball_contacts, probe.cushion_contacts,
               probe.ball_impacts]
    listings = [text for each in entries for text in each.inspect_asm().values()]
    print("fma", sum(len(re.findall(r"\\bv?f(n)?m(add|sub)", t, re.IGNORECASE)) for t in listings))
"""


def fresh_digest(cache: Path, **variables: str) -> dict[str, str]:
    """What DIGEST prints from a fresh process with an empty numba cache."""
    return fresh_digests(cache, DIGEST, **variables)


@hard
@pytest.mark.parametrize("cpu", ["generic", "x86-64-v2", "x86-64-v4", binding.get_host_cpu_name()])
def test_the_airborne_kernels_give_the_same_bytes_on_each_cpu(cpu: str, tmp_path: Path) -> None:
    if not host_knows(cpu):
        pytest.skip(f"this host's LLVM does not know {cpu} or cannot run its code")
    host = fresh_digest(tmp_path / "host")
    assert host["fma"] == "0"
    assert fresh_digest(tmp_path / cpu, NUMBA_CPU_NAME=cpu) == host


@hard
def test_the_airborne_kernels_run_uncompiled_with_the_same_bytes(tmp_path: Path) -> None:
    compiled = fresh_digest(tmp_path / "host")
    uncompiled = fresh_digest(tmp_path / "python", NUMBA_DISABLE_JIT="1")
    assert uncompiled["digest"] == compiled["digest"]
