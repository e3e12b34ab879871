"""The invariants a hard case must keep, checked from a SimulationResult alone.

Each check reads the result the way a user would (positions, events) plus the
anchors of an exact run (result.motion: one row per ball per contact, in the order
the contacts were resolved), so that velocities just before and just after every
contact are known exactly, without finite differences.

- `check_no_overlap`: centre distances >= 2r - 1e-9 m exactly at every anchor time
  and on a grid inside every interval between anchors, dense enough that no ball
  moves more than r/4 between samples (between anchors each ball rolls along one
  straight line, so a ball passing through another cannot fall between samples).
- `check_inside_cushions`: the raw (unclamped) motion stays within 1e-9 m of the
  cushion lines.
- `check_energy_never_rises`: kinetic energy just before and just after every
  contact instant, in time order, never increases.
- `check_contacts_conserve_momentum`: at every instant, each group of balls linked
  by ball-ball contacts (and touching no cushion at that instant) keeps its total
  momentum, and its kinetic energy if the contacts are elastic.
- `event_count_bound`: an upper bound on the number of events, derived below.
- `check_spin_case`: every invariant of a spin-model run (issue 22), with or without
  pockets: ended by itself within WALL_LIMIT s of CPU for fewer than WALL_LIMIT_BALLS
  balls, no overlap (naive's steps too), translational plus rotational energy never
  rising (`check_spin_energy_never_rises`), momentum at every contact, `exact` ==
  `event`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

from billiards.physics.engine.result import AnchoredMotion, SampledMotion, SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.laws.ball_ball import ELASTIC_BELOW
from billiards.physics.methods import entry as methods
from billiards.physics.numerics.arithmetic import dot, total

FloatArray = npt.NDArray[np.float64]

R = 0.0286  # m, the seed report's ball radius
TABLE = (2.13, 1.065)  # m
DECEL = 0.01 * 9.81  # m/s^2, mu g
OVERLAP_TOLERANCE = 1e-9  # m: no ball may overlap another (or pass a cushion) by more
SAMPLE_TRAVEL = R / 4  # m: no ball moves further than this between overlap samples
EXACT_METHODS = ("event", "exact")
# m/s: a speed whose square underflows (sqrt(v . v) = 0), rest by the physics' rule.
REST_SPEED = 1.5e-162


def make_setup(
    positions: FloatArray,
    velocities: FloatArray,
    masses: FloatArray | None = None,
    *,
    max_time: float = 600.0,
    **overrides: Any,
) -> Setup:
    """Setup.of with the seed's defaults, but a longer max_time: hard cases roll long."""
    return Setup.of(positions, velocities, masses, max_time=max_time, **overrides)


def run(setup: Setup, method: str = "event", dt: float = 1 / 240) -> SimulationResult:
    ids = tuple(f"b{index}" for index in range(len(setup.positions)))
    return methods.run(setup, ids, method, dt)


def _case_marks(
    known: dict[int, str], lenient: set[int], case: int, hard: bool
) -> list[pytest.MarkDecorator]:
    marks = [pytest.mark.hard] if hard else []
    if case in known:
        marks.append(pytest.mark.xfail(strict=case not in lenient, reason=known[case]))
    return marks


def _hard_selected(markexpr: str) -> bool:
    return "hard" in markexpr and "not hard" not in markexpr


def generate_families(
    metafunc: pytest.Metafunc,
    families: dict[str, int],
    sample: dict[str, int],
    seed: int,
    xfail: dict[str, dict[int, str]] | None = None,
    lenient: dict[str, set[int]] | None = None,
) -> None:
    """Parametrize each random family a test names (a fixture per family: the case
    index): the full family under `-m hard` (each case marked hard), else a seeded
    sample of it. xfail: family -> {case: reason}, cases known to fail, marked strict
    xfails (so each must still fail, and passing one is flagged to be unmarked);
    lenient: family -> cases among them whose xfail is not strict (a CPU time near its
    limit, which a loaded machine may or may not cross)."""
    for family, size in families.items():
        if family not in metafunc.fixturenames:
            continue
        known = (xfail or {}).get(family, {})
        loose = (lenient or {}).get(family, set())
        if _hard_selected(metafunc.config.option.markexpr or ""):
            params = [
                pytest.param(i, marks=_case_marks(known, loose, i, True)) for i in range(size)
            ]
        else:
            chosen = np.random.default_rng(seed).choice(size, sample[family], replace=False)
            params = [
                pytest.param(int(i), marks=_case_marks(known, loose, int(i), False))
                for i in sorted(chosen)
            ]
        metafunc.parametrize(family, params, ids=str)


# --- reading the anchors -----------------------------------------------------------------


@dataclass(frozen=True)
class Instant:
    """Velocities of every ball just before and just after one contact instant."""

    time: float
    before: FloatArray  # (N, 2)
    after: FloatArray  # (N, 2)


def anchored(result: SimulationResult) -> AnchoredMotion:
    assert isinstance(result.motion, AnchoredMotion), "needs an exact run (event or exact)"
    return result.motion


def instants(result: SimulationResult) -> list[Instant]:
    """Every distinct anchor time, with velocities either side of it (at t = 0: the
    initial velocities, and those after any contact at the very start)."""
    motion = anchored(result)
    times = np.unique(motion.t0)
    before = motion.segment_state(motion.segments_at(times, side="left"), times[:, None])[1]
    after = motion.segment_state(motion.segments_at(times), times[:, None])[1]
    return [Instant(time, before[k], after[k]) for k, time in enumerate(times.tolist())]


def kinetic_energy(
    masses: FloatArray,
    velocities: FloatArray,
    spins: FloatArray | None = None,
    radius: float | None = None,
) -> float:
    """Translational energy, plus rotational (I = 2/5 m R^2) with `spins` (and the balls'
    `radius`, which they need), summed exactly."""
    energy = dot(velocities, velocities)
    if spins is not None:
        assert radius is not None, "a rotational energy needs the radius"
        energy = energy + 0.4 * radius * radius * dot(spins, spins)
    return 0.5 * total(masses * energy)


# --- the invariants ----------------------------------------------------------------------


def sample_times(result: SimulationResult) -> FloatArray:
    """Every anchor time, plus a grid inside each interval between anchors on which no
    ball moves more than SAMPLE_TRAVEL.

    Between anchors each ball's velocity is linear in time (constant acceleration, then
    at rest), so its speed, a convex function, is largest at one end of the interval:
    just after the anchor that opens it or just before the one that closes it. In the
    rolling model that is always the first (speeds only fall); in the spin model a ball
    that starts to slide from rest, or whose spin drives it, speeds up until the next."""
    motion = anchored(result)
    breaks = np.unique(np.concatenate([motion.t0, [result.rest_time]]))
    breaks = breaks[breaks <= result.rest_time]
    # Each ball's speed just after each break and just before the next, all at once.
    after = motion.velocities_at(breaks[:-1])
    ends = breaks[1:]
    before = motion.segment_state(motion.segments_at(ends, side="left"), ends[:, None])[1]
    speeds = np.maximum(np.hypot(after[..., 0], after[..., 1]), np.hypot(*before.T).T)
    fastest = np.max(speeds, axis=1, initial=0.0)
    counts = np.ceil(fastest * np.diff(breaks) / SAMPLE_TRAVEL).astype(int)
    pieces = [breaks]
    for start, end, count in zip(
        breaks[:-1].tolist(), breaks[1:].tolist(), counts.tolist(), strict=True
    ):
        if count > 1:
            pieces.append(np.linspace(start, end, count + 1)[1:-1])
    return np.unique(np.concatenate(pieces))


def raw_positions(result: SimulationResult, times: FloatArray) -> FloatArray:
    """Positions from the motion itself, without the result's clamp to the cushions."""
    return result.motion.positions_at(np.asarray(times, dtype=np.float64))


def smallest_gap(
    result: SimulationResult,
    times: FloatArray,
    chunk: int = 2048,
    positions_at: Callable[[SimulationResult, FloatArray], FloatArray] | None = None,
) -> float:
    """Smallest centre distance minus 2r over `times` (inf for a single ball), of the
    positions `positions_at` gives (default: raw_positions).

    Exact, without looking at every pair: at each time the balls are sorted by x, and
    neighbours k places apart in that order are compared for k = 1, 2, ... until even
    their x distance exceeds the smallest distance found (it only grows with k)."""
    count = len(result.ball_ids)
    if count < 2:
        return math.inf
    smallest = math.inf
    for start in range(0, len(times), chunk):
        positions = (positions_at or raw_positions)(result, times[start : start + chunk])
        order = np.argsort(positions[..., 0], axis=1, kind="stable")
        ordered = np.take_along_axis(positions, order[..., None], axis=1)
        for apart in range(1, count):
            delta = ordered[:, apart:] - ordered[:, :-apart]
            if float(delta[..., 0].min()) >= smallest:
                break
            smallest = min(smallest, float(np.hypot(delta[..., 0], delta[..., 1]).min()))
    return smallest - 2 * result.radius


def check_no_nan(result: SimulationResult) -> None:
    motion = anchored(result)
    assert np.isfinite(motion.p0).all() and np.isfinite(motion.v0).all(), "NaN in the anchors"
    assert np.isfinite(motion.t0).all(), "NaN or inf in an anchor time"
    assert all(math.isfinite(e.time) and math.isfinite(e.impact_speed) for e in result.events)
    assert math.isfinite(result.rest_time)


def check_no_overlap(result: SimulationResult, times: FloatArray) -> None:
    gap = smallest_gap(result, times)
    assert gap >= -OVERLAP_TOLERANCE, f"two balls overlap by {-gap:.3g} m"


def check_inside_cushions(result: SimulationResult, times: FloatArray) -> None:
    positions = raw_positions(result, times)
    length, width = result.table_size
    r = result.radius
    worst = max(
        r - positions[..., 0].min(),
        positions[..., 0].max() - (length - r),
        r - positions[..., 1].min(),
        positions[..., 1].max() - (width - r),
    )
    assert worst <= OVERLAP_TOLERANCE, f"a ball is {worst:.3g} m past a cushion line"


def check_energy_never_rises(result: SimulationResult) -> None:
    masses = result.masses
    energy = [kinetic_energy(masses, result.initial_velocities)]
    for instant in instants(result):
        energy += [kinetic_energy(masses, instant.before), kinetic_energy(masses, instant.after)]
    steps = np.diff(energy)
    allowed = 1e-12 * energy[0] + 1e-300
    assert np.all(steps <= allowed), f"kinetic energy rose by {steps.max():.3g} J"


def check_contacts_conserve_momentum(
    result: SimulationResult, restitution: float, *, frictionless: bool = True
) -> None:
    """Per instant, each cluster of balls joined by ball-ball contacts (none of them at a
    cushion at that instant, nor pushed by the cloth: a held push, laws.held, logged as
    the balls' state changes) keeps its momentum, and its energy when elastic (but for a
    held contact, which is plastic: logged at impact speed 0, or in the spin model a soft
    one, below ELASTIC_BELOW, which a slip presses back and the calendar holds) and
    frictionless (the frictional ball law turns speed into spin and loses some to its
    slip, which check_spin_energy_never_rises bounds)."""
    ids = {ball_id: index for index, ball_id in enumerate(result.ball_ids)}
    soft = ELASTIC_BELOW if result.model == "spin" else 0.0
    zero_speed: dict[float, list[tuple[float, tuple[int, ...]]]] = {}
    for event in result.events:
        if event.kind == "ball" and (event.impact_speed == 0 or event.impact_speed < soft):
            zero_speed.setdefault(event.time, []).append((0.0, tuple(ids[b] for b in event.balls)))
    changed: dict[float, set[int]] = {}
    for change in result.transitions:
        changed.setdefault(change.time, set()).add(ids[change.ball])
    by_time: dict[float, list[tuple[str, tuple[int, ...]]]] = {}
    for event in result.events:
        by_time.setdefault(event.time, []).append((event.kind, tuple(ids[b] for b in event.balls)))
    masses = result.masses
    for instant in instants(result):
        contacts = by_time.get(instant.time, [])
        # A cushion, jaw or pocket takes momentum from outside the cluster.
        at_cushion = {balls[0] for kind, balls in contacts if kind != "ball"}
        at_cushion |= changed.get(instant.time, set())
        for cluster in _clusters([balls for kind, balls in contacts if kind == "ball"]):
            if cluster & at_cushion:
                continue
            members = np.array(sorted(cluster))
            m = masses[members, None]
            before = (m * instant.before[members]).sum(axis=0)
            after = (m * instant.after[members]).sum(axis=0)
            # Plus the momentum of a ball at REST_SPEED, which the physics calls rest
            # (spin.motion.classify: its speed underflows to 0), by member.
            scale = float((m * np.abs(instant.before[members])).sum()) + 1e-300
            scale += 1e13 * REST_SPEED * float(m.sum())
            assert np.all(np.abs(after - before) <= 1e-13 * scale * len(members)), (
                f"momentum changed by {after - before} at t = {instant.time}"
            )
            held = any(
                speed == 0 and set(balls) <= cluster
                for speed, balls in zero_speed.get(instant.time, [])
            )
            if restitution == 1.0 and frictionless and not held:
                # (A held contact, laws.held, logged at impact speed 0, is plastic.)
                e_before = kinetic_energy(masses[members], instant.before[members])
                e_after = kinetic_energy(masses[members], instant.after[members])
                assert abs(e_after - e_before) <= 1e-13 * e_before * len(members), (
                    f"an elastic contact changed the energy by {e_after - e_before:.3g} J"
                )


def _clusters(pairs: list[tuple[int, ...]]) -> list[set[int]]:
    clusters: list[set[int]] = []
    for pair in pairs:
        joined = set(pair)
        for cluster in [c for c in clusters if c & joined]:
            joined |= cluster
            clusters.remove(cluster)
        clusters.append(joined)
    return clusters


# --- how many events a run may have --------------------------------------------------------


def path_length_bound(setup: Setup) -> float:
    """Total distance all balls can roll: S <= E0 / (mu g m_min).

    Rolling friction takes mu g m_i joules per metre from ball i, contacts never add
    energy, so sum_i m_i s_i <= E0. Without friction, or with max_time first, no ball
    is ever faster than v_max = sqrt(2 E0 / m_min) (it would hold all the energy), so
    S <= N v_max max_time also holds.
    """
    energy = kinetic_energy(setup.masses, setup.velocities)
    lightest = float(setup.masses.min())
    count = len(setup.masses)
    by_time = count * math.sqrt(2 * energy / lightest) * setup.max_time
    if setup.decel > 0:
        return min(energy / (setup.decel * lightest), by_time)
    return by_time


def cushion_contact_bound(setup: Setup, ball_contacts: int) -> float:
    """Cushion contacts C <= 2N + 4B + S (1/(L - 2r) + 1/(W - 2r)).

    Cut ball i's run at its B_i ball-ball contacts into B_i + 1 stretches. Within a
    stretch the ball only meets cushions, and two x-cushion contacts in a row are on
    opposite cushions (a bounce reverses vx, only the far cushion reverses it back),
    L - 2r apart in x; likewise in y. So a stretch of length s holds at most
    2 + s / (L - 2r) + s / (W - 2r) cushion contacts (a corner counts one of each).
    Summing over stretches and balls with sum_i B_i = 2B and sum_i s_i = S gives the
    bound; S is bounded by `path_length_bound`.
    """
    length, width = setup.table_size
    r = setup.radius
    count = len(setup.masses)
    per_metre = 1 / (length - 2 * r) + 1 / (width - 2 * r)
    return 2 * count + 4 * ball_contacts + path_length_bound(setup) * per_metre


def check_event_count(result: SimulationResult, setup: Setup) -> None:
    """Cushion contacts within their proven bound, and the run finished within the
    max_events guard (the only bound on ball-ball contacts; see test_hard_cases)."""
    ball_contacts = sum(1 for event in result.events if event.kind == "ball")
    cushion_contacts = len(result.events) - ball_contacts
    bound = cushion_contact_bound(setup, ball_contacts)
    assert cushion_contacts <= bound, f"{cushion_contacts} cushion contacts > bound {bound:.0f}"
    assert len(result.events) <= setup.max_events, "the max_events guard ended the run"


def check_sound(result: SimulationResult, setup: Setup) -> None:
    """Every invariant of an exact run (determinism: see check_methods_agree_bit_for_bit)."""
    check_no_nan(result)
    times = sample_times(result)
    check_inside_cushions(result, times)
    check_no_overlap(result, times)
    check_energy_never_rises(result)
    check_contacts_conserve_momentum(result, setup.restitution)
    check_event_count(result, setup)


def fingerprint(result: SimulationResult) -> tuple[object, ...]:
    """Everything a run produces, as exact values (bit-identical runs compare equal)."""
    motion = anchored(result)
    return (
        tuple((e.time, e.kind, e.balls, e.impact_speed, e.pocket) for e in result.events),
        result.rest_time,
        motion.ball.tobytes(),
        motion.t0.tobytes(),
        motion.p0.tobytes(),
        motion.v0.tobytes(),
    )


def check_methods_agree_bit_for_bit(setup: Setup, reference: SimulationResult) -> None:
    """`exact` at a step reproduces the `event` reference exactly. That is also the
    rerun check: the stepped run goes through the same calendar again from scratch, so
    any run-to-run difference (state leaking between runs, unseeded order) shows here;
    reruns of one method are pinned for the shipped scenes (tests/test_fingerprints.py)."""
    stepped = run(setup, "exact", dt=1 / 240)
    assert fingerprint(stepped) == fingerprint(reference), "exact differs from event"


# --- tables with pockets -----------------------------------------------------------------


def capture_times(result: SimulationResult) -> FloatArray:
    """When each ball was pocketed (inf: never)."""
    drops = np.full(len(result.ball_ids), np.inf)
    for event in result.events:
        if event.kind == "pocket":
            drops[result.ball_ids.index(event.balls[0])] = event.time
    return drops


def on_table_positions(result: SimulationResult, times: FloatArray) -> FloatArray:
    """Raw positions, with each pocketed ball moved far off (and apart) once gone."""
    positions = raw_positions(result, times)
    gone = times[:, None] > capture_times(result)[None, :]
    away = 1e6 + 10.0 * np.arange(len(result.ball_ids))
    positions[..., 0] = np.where(gone, away[None, :], positions[..., 0])
    positions[..., 1] = np.where(gone, 1e6, positions[..., 1])
    return positions


def check_no_pocketed_overlap(result: SimulationResult, times: FloatArray) -> None:
    """No two balls still on the table overlap (a pocketed ball is gone)."""
    gap = smallest_gap(result, times, positions_at=on_table_positions)
    assert gap >= -OVERLAP_TOLERANCE, f"two balls overlap by {-gap:.3g} m"


def check_on_pocket_table(result: SimulationResult, times: FloatArray) -> None:
    """No ball (until pocketed) past a cushion line where the cushion exists, within a
    jaw's reach, or past a capture line, by more than 1e-9 m."""
    pockets = result.pockets
    assert pockets is not None
    positions = raw_positions(result, times)
    playing = times[:, None] <= capture_times(result)[None, :]
    p = positions[playing]  # (M, 2): every ball still on the table, at every time
    length, width = result.table_size
    r = result.radius
    lines = ((0, r, -1.0), (0, length - r, 1.0), (1, r, -1.0), (1, width - r, 1.0))
    for (axis, line, side), segments in zip(lines, pockets.segments, strict=True):
        along = p[:, 1 - axis]
        covered = ((along[:, None] >= segments[:, 0]) & (along[:, None] <= segments[:, 1])).any(1)
        past = side * (p[covered, axis] - line)
        worst = float(past.max(initial=-np.inf))
        assert worst <= OVERLAP_TOLERANCE, f"a ball is {worst:.3g} m past a cushion"
    offset = p[:, None, :] - pockets.jaws[None]
    inside = pockets.jaw_reach - np.hypot(offset[..., 0], offset[..., 1]).min(
        axis=1, initial=np.inf
    )
    worst = float(inside.max(initial=-np.inf))
    assert worst <= OVERLAP_TOLERANCE, f"a ball is {worst:.3g} m inside a jaw"
    beyond = float((p @ pockets.capture_normal.T - pockets.capture_level).max(initial=-np.inf))
    assert beyond <= OVERLAP_TOLERANCE, f"a ball is {beyond:.3g} m past a capture line unpocketed"


def check_pocketed(result: SimulationResult) -> None:
    """Each pocketed ball dropped once, on its pocket's capture line, and nothing
    involves it afterwards."""
    pockets = result.pockets
    assert pockets is not None
    drops = capture_times(result)
    dropped = [event for event in result.events if event.kind == "pocket"]
    assert len({event.balls[0] for event in dropped}) == len(dropped), "a ball dropped twice"
    for event in dropped:
        ball = result.ball_ids.index(event.balls[0])
        where = raw_positions(result, np.array([event.time]))[0, ball]
        pocket = pockets.names.index(str(event.pocket))
        across = float(where @ pockets.capture_normal[pocket] - pockets.capture_level[pocket])
        assert abs(across) <= OVERLAP_TOLERANCE, f"dropped {across:.3g} m off the capture line"
    for event in result.events:
        later = [drops[result.ball_ids.index(b)] < event.time for b in event.balls]
        assert not any(later), f"a {event.kind} contact at t = {event.time} involves a gone ball"


def check_pocket_sound(result: SimulationResult, setup: Setup) -> None:
    """Every invariant of an exact run on a table with pockets."""
    check_no_nan(result)
    times = sample_times(result)
    check_on_pocket_table(result, times)
    check_no_pocketed_overlap(result, times)
    check_energy_never_rises(result)
    check_contacts_conserve_momentum(result, setup.restitution)
    check_pocketed(result)
    assert len(result.events) <= setup.max_events, "the max_events guard ended the run"


# --- the spin model ----------------------------------------------------------------------

WALL_LIMIT = 2.0  # s of CPU: no run of fewer than WALL_LIMIT_BALLS balls may take longer
WALL_LIMIT_BALLS = 20


def check_spin_energy_never_rises(result: SimulationResult, times: FloatArray) -> None:
    """Translational plus rotational energy, just before and at every sample time
    (every anchor among them), never rises beyond rounding (spin turns into speed, so
    the translational energy alone may)."""
    every = np.unique(np.concatenate([times, np.nextafter(times, -np.inf)]))
    velocities = result.velocities_at(every)
    spins = result.spins_at(every)
    energy = np.array(
        [
            kinetic_energy(result.masses, v, w, result.radius)
            for v, w in zip(velocities, spins, strict=True)
        ]
    )
    rise = float(np.diff(energy).max(initial=0.0))
    assert rise <= 1e-12 * energy[0] + 1e-300, f"energy rose by {rise:.3g} J"


def check_naive_never_overlaps(setup: Setup) -> None:
    """The stepped method's output (every step) holds no overlap beyond 1e-9 m between
    balls still on the table."""
    result = run(setup, "naive")
    assert isinstance(result.motion, SampledMotion)
    positions_at = None if setup.pockets is None else on_table_positions
    gap = smallest_gap(result, result.motion.times, positions_at=positions_at)
    assert gap >= -OVERLAP_TOLERANCE, f"naive: two balls overlap by {-gap:.3g} m"


def check_spin_case(
    setup: Setup, *, naive: bool = True, spins_on: bool = False
) -> SimulationResult:
    """Every invariant of issue 22 on one spin-model setup, with or without pockets:
    the `event` run ends by itself (not cut by max_time or max_events) within WALL_LIMIT
    of CPU for fewer than WALL_LIMIT_BALLS balls; no overlap beyond 1e-9 m on the grid
    of sample_times (and, with `naive`, none in the naive method's steps); nothing past
    a cushion (or a jaw or capture line); the energy never rises; momentum kept at
    every ball-ball contact; `exact` equal to `event` bit for bit. A RuntimeWarning is
    an error under the suite's filterwarnings. spins_on: a ball may still spin about
    the vertical at max_time (no spinning friction), every ball otherwise at rest.
    Returns the `event` run."""
    started = time.process_time()
    result = run(setup, "event")
    spent = time.process_time() - started
    assert result.stopped_by != "max_events", "the max_events guard ended the run"
    if spins_on and not result.complete:
        end = np.array([result.rest_time])
        assert not result.velocities_at(end).any(), "a ball still moves at max_time"
        assert not result.spins_at(end)[..., :2].any(), "a ball still rolls at max_time"
    else:
        assert result.complete, f"the run did not come to rest ({result.stopped_by})"
    if len(setup.positions) < WALL_LIMIT_BALLS:
        assert spent <= WALL_LIMIT, f"{spent:.2f} s of CPU, {len(result.events)} events"
    check_no_nan(result)
    times = sample_times(result)
    if setup.pockets is None:
        check_inside_cushions(result, times)
        check_no_overlap(result, times)
    else:
        check_on_pocket_table(result, times)
        check_no_pocketed_overlap(result, times)
        check_pocketed(result)
    check_spin_energy_never_rises(result, times)
    check_contacts_conserve_momentum(
        result, setup.restitution, frictionless=setup.ball_law == "frictionless"
    )
    stepped = run(setup, "exact", dt=1 / 240)
    assert fingerprint(stepped) == fingerprint(result), "exact differs from event"
    assert stepped.transitions == result.transitions, "exact's transitions differ"
    if naive:
        check_naive_never_overlaps(setup)
    return result
