"""Off the cloth in the compiled loop (issue 45): a ball driven into the bed flies a
parabola, lands at the closed-form root, bounces (heights e_t^2 apart, the time in the
air its geometric series, the number of hops finite) and slides on; energy never rises
at a bed contact; a flying ball passes over a ball it clears and meets one it does not
in 3D; a jump stroke is simulated (the shipped jump_shot); a run that never flies is
as before (its pins: test_fingerprints, test_compiled)."""

from __future__ import annotations

import itertools
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from billiards.physics.compiled.airborne import probe
from billiards.physics.compiled.airborne.bounces import SETTLE_HEIGHT
from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods.entry import run
from billiards.physics.spin.motion import FLYING
from billiards.physics.spin.result import SpinMotion
from billiards.rules import seed
from billiards.scene.reader import Scene, default_scene_path, load_scene
from billiards.scene.stroke import strike
from billiards.simulation import setup_from_scene, simulate_scene
from tests.commands import run_module

R = seed.RADIUS
G = seed.GRAVITY
E_T = seed.TABLE_RESTITUTION
MU_S = seed.SLIDING_FRICTION
EPS = float(np.finfo(np.float64).eps)
MASS = seed.MASS


def flight(
    drive: float,
    velocity: tuple[float, float] = (0.0, 0.0),
    spin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    others: tuple[tuple[float, float], ...] = (),
    **constants: float,
) -> SimulationResult:
    """One ball at the table's middle driven into the bed at `drive` (and balls at rest
    at `others`), by the compiled loop's spin model."""
    count = 1 + len(others)
    positions = [(1.0, 0.5325), *others]
    velocities = [velocity] + [(0.0, 0.0)] * len(others)
    spins = [spin] + [(0.0, 0.0, 0.0)] * len(others)
    drives = np.array([drive] + [0.0] * len(others))
    setup = Setup.of(
        positions,
        velocities,
        spins=spins,
        model="spin",
        drives=drives,
        max_time=20.0,
        **constants,
    )
    assert len(setup.positions) == count
    return run(setup, tuple(str(ball) for ball in range(count)), "event", seed.DT)


def segments_of(result: SimulationResult, ball: int) -> list[int]:
    motion = result.motion
    assert isinstance(motion, SpinMotion)
    return [row for row in range(len(motion.ball)) if motion.ball[row] == ball]


def test_a_ball_in_the_air_follows_the_parabola_to_rounding() -> None:
    drive = 3.0
    result = flight(drive, (1.0, 0.0), sliding_friction=0.0)
    launch = E_T * drive
    landing = 2.0 * launch / G
    times = np.linspace(0.0, landing, 41)[1:-1]
    heights = result.heights_at(times)[:, 0]
    expected = R + launch * times - 0.5 * G * times * times
    assert np.allclose(heights, expected, rtol=0, atol=8 * EPS)
    # Without the bed's friction the flight keeps the strike's horizontal velocity.
    positions = result.positions_at(times)[:, 0]
    assert np.allclose(positions[:, 0], 1.0 + times, rtol=0, atol=8 * EPS)
    assert np.all(positions[:, 1] == 0.5325)


def test_the_landing_is_a_motion_state_change_at_the_root_of_z_equals_r() -> None:
    drive = 3.0
    result = flight(drive)
    first = result.transitions[0]
    launch = E_T * drive
    assert first.ball == "0" and first.state == "flying"  # it bounces up again
    assert first.time == pytest.approx(2.0 * launch / G, rel=4 * EPS)
    assert result.heights_at(np.array([first.time]))[0, 0] == R


def hops(drive: float, restitution: float) -> tuple[list[float], int]:
    """The times of a ball's landings driven straight down at `drive` (no horizontal
    motion: nothing but the bed), and the number of flights the closed form gives."""
    result = flight(drive, table_restitution=restitution)
    landings = [each.time for each in result.transitions if each.ball == "0"]
    launch = restitution * drive
    lowest = np.sqrt(2.0 * G * SETTLE_HEIGHT)
    count = 0
    while launch >= lowest:
        count += 1
        launch *= restitution
    return landings, count


@pytest.mark.parametrize("restitution", [0.5, 0.8])
def test_the_hops_are_finite_and_their_air_time_is_the_geometric_series(
    restitution: float,
) -> None:
    drive = 4.0
    landings, count = hops(drive, restitution)
    # Each flight ends at a landing; the last landing settles (a state other than flying).
    assert len(landings) == count
    v, e = Fraction(drive), Fraction(restitution)
    series = 2 * v * e * (1 - e**count) / (Fraction(G) * (1 - e))
    assert landings[-1] == pytest.approx(float(series), rel=64 * EPS)
    flights = np.diff([0.0, *landings])
    assert np.allclose(flights[1:] / flights[:-1], restitution, rtol=1e-12)


def test_the_bounce_heights_fall_by_e_t_squared() -> None:
    drive = 4.0
    result = flight(drive)
    landings = [0.0] + [each.time for each in result.transitions if each.ball == "0"]
    apexes = [(start + end) / 2 for start, end in itertools.pairwise(landings)]
    rises = result.heights_at(np.array(apexes))[:, 0] - R
    assert len(rises) >= 3
    assert np.allclose(rises[1:] / rises[:-1], E_T * E_T, rtol=1e-12)
    assert rises[0] == pytest.approx((E_T * drive) ** 2 / (2 * G), rel=1e-13)


def kinetic(velocity: np.ndarray, spin: np.ndarray) -> float:
    """Kinetic energy over mass: |v|^2 / 2 + (2/5 R^2) |w|^2 / 2."""
    return 0.5 * float(velocity @ velocity) + 0.2 * R * R * float(spin @ spin)


def test_energy_never_rises_at_a_bed_contact() -> None:
    rng = np.random.default_rng(45)
    for _ in range(6):
        spin = tuple(rng.uniform(-60, 60, 3))
        result = flight(rng.uniform(2, 6), tuple(rng.uniform(-1.5, 1.5, 2)), spin)
        motion = result.motion
        assert isinstance(motion, SpinMotion) and motion.vz0 is not None
        rows = segments_of(result, 0)
        landed = 0
        for before, after in itertools.pairwise(rows):
            if motion.state[before] != FLYING:
                continue
            tau = motion.t0[after] - motion.t0[before]
            falling = motion.vz0[before] - G * tau
            down = np.array([*motion.v0[before], falling])
            up = np.array([*motion.v0[after], motion.vz0[after]])
            assert kinetic(up, motion.w0[after]) <= kinetic(down, motion.w0[before]) * (1 + 8 * EPS)
            landed += 1
        assert landed >= 2


def test_the_jump_strokes_launch_is_the_bed_laws_to_the_bit() -> None:
    scene = load_scene(default_scene_path().parent / "jump_shot.toml")
    setup = setup_from_scene(scene)
    assert setup.drives is not None
    cue = scene.balls[0]
    assert cue.stroke is not None
    struck = strike(cue.stroke, cue.mass, scene.radius)
    assert setup.drives[0] == struck.drive_down
    row = [*struck.velocity, *struck.spin, struck.drive_down, R, E_T, MU_S]
    launched = probe.jumps(np.array([row]))[0]
    result = simulate_scene(scene, method="event")
    motion = result.motion
    assert isinstance(motion, SpinMotion) and motion.vz0 is not None
    first = segments_of(result, 0)[0]
    assert motion.state[first] == FLYING
    got = [*motion.v0[first], motion.vz0[first], *motion.w0[first]]
    assert got == launched.tolist()
    assert motion.vz0[first] == E_T * struck.drive_down  # TP A-30/31's vertical part, kept


def test_the_jump_shot_clears_the_blocker_and_pockets_the_1() -> None:
    scene = load_scene(default_scene_path().parent / "jump_shot.toml")
    result = simulate_scene(scene, method="event")
    assert not any("blocker" in event.balls for event in result.events)
    assert [(each.ball, each.pocket) for each in result.pocketed] == [("1", "foot-left")]
    first_hit = next(event for event in result.events if event.kind == "ball")
    times = np.linspace(0.0, first_hit.time, 2001)
    centres = np.concatenate(
        [result.positions_at(times), result.heights_at(times)[..., None]], axis=2
    )
    gap = np.linalg.norm(centres[:, 0] - centres[:, 1], axis=1)
    assert gap.min() > 2 * R  # over it, never through it
    flying = result.heights_at(times)[:, 0] > R
    passing = np.argmin(gap)
    assert flying[passing] and centres[passing, 0, 2] > 3 * R - 0.01


def test_a_flying_ball_that_does_not_clear_a_ball_meets_it_in_3d() -> None:
    # Low and fast: the flyer comes down onto the ball ahead on its upper half.
    result = flight(2.0, (2.0, 0.0), others=((1.2, 0.5325),), sliding_friction=0.0)
    hit = next(event for event in result.events if event.kind == "ball")
    assert hit.balls == ("0", "1")
    at = np.array([hit.time])
    centres = np.concatenate([result.positions_at(at), result.heights_at(at)[..., None]], axis=2)
    assert np.linalg.norm(centres[0, 0] - centres[0, 1]) == pytest.approx(2 * R, rel=1e-9)
    assert centres[0, 0, 2] > R  # in the air as it touches
    # Momentum in the cloth's plane kept (the bed takes only vertical momentum).
    before = result.velocities_at(np.array([hit.time * (1 - 1e-9)]))[0]
    after = result.velocities_at(at)[0]
    assert np.allclose(before.sum(axis=0), after.sum(axis=0), rtol=0, atol=1e-12)


def test_a_run_that_never_flies_is_as_before() -> None:
    scene = load_scene(default_scene_path().parent / "masse_shot.toml")  # elevated, no jump
    assert setup_from_scene(scene).drives is None
    result = simulate_scene(scene, method="event")
    assert isinstance(result.motion, SpinMotion) and result.motion.z0 is None
    assert np.all(result.heights_at(np.array([0.0, 0.5, 1.0])) == R)


def test_flight_runs_only_in_the_compiled_spin_model() -> None:
    setup = Setup.of([(1.0, 0.5)], [(1.0, 0.0)], spins=[(0, 0, 0)], model="spin", drives=[3.0])
    with pytest.raises(ValueError, match="compiled loop only"):
        run(setup, ("0",), "naive", seed.DT)
    with pytest.raises(ValueError, match="gravity > 0"):
        run(
            Setup.of([(1.0, 0.5)], spins=[(0, 0, 0)], model="spin", drives=[3.0], gravity=0.0),
            ("0",),
            "event",
            seed.DT,
        )


@pytest.mark.long
def test_a_jump_with_zero_gravity_is_one_line_and_exit_2(tmp_path: Path) -> None:
    path = tmp_path / "s.toml"
    text = (default_scene_path().parent / "jump_shot.toml").read_text()
    path.write_text(text.replace('model = "spin"', 'model = "spin"\ngravity = 0'))
    done = run_module("billiards.simulate", str(path))
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and "physics.gravity = 0" in done.stderr


@pytest.mark.long
def test_a_jump_by_naive_is_one_line_and_exit_2() -> None:
    done = run_module("billiards.simulate", "jump_shot", "--method", "naive")
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and "expected 'event' or 'exact'" in done.stderr


def at_the_foot_cushion(start: float, drive: float) -> SimulationResult:
    """A ball launched towards the foot cushion at 1 m/s (no bed friction), driven into
    the bed at `drive`."""
    setup = Setup.of(
        [(start, 0.5325)],
        [(1.0, 0.0)],
        spins=[(0.0, 0.0, 0.0)],
        model="spin",
        drives=[drive],
        sliding_friction=0.0,
        max_time=20.0,
    )
    return run(setup, ("0",), "event", seed.DT)


def test_a_ball_flying_high_at_a_cushion_leaves_the_table_over_the_rail() -> None:
    result = at_the_foot_cushion(2.0, 6.0)
    (gone,) = result.events
    assert (gone.kind, gone.pocket) == ("pocket", None)  # reported like a drop, no pocket
    assert gone.time == pytest.approx(0.13, rel=1e-12)  # across = 0: x = L
    assert result.heights_at(np.array([gone.time * (1 - 1e-9)]))[0, 0] > seed.CUSHION_HEIGHT + R
    assert result.pocketed == ()


def test_a_ball_flying_at_the_cushion_height_meets_its_nose_in_3d() -> None:
    result = at_the_foot_cushion(2.0, 1.416)
    hit = result.events[0]
    assert hit.kind == "cushion"
    before, after = hit.time * (1 - 1e-9), hit.time
    z = result.heights_at(np.array([after]))[0, 0]
    assert z > seed.CUSHION_HEIGHT  # above the nose line: not the face
    x = result.motion.positions_at(np.array([after]))[0, 0, 0]  # beyond the clamp
    across, rise = seed.TABLE_SIZE[0] - x, z - seed.CUSHION_HEIGHT
    assert across * across + rise * rise == pytest.approx(R * R, rel=1e-9)
    motion = result.motion
    assert isinstance(motion, SpinMotion) and motion.vz0 is not None
    rows = segments_of(result, 0)
    flying_then = rows[0]
    landing_speed = motion.vz0[flying_then] - G * (hit.time - motion.t0[flying_then])
    down = np.array([*result.velocities_at(np.array([before]))[0, 0], landing_speed])
    hit_row = next(row for row in rows if motion.t0[row] == hit.time)
    up = np.array([*motion.v0[hit_row], motion.vz0[hit_row]])
    assert up @ up <= down @ down * (1 + 8 * EPS)  # energy never rises
    assert up[0] < 0 and up[2] > landing_speed  # pushed back and up off the nose


def test_a_ball_flying_low_at_a_cushion_meets_its_face() -> None:
    result = at_the_foot_cushion(2.09, 0.8)
    hit = result.events[0]
    assert hit.kind == "cushion"
    z = result.heights_at(np.array([hit.time]))[0, 0]
    assert R < z <= seed.CUSHION_HEIGHT
    assert result.positions_at(np.array([hit.time]))[0, 0, 0] == seed.TABLE_SIZE[0] - R


def test_the_gltf_tracks_carry_the_flights_parabola() -> None:
    from billiards.export.tracks import evaluate_keys, motion_tracks

    result = simulate_scene(load_scene(default_scene_path().parent / "jump_shot.toml"))
    tracks = motion_tracks(result, result.transitions)
    cue = tracks.balls[0]
    times = np.linspace(0.0, 0.5, 501)
    drawn = evaluate_keys(cue.times, cue.values, cue.in_tangents, cue.out_tangents, times)
    assert np.allclose(drawn[:, 2], result.heights_at(times)[:, 0], rtol=0, atol=1e-12)
    assert drawn[:, 2].max() > 3 * R  # it lifts off


def test_the_beds_restitution_is_a_scene_key() -> None:
    text = (default_scene_path().parent / "jump_shot.toml").read_text()
    softer = text.replace('model = "spin"', 'model = "spin"\ntable_restitution = 0.4')
    scene = scene_from_text(softer)
    setup = setup_from_scene(scene)
    assert setup.table_restitution == 0.4 and setup.drives is not None
    result = simulate_scene(scene, method="event")
    motion = result.motion
    assert isinstance(motion, SpinMotion) and motion.vz0 is not None
    assert motion.vz0[segments_of(result, 0)[0]] == 0.4 * setup.drives[0]
    # A dead bed throws nothing up: no jump, the run stays on the cloth.
    dead = scene_from_text(text.replace('model = "spin"', 'model = "spin"\ntable_restitution = 0'))
    assert setup_from_scene(dead).drives is None


def scene_from_text(text: str) -> Scene:
    import tomllib

    from billiards.scene.reader import scene_from_dict

    return scene_from_dict(tomllib.loads(text), "jump.toml")


def jump_family(case: int) -> Setup:
    """A seeded jump among a few balls (2 to 6) near the cue ball: the stroke's drive,
    velocity and spin drawn, pockets or none, the mirror cushion or Han 2005's."""
    from billiards.physics.pockets import pocket_table

    rng = np.random.default_rng([45, case])
    count = int(rng.integers(2, 7))
    positions: list[np.ndarray] = [rng.uniform([0.9, 0.4], [1.2, 0.66])]
    while len(positions) < count:
        place = rng.uniform([0.8, 0.3], [1.3, 0.76])
        if all(np.hypot(*(place - other)) > 2.2 * R for other in positions):
            positions.append(place)
    angle = rng.uniform(0, 2 * np.pi)
    velocities = np.zeros((count, 2))
    velocities[0] = rng.uniform(1.0, 4.0) * np.array([np.cos(angle), np.sin(angle)])
    spins = np.zeros((count, 3))
    spins[0] = rng.uniform(-80, 80, 3)
    drives = np.zeros(count)
    drives[0] = rng.uniform(1.0, 3.5)
    size = seed.TABLE_SIZE
    holes = (size, R, seed.CORNER_POCKET_WIDTH, seed.SIDE_POCKET_WIDTH, seed.JAW_RADIUS)
    return Setup.of(
        positions,
        velocities,
        spins=spins,
        model="spin",
        drives=drives,
        pockets=pocket_table(*holes) if rng.integers(2) else None,
        cushion_law=("mirror", "han2005")[int(rng.integers(2))],
        max_time=30.0,
    )


def energies(result: SimulationResult, times: np.ndarray) -> np.ndarray:
    """Each ball's mechanical energy over its mass at `times` (T, N): |v|^2 / 2 (with
    v_z) + (2/5 R^2) |w|^2 / 2 + g (z - R)."""
    velocity = result.velocities_at(times)
    climb = result.climbs_at(times)
    spin = result.spins_at(times)
    moving = 0.5 * ((velocity * velocity).sum(axis=-1) + climb * climb)
    turning = 0.2 * R * R * (spin * spin).sum(axis=-1)
    return moving + turning + G * (result.heights_at(times) - R)


@pytest.mark.parametrize("part", range(4))
def test_random_jumps_never_overlap_never_sink_and_never_gain_energy(part: int) -> None:
    for case in range(10 * part, 10 * part + 10):
        setup = jump_family(case)
        ids = tuple(str(ball) for ball in range(len(setup.positions)))
        result = run(setup, ids, "event", seed.DT)
        stepped = run(setup, ids, "exact", 1 / 30)
        assert [e.time for e in stepped.events] == [e.time for e in result.events]
        times = np.linspace(0.0, min(result.rest_time, 4.0), 2001)
        centres = np.concatenate(
            [result.motion.positions_at(times), result.heights_at(times)[..., None]], axis=2
        )
        assert centres[..., 2].min() >= R * (1 - 1e-12), case  # never into the bed
        gone = {event.balls[0]: event.time for event in result.events if event.kind == "pocket"}
        for first, second in itertools.combinations(range(len(ids)), 2):
            here = np.ones(len(times), dtype=bool)
            for ball in (first, second):
                here &= times < gone.get(ids[ball], np.inf)
            gap = np.linalg.norm(centres[here, first] - centres[here, second], axis=1)
            assert gap.size == 0 or gap.min() >= 2 * R * (1 - 1e-9), case
        # At every event the run's energy (the balls still on the table) never rises.
        previous = 0.0
        for event in result.events:
            if event.time <= previous:
                continue
            before = event.time - min(1e-9, (event.time - previous) / 2)
            totals = energies(result, np.array([before, event.time]))
            kept = [ids.index(ball) for ball in ids if gone.get(ball, np.inf) > event.time]
            was, now = totals[0, kept].sum(), totals[1, kept].sum()
            assert now <= was * (1 + 1e-9) + 1e-12, (case, event)
            previous = event.time


# --- contacts that lift balls (physics.airborne), the hopping break, pockets in flight ---


def test_a_ball_struck_from_above_is_thrown_up_by_the_bed() -> None:
    # The flyer comes down on the resting ball's upper half: the 3D contact drives that
    # ball into the bed (momentum kept in three axes), and the bed throws it up at e_t
    # of that speed (frictionless bed here: its velocity on the cloth passes).
    result = flight(2.0, (2.0, 0.0), others=((1.2, 0.5325),), sliding_friction=0.0)
    motion = result.motion
    assert isinstance(motion, SpinMotion) and motion.vz0 is not None and motion.z0 is not None
    hit = next(event for event in result.events if event.kind == "ball")
    rows = {ball: segments_of(result, ball) for ball in (0, 1)}
    before = {ball: max(r for r in rows[ball] if motion.t0[r] < hit.time) for ball in (0, 1)}
    after = {ball: min(r for r in rows[ball] if motion.t0[r] == hit.time) for ball in (0, 1)}
    tau = hit.time - motion.t0[before[0]]
    flyer = [*motion.v0[before[0]], motion.vz0[before[0]] - G * tau]
    struck_at = [*result.positions_at(np.array([hit.time]))[0, 1], R]
    flyer_at = [*result.positions_at(np.array([hit.time]))[0, 0], motion.z0[after[0]]]
    row = [*flyer_at, *struck_at, *flyer, MASS, 0.0, 0.0, 0.0, MASS, seed.RESTITUTION]
    impact = probe.ball_impacts(np.array(row)[None])[0]
    assert np.allclose(impact[:3] + impact[3:6], flyer, rtol=0, atol=1e-14)  # momentum
    assert impact[5] < 0  # the struck ball is driven into the bed
    struck = after[1]
    assert motion.state[struck] == FLYING
    assert motion.v0[struck].tolist() == pytest.approx(impact[3:5].tolist(), rel=1e-12)
    assert motion.vz0[struck] == pytest.approx(-E_T * impact[5], rel=1e-12)
    assert motion.vz0[after[0]] == pytest.approx(impact[2], rel=1e-12)
    # Energy never rises: the contact keeps it (elastic), the bed takes (1 - e_t^2).
    was = kinetic(np.array(flyer), np.zeros(3))
    now = kinetic(np.array([*motion.v0[after[0]], motion.vz0[after[0]]]), np.zeros(3))
    now += kinetic(np.array([*motion.v0[struck], motion.vz0[struck]]), np.zeros(3))
    assert now <= was * (1 + 8 * EPS)


def test_the_airborne_key_lets_balls_fly_and_costs_a_level_break_nothing() -> None:
    pool = (default_scene_path().parent / "pool_break.toml").read_text()
    lifted = scene_from_text(pool.replace('model = "spin"', 'model = "spin"\nairborne = true'))
    assert lifted.physics.airborne
    setup = setup_from_scene(lifted)
    assert setup.drives is not None and not setup.drives.any()  # a level cue: no drive
    from tests.test_fingerprints import PINS, fingerprint

    assert fingerprint(simulate_scene(lifted)) == PINS["pool_break", "exact", None]


@pytest.mark.parametrize(
    ("change", "said"),
    [
        ('model = "spin"\nairborne = true\ngravity = 0', "physics.gravity = 0"),
        ('model = "rolling"\nairborne = true', 'physics.model = "spin" first'),
    ],
)
def test_the_airborne_key_refuses_a_scene_that_cannot_fly(change: str, said: str) -> None:
    from billiards.scene.reader import SceneError

    text = (default_scene_path().parent / "pool_break.toml").read_text()
    text = text.replace('cushion_model = "han2005"\n', "").replace('model = "spin"', change)
    text = text.replace("tip = [0.0, 0.2]\n", "")
    with pytest.raises(SceneError, match=said) as refused:
        scene_from_text(text)
    assert "\n" not in str(refused.value)


def test_the_hop_break_lifts_an_object_ball_and_never_gains_energy() -> None:
    scene = load_scene(default_scene_path().parent / "hop_break.toml")
    assert scene.physics.airborne
    result = simulate_scene(scene, method="event")
    motion = result.motion
    assert isinstance(motion, SpinMotion) and motion.vz0 is not None
    ids = scene.ball_ids
    flew = {ids[motion.ball[row]] for row in range(len(motion.ball)) if motion.state[row] == FLYING}
    assert "cue" in flew and flew - {"cue"}, flew  # the cue ball hops, an object ball flies
    first = next(event for event in result.events if event.kind == "ball")
    assert first.balls == ("cue", "1")
    at = np.array([first.time])
    assert result.heights_at(at)[0, 0] > R + 0.01  # in the air, on the head ball's upper half
    times = np.linspace(0.0, 1.0, 4001)
    assert result.heights_at(times).min() >= R * (1 - 1e-12)
    previous = 0.0
    for event in result.events:
        if event.time <= previous or event.kind == "pocket":
            continue
        before = event.time - min(1e-9, (event.time - previous) / 2)
        totals = energies(result, np.array([before, event.time])).sum(axis=1)
        assert totals[1] <= totals[0] * (1 + 1e-9) + 1e-12, event
        previous = event.time


def into_the_corner(start: float, drive: float, speed: float) -> SimulationResult:
    """A ball at (start, start) sent at `speed` straight into the corner pocket at the
    origin, driven into the bed at `drive`."""
    return run(corner_setup(start, drive, speed), ("0",), "event", seed.DT)


def corner_setup(start: float, drive: float, speed: float) -> Setup:
    """into_the_corner's setup."""
    from billiards.physics.pockets import pocket_table

    holes = (seed.TABLE_SIZE, R, seed.CORNER_POCKET_WIDTH, seed.SIDE_POCKET_WIDTH, seed.JAW_RADIUS)
    velocity = (-speed / np.sqrt(2.0), -speed / np.sqrt(2.0))
    return Setup.of(
        [(start, start)],
        [velocity],
        spins=[(0.0, 0.0, 0.0)],
        model="spin",
        drives=[drive],
        pockets=pocket_table(*holes),
        max_time=20.0,
    )


def test_a_ball_flying_low_over_a_pocket_drops_into_it() -> None:
    result = into_the_corner(0.12, 1.2, 2.0)
    (drop,) = result.events
    assert drop.kind == "pocket" and drop.pocket is not None
    z = result.heights_at(np.array([drop.time * (1 - 1e-12)]))[0, 0]
    assert R < z <= seed.CUSHION_HEIGHT + R  # in the air, below the rim: it falls in
    assert [each.ball for each in result.pocketed] == ["0"]


def test_a_ball_flying_high_over_a_pocket_leaves_the_table() -> None:
    result = into_the_corner(0.25, 6.0, 1.5)
    (gone,) = result.events
    assert (gone.kind, gone.pocket) == ("pocket", None)  # off the table, not pocketed
    z = result.heights_at(np.array([gone.time * (1 - 1e-12)]))[0, 0]
    assert z > seed.CUSHION_HEIGHT + R
    assert result.pocketed == ()


# --- shown: a ball that left the table ---------------------------------------------------


def test_a_ball_that_left_the_table_flies_on_in_the_film_and_then_vanishes() -> None:
    from billiards.record.drop import GONE_DEPTH, OFF_TABLE_GONE, off_table_end
    from billiards.record.sampling import record_trajectory
    from billiards.record.window import motion_end

    result = at_the_foot_cushion(2.0, 6.0)  # over the foot rail at 0.13 s
    (gone,) = result.events
    end = off_table_end(result)
    assert motion_end(result) == end > gone.time + 0.3  # the film waits for its fall
    trajectory = record_trajectory(result, fps=200.0, end=end + 0.1)
    times, drawn = trajectory.times, trajectory.positions[:, 0]
    flying = (times > gone.time) & (times < end)
    # On along its parabola past the rail: x = 2 + t (1 m/s), z its flight's.
    assert np.allclose(drawn[flying, 0], 2.0 + times[flying], rtol=0, atol=1e-6)
    assert drawn[flying, 0].min() > seed.TABLE_SIZE[0]
    launch = E_T * 6.0
    z = R + launch * times[flying] - 0.5 * G * times[flying] ** 2
    assert np.allclose(drawn[flying, 2], z, rtol=0, atol=1e-6)
    assert np.all(drawn[times > end, 2] == GONE_DEPTH)  # out of sight, fallen past the edge
    assert drawn[flying, 2].min() > -OFF_TABLE_GONE


def test_the_top_view_says_a_ball_left_the_table_and_draws_it_nowhere_at_rest() -> None:
    from billiards.pictures.top_view import (
        _summary,
        left_the_table,
        pocketed_marks,
        sample_path_bends,
    )

    result = at_the_foot_cushion(2.0, 6.0)
    trajectory = sample_path_bends(result, seed.TABLE_SIZE)
    assert left_the_table(trajectory) == ["0"]
    assert pocketed_marks(trajectory) == []  # no hole holds it
    assert _summary(trajectory, [], ["0"]).endswith("; off the table: 0")
    # Its path runs on over the rail, in the air.
    assert trajectory.positions[-1, 0, 0] > seed.TABLE_SIZE[0] + 0.1


def test_the_gltf_tracks_fly_a_ball_that_left_the_table_on_and_hide_it() -> None:
    from billiards.export.tracks import evaluate_keys, motion_tracks
    from billiards.record.drop import departures, flight_at, off_table_end

    result = at_the_foot_cushion(2.0, 6.0)
    (track,) = motion_tracks(result, result.transitions).balls
    end = off_table_end(result)
    assert track.hidden_from == pytest.approx(end, rel=1e-12)
    times = np.linspace(0.0, end, 400)
    drawn = evaluate_keys(track.times, track.values, track.in_tangents, track.out_tangents, times)
    (departure,) = departures(result)
    gone = result.events[0].time
    after = times > gone
    assert np.allclose(drawn[after], flight_at(departure, times[after])[0], rtol=0, atol=1e-6)
    before = ~after
    flat = result.motion.positions_at(times[before])[:, 0]
    assert np.allclose(drawn[before, :2], flat, rtol=0, atol=1e-9)
    assert np.allclose(drawn[before, 2], result.heights_at(times[before])[:, 0], atol=1e-9)
