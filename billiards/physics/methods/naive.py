"""The seed report's discrete method, kept to show what exactness buys.

Each step: move by v dt, slow by mu g dt (along the motion), then find what went
wrong: balls past a cushion are mirrored back and bounced, overlapping pairs that
approach get the contact impulse, and every overlap is pushed apart. Inaccurate by
design, but it never outputs overlapping balls, NaN, or balls stuck together.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.ball_ball import PairContact
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from billiards.physics.numerics.arithmetic import dot, length, norm
from billiards.physics.numerics.arrays import BoolArray, FloatArray
from billiards.physics.pockets import PocketTable, on_cushion, pocket_of

NaiveEvent = tuple[float, str, tuple[int, ...], float, str | None]  # last: the pocket
NaiveRun = tuple[FloatArray, FloatArray, FloatArray, FloatArray | None, list[NaiveEvent], bool]

PUSH_ROUNDS = 200  # push-apart rounds per step; dense frozen racks need a few dozen


def run_naive(setup: Setup, dt: float) -> NaiveRun:
    """(step times, positions, velocities, spins (None: rolling) per step, events, complete)."""
    positions = np.array(setup.positions, dtype=np.float64)
    velocities = np.array(setup.velocities, dtype=np.float64)
    spin_model = setup.model == "spin"
    spins = np.zeros((len(positions), 3))
    if spin_model and setup.spins is not None:
        spins = np.array(setup.spins, dtype=np.float64)
    count, r, bounds, pockets = len(positions), setup.radius, setup.bounds, setup.pockets
    gone = np.zeros(count, dtype=bool)  # pocketed: out of every pair
    upper = np.triu(np.ones((count, count), dtype=bool), k=1)
    times, history, velocity_history = [0.0], [positions.copy()], [velocities.copy()]
    spin_history = [spins.copy()]
    events: list[NaiveEvent] = []
    step, complete = 0, False
    while True:
        step += 1
        now = step * dt
        if now > setup.max_time:
            break
        positions = positions + velocities * dt
        if spin_model:
            velocities, spins = _spin_step(velocities, spins, setup, dt)
        else:
            velocities = _rolling_step(velocities, setup.decel, dt)
        balls = _Balls(setup, positions, velocities, spins, gone, upper, events, now)
        if pockets is not None:
            balls.pocket_step()
        balls.cushion_step()
        balls.collide()
        if pockets is None:
            _push_apart(positions, r, bounds, upper)
        else:
            # Pushed apart freely (a ball in a mouth is past the cushion lines), then
            # held out of the cushions and jaws again.
            _push_apart(positions, r, np.array([-np.inf, np.inf, -np.inf, np.inf]), upper)
            _hold_on_table(positions, gone, bounds, pockets)
            if _overlaps(positions, r, upper)[0].size:
                # The hold undid part of a push (a ball against a cushion or a jaw):
                # cleared one pair at a time, as without pockets (_unjam).
                _unjam(positions, r, bounds, upper, (gone, pockets))
        times.append(now)
        history.append(positions.copy())
        velocity_history.append(velocities.copy())
        if spin_model:
            spin_history.append(spins.copy())
        if not velocities.any() and not (spin_model and spins.any()):
            complete = True
            break
        if len(events) > setup.max_events:
            break
    sampled = np.array(times), np.array(history), np.array(velocity_history)
    return *sampled, np.array(spin_history) if spin_model else None, events, complete


def _rolling_step(velocities: FloatArray, decel: float, dt: float) -> FloatArray:
    """One step of the seed's rolling friction: each speed slows by mu g dt, to rest."""
    speed = norm(velocities)
    slowed = np.maximum(speed - decel * dt, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(speed[:, None] > 0, velocities * (slowed / speed)[:, None], 0.0)


@dataclass
class _Balls:
    """A naive run's balls at one step, changed in place."""

    setup: Setup
    positions: FloatArray
    velocities: FloatArray
    spins: FloatArray
    gone: BoolArray  # pocketed, out of every pair
    upper: BoolArray  # the pairs (i < j) that can still meet
    events: list[NaiveEvent]
    now: float

    def cushion_step(self) -> None:
        """Balls past a cushion line (where the cushion exists) are mirrored back in and
        bounced by the cushion law."""
        positions, velocities, spins = self.positions, self.velocities, self.spins
        bounds, pockets = self.setup.bounds, self.setup.pockets
        for axis in range(2):
            low, high = bounds[2 * axis], bounds[2 * axis + 1]
            column = positions[:, axis]
            for wall, outside in ((low, column < low), (high, column > high)):
                if pockets is not None:
                    # Only where the cushion exists: past its ends lie the pockets.
                    cushioned = on_cushion(positions[:, 1 - axis], pockets.segments[2 * axis])
                    outside &= cushioned & ~self.gone
                hit = outside.nonzero()[0]
                if hit.size == 0:
                    continue
                # Mirror back in; a ball that overshot by more than the table stays in.
                positions[hit, axis] = np.clip(2 * wall - positions[hit, axis], low, high)
                into = np.zeros((hit.size, 2))
                into[:, axis] = 1.0 if wall == high else -1.0
                balls = CushionContact(velocities[hit], spins[hit], into, self.setup.masses[hit])
                velocities[hit], spins[hit], approach = self._cushion(balls)
                self.events.extend(
                    (self.now, "cushion", (ball,), float(speed), None)
                    for ball, speed in zip(hit.tolist(), approach.tolist(), strict=True)
                )

    def pocket_step(self) -> None:
        """A ball past a capture line drops (out of every pair); one inside a jaw's reach
        is put back on it and, if closing, bounced by the cushion law."""
        positions, velocities, spins = self.positions, self.velocities, self.spins
        setup = self.setup
        pockets, gone, now = setup.pockets, self.gone, self.now
        assert pockets is not None
        which = pocket_of(pockets, positions)
        for ball in ((which >= 0) & ~gone).nonzero()[0].tolist():
            pocket = int(which[ball])
            speed = length(velocities[ball, 0], velocities[ball, 1])
            self.events.append((now, "pocket", (ball,), speed, pockets.names[pocket]))
            gone[ball] = True
            velocities[ball], spins[ball] = 0.0, 0.0
            self.upper[ball, :], self.upper[:, ball] = False, False
        reach = pockets.jaw_reach
        offset = positions[:, None, :] - pockets.jaws[None, :, :]
        distance = np.sqrt(dot(offset, offset))  # against the reach only: no denormal care
        for ball, jaw in zip(*((distance < reach) & ~gone[:, None]).nonzero(), strict=True):
            out = offset[ball, jaw] / distance[ball, jaw]
            positions[ball] = pockets.jaws[jaw] + reach * out
            if float(dot(velocities[ball], out)) >= 0:
                continue
            rows = slice(ball, ball + 1)
            balls = CushionContact(velocities[rows], spins[rows], -out[None], setup.masses[rows])
            velocities[rows], spins[rows], approaches = self._cushion(balls)
            name = pockets.names[pockets.jaw_pocket[jaw]]
            self.events.append((now, "cushion", (int(ball),), float(approaches[0]), name))

    def _cushion(self, balls: CushionContact) -> tuple[FloatArray, FloatArray, FloatArray]:
        return CUSHION_LAWS[self.setup.cushion_law](balls, CushionConstants.of(self.setup))

    def collide(self) -> None:
        """Overlapping pairs that approach get the ball law's contact."""
        velocities, spins, setup = self.velocities, self.spins, self.setup
        ball_law = BALL_LAWS[setup.ball_law]
        first, second, delta, distance = _overlaps(self.positions, setup.radius, self.upper)
        for i, j, d, dist in zip(first.tolist(), second.tolist(), delta, distance, strict=True):
            normal = d / dist if dist > 0 else np.array([1.0, 0.0])
            pair = [i, j]
            contact = PairContact(normal, velocities[pair], spins[pair], setup.masses[pair])
            after, turned, approach = ball_law(contact, setup.restitution, setup)
            if approach == 0:
                continue
            velocities[pair], spins[pair] = after, turned
            self.events.append((self.now, "ball", (i, j), approach, None))


def _hold_on_table(
    positions: FloatArray, gone: BoolArray, bounds: FloatArray, pockets: PocketTable
) -> None:
    """Put balls pushed past a cushion (where it exists) or into a jaw back on it."""
    for axis in range(2):
        low, high = bounds[2 * axis], bounds[2 * axis + 1]
        along = on_cushion(positions[:, 1 - axis], pockets.segments[2 * axis]) & ~gone
        positions[along, axis] = np.clip(positions[along, axis], low, high)
    offset, reach = positions[:, None, :] - pockets.jaws[None, :, :], pockets.jaw_reach
    distance = np.sqrt(dot(offset, offset))  # against the reach only: no denormal care
    for ball, jaw in zip(*((distance < reach) & ~gone[:, None]).nonzero(), strict=True):
        positions[ball] = pockets.jaws[jaw] + reach * offset[ball, jaw] / distance[ball, jaw]


def _spin_step(
    velocities: FloatArray, spins: FloatArray, setup: Setup, dt: float
) -> tuple[FloatArray, FloatArray]:
    """One explicit step of the spin model (billiards.physics.spin.motion), seed-style."""
    # Imported here: a rolling run loads none of the spin model.
    from billiards.physics.spin.motion import NO_SLIP, rolling_spin, slip_velocity

    r = setup.radius
    velocities, spins = velocities.copy(), spins.copy()
    slip = slip_velocity(velocities, spins, r)
    slip_speed = norm(slip)
    scale = norm(velocities) + r * norm(spins[:, :2])
    sliding = slip_speed > NO_SLIP * scale
    if sliding.any():
        slip_hat = slip[sliding] / slip_speed[sliding, None]
        # The slip shrinks at 7/2 mu_s g: a step longer than what is left ends the slide.
        share = np.minimum(setup.slide_decel * dt, slip_speed[sliding] / 3.5)
        acceleration = -slip_hat * share[:, None]
        velocities[sliding] += acceleration
        spins[sliding, :2] -= 2.5 * rolling_spin(acceleration, r)
        ended = share < setup.slide_decel * dt
        rows = sliding.nonzero()[0][ended]
        spins[rows, :2] = rolling_spin(velocities[rows], r)
    rolling = ~sliding
    velocities[rolling] = _rolling_step(velocities[rolling], setup.decel, dt)
    spins[rolling, :2] = rolling_spin(velocities[rolling], r)
    spins[:, 2] = np.sign(spins[:, 2]) * np.maximum(np.abs(spins[:, 2]) - setup.spin_decel * dt, 0)
    return velocities, spins


def _overlaps(
    positions: FloatArray, r: float, upper: np.ndarray
) -> tuple[np.ndarray, np.ndarray, FloatArray, FloatArray]:
    delta = positions[:, None, :] - positions[None, :, :]
    distance = np.sqrt(dot(delta, delta))  # against 2r only: no denormal care
    first, second = np.nonzero(upper & (distance < 2 * r))
    return first, second, delta[first, second], distance[first, second]


def _push_apart(positions: FloatArray, r: float, bounds: FloatArray, upper: np.ndarray) -> None:
    """Separate overlapping balls along their line of centres, keeping them on the table."""
    for _ in range(PUSH_ROUNDS):
        first, second, delta, distance = _overlaps(positions, r, upper)
        if first.size == 0:
            return
        safe = np.where(distance > 0, distance, 1.0)
        normal = np.where(distance[:, None] > 0, delta / safe[:, None], [1.0, 0.0])
        # A hair more than half the overlap each, so that rounding cannot leave one.
        push = (0.5 * (2 * r - distance) * (1 + 1e-9) + 1e-13)[:, None] * normal
        np.add.at(positions, first, push)
        np.add.at(positions, second, -push)
        positions[:, 0] = np.clip(positions[:, 0], bounds[0], bounds[1])
        positions[:, 1] = np.clip(positions[:, 1], bounds[2], bounds[3])
    _unjam(positions, r, bounds, upper)


JAM_SWEEPS = 10_000  # Gauss-Seidel sweeps at most; a jammed line of 15 needs a few dozen


def _unjam(
    positions: FloatArray,
    r: float,
    bounds: FloatArray,
    upper: np.ndarray,
    table: tuple[BoolArray, PocketTable] | None = None,
) -> None:
    """A line jammed on a cushion, one pair at a time (Gauss-Seidel): the clamp passes on."""
    for _ in range(JAM_SWEEPS):
        first, second, _, _ = _overlaps(positions, r, upper)
        if first.size == 0:
            return
        for i, j in zip(first.tolist(), second.tolist(), strict=True):
            delta = positions[i] - positions[j]
            distance = length(delta[0], delta[1])
            if distance >= 2 * r:
                continue
            normal = delta / distance if distance > 0 else np.array([1.0, 0.0])
            total = (2 * r - distance) * (1 + 1e-9) + 2e-13
            moved_i = _clamped_move(positions, i, 0.5 * total * normal, bounds, table)
            _clamped_move(positions, j, -(total - moved_i) * normal, bounds, table)


def _clamped_move(
    positions: FloatArray,
    ball: int,
    step: FloatArray,
    bounds: FloatArray,
    table: tuple[BoolArray, PocketTable] | None,
) -> float:
    """Move a ball by `step`, held on the table; how far it went along the step."""
    before = positions[ball].copy()
    if table is None:
        positions[ball, 0] = min(max(before[0] + step[0], bounds[0]), bounds[1])
        positions[ball, 1] = min(max(before[1] + step[1], bounds[2]), bounds[3])
    else:
        gone, pockets = table
        moved = (before + step)[None]
        _hold_on_table(moved, gone[ball : ball + 1], bounds, pockets)
        positions[ball] = moved[0]
    step_length = length(step[0], step[1])
    if step_length == 0:
        return 0.0
    return float(dot(positions[ball] - before, step)) / step_length
