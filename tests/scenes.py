"""Small scene builders shared by the physics tests."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from billiards.physics.engine.result import AnchoredMotion, SimulationResult
from billiards.scene.reader import Scene, parse_scene
from tests import hard_checks

R = hard_checks.R
MU_G = hard_checks.DECEL


def scene_of(
    balls: Sequence[tuple[str, Sequence[float], Sequence[float]]],
    *,
    masses: dict[str, float] | None = None,
    extra: str = "",
) -> Scene:
    """A scene with explicit balls (id, position, velocity) and extra TOML on top."""
    lines = [extra]
    for ball_id, position, velocity in balls:
        lines += [
            "[[ball]]",
            f'id = "{ball_id}"',
            f"position = [{float(position[0])!r}, {float(position[1])!r}]",
            f"velocity = [{float(velocity[0])!r}, {float(velocity[1])!r}]",
        ]
        if masses and ball_id in masses:
            lines.append(f"mass = {masses[ball_id]!r}")
    return parse_scene("\n".join(lines), "test.toml")


def break_scene(speed: float = 3.0, gap: float = 0.0001, offset: float = 0.0) -> Scene:
    return parse_scene(
        f"""
        [rack]
        gap = {gap!r}
        [[ball]]
        id = "cue"
        position = [0.5325, {0.5325 + offset!r}]
        velocity = [{speed!r}, 0.0]
        mass = 0.170
        """,
        "break.toml",
    )


def sample_times(result: SimulationResult, count: int = 500) -> np.ndarray:
    """Every contact time (and the instant before it), an even grid, and for exact runs
    the hard-case grid on which no ball moves more than r/4 between samples."""
    events = np.array([event.time for event in result.events])
    grid = np.linspace(0.0, result.rest_time, count)
    fine = hard_checks.sample_times(result) if isinstance(result.motion, AnchoredMotion) else grid
    return np.unique(np.concatenate([grid, fine, events, np.nextafter(events, -np.inf)]))


def min_gap(result: SimulationResult, times: np.ndarray) -> float:
    """Smallest centre distance minus 2r over the times (inf for one ball)."""
    return hard_checks.smallest_gap(result, times)


def kinetic_energy(result: SimulationResult, times: np.ndarray) -> np.ndarray:
    velocities = result.velocities_at(times)
    return 0.5 * np.sum(result.masses * np.sum(velocities**2, axis=2), axis=1)


def assert_sound(result: SimulationResult, tolerance: float = 1e-9) -> None:
    """The invariants every method must keep: no overlap, no escape, no NaN,
    energy never rises, and the run ends."""
    assert result.complete, "the run did not end before max_time"
    if isinstance(result.motion, AnchoredMotion):
        times = sample_times(result)
        hard_checks.check_no_nan(result)
        hard_checks.check_inside_cushions(result, times)
        hard_checks.check_no_overlap(result, times)
        hard_checks.check_energy_never_rises(result)
        return
    # The naive method claims only its own steps.
    times = result.motion.times
    positions = result.motion.positions_at(times)
    assert np.isfinite(positions).all(), "NaN or inf in positions"
    length, width = result.table_size
    r = result.radius
    assert positions[..., 0].min() >= r - tolerance, "a ball crossed the x = 0 cushion"
    assert positions[..., 0].max() <= length - r + tolerance, "a ball crossed the x = L cushion"
    assert positions[..., 1].min() >= r - tolerance, "a ball crossed the y = 0 cushion"
    assert positions[..., 1].max() <= width - r + tolerance, "a ball crossed the y = W cushion"
    assert min_gap(result, times) >= -tolerance, "two balls overlap"
    energy = kinetic_energy(result, times)
    assert np.isfinite(energy).all()
    assert np.all(np.diff(energy) <= 1e-12 * energy[0] + 1e-15), "kinetic energy rose"


def contact_velocities(result: SimulationResult) -> list[tuple[np.ndarray, np.ndarray]]:
    """For each event, the velocities of its balls just before and just after it.

    Read from the anchors: every event re-anchors each of its balls once, in order,
    so simultaneous contacts are told apart exactly."""
    motion = result.motion
    assert isinstance(motion, AnchoredMotion)
    segments = {ball: list(np.flatnonzero(motion.ball == ball)) for ball in range(motion.count)}
    used = dict.fromkeys(segments, 0)
    out = []
    for event in result.events:
        before, after = [], []
        for ball_id in event.balls:
            ball = result.ball_ids.index(ball_id)
            previous = segments[ball][used[ball]]
            used[ball] += 1
            following = segments[ball][used[ball]]
            before.append(motion.segment_state(np.array([previous]), event.time)[1][0])
            after.append(motion.v0[following])
        out.append((np.array(before), np.array(after)))
    return out
