"""The spin model's calendar: contacts and motion-state changes, each at its exact time.

It has the rolling calendar's interface (next_time, resolve_next, latest_stop,
event_count, log), so the stepper's event and fixed-step loops drive it unchanged,
and it looks its contact laws up in the same registries. What differs is the motion
(billiards.physics.spin_motion): every ball holds one motion state with a constant
acceleration, and the end of that state (slide -> roll, roll -> spin or rest,
spin -> rest) is a per-ball calendar entry at a closed-form time that re-anchors the
ball. A ball's cushion entry is the first root of a quadratic per wall, a pair's the
first root of the quartic |d(t)|^2 = (2r)^2, each sought only until the earlier of the
two balls' next state change, where it is asked again: contacts stay exact.
Those times are free functions of the anchors in billiards.physics.spin_contact_times.

Ties: as in the rolling calendar (cushions before pairs, lower indices first), with
motion-state changes before both (they move nothing).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from billiards.physics.arithmetic import dot, length, norm, total
from billiards.physics.calendar import ContactCalendar, ContactLog
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS, JAW_LAWS, SPIN_CUSHION_LAWS
from billiards.physics.laws.ball_ball import ELASTIC_BELOW, line_of_centres, pressed_separation
from billiards.physics.setup import Setup
from billiards.physics.spin_contact_times import cushion_contacts, pair_contacts
from billiards.physics.spin_motion import (
    REST,
    ROLLING,
    SLIDING,
    FloatArray,
    IntArray,
    classify,
    rolling_spin,
    spin_state,
    state_laws,
)


@dataclass
class SpinLog(ContactLog):
    """What happened: the rolling calendar's log (contacts and every anchor), plus the
    motion-state changes and each anchor's spin and state."""

    transitions: list[tuple[float, int, int]] = field(default_factory=list)  # t, ball, state
    segment_w0: list[FloatArray] = field(default_factory=list)
    segment_state: list[int] = field(default_factory=list)


class SpinCalendar:
    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.ball_law = BALL_LAWS[setup.ball_law]
        self.cushion_law = CUSHION_LAWS.get(setup.cushion_law)
        self.spin_cushion_law = SPIN_CUSHION_LAWS.get(setup.cushion_law)
        if self.cushion_law is None and self.spin_cushion_law is None:
            raise ValueError(f"unknown cushion law {setup.cushion_law!r}")
        self.radius = setup.radius
        count = len(setup.positions)
        self.bounds = setup.bounds
        self.t0 = np.zeros(count)
        self.p0 = np.array(setup.positions, dtype=np.float64)
        self.v0 = np.zeros((count, 2))
        self.w0 = np.zeros((count, 3))
        self.state = np.full(count, REST, dtype=np.intp)
        self.acceleration = np.zeros((count, 2))
        self.angular = np.zeros((count, 2))
        self.duration = np.full(count, np.inf)
        self.cushion_time = np.full(count, np.inf)
        self.cushion_wall = np.zeros(count, dtype=np.intp)
        self.change_time = np.full(count, np.inf)  # when each ball's motion state ends
        self.pair_time = np.full((count, count), np.inf)
        self.log = SpinLog()
        self.event_count = 0
        # Pairs parted by the pressed law, and when: never twice at one instant.
        self.pressed_at: dict[tuple[int, int], float] = {}
        # As in the rolling calendar: a ball's second contact at one instant is elastic.
        self.contact_time = np.full(len(setup.positions), -np.inf)
        # The fastest any ball has gone: the scale of the velocities' rounding errors.
        self.speed_scale = 0.0
        # A table with pockets (physics.pockets): entries reach the jaws and capture
        # lines too, and a pocketed ball is gone (no later contact involves it).
        self.pockets = setup.pockets
        self.gone = np.zeros(count, dtype=bool)
        self.jaw_law = JAW_LAWS.get(setup.cushion_law)
        spins = np.zeros((count, 3)) if setup.spins is None else np.asarray(setup.spins, np.float64)
        every = np.arange(count)
        self._reanchor(every, 0.0, self.p0.copy(), np.array(setup.velocities, float), spins)

    # -- the next event ---------------------------------------------------------------

    def next_time(self) -> float:
        return min(
            float(self.change_time.min(initial=np.inf)),
            float(self.cushion_time.min(initial=np.inf)),
            float(self.pair_time.min(initial=np.inf)),
        )

    def resolve_next(self) -> float:
        """Resolve the earliest event (by the tie rule); returns its time."""
        change_ball = int(self.change_time.argmin())
        change_time = float(self.change_time[change_ball])
        cushion_ball = int(self.cushion_time.argmin())
        cushion_time = float(self.cushion_time[cushion_ball])
        flat = int(self.pair_time.argmin())
        pair_time = float(self.pair_time.flat[flat])
        if change_time <= cushion_time and change_time <= pair_time:
            self._change_state(change_ball, change_time)
            return change_time
        if cushion_time <= pair_time:
            self._resolve_cushion(cushion_ball, cushion_time)
            return cushion_time
        first, second = divmod(flat, len(self.cushion_time))
        self._resolve_pair(first, second, pair_time)
        return pair_time

    def latest_stop(self) -> float:
        """When the last ball came to rest, or the end of the latest state still running
        (so it is past any step's end until every ball rests)."""
        ends = np.where(self.state == REST, self.t0, self.t0 + self.duration)
        return float(ends.max(initial=0.0))

    def state_at(self, balls: IntArray, time: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        return spin_state(
            self.p0[balls],
            self.v0[balls],
            self.w0[balls],
            self.acceleration[balls],
            self.angular[balls],
            self.t0[balls],
            self.duration[balls],
            self.setup.spin_decel,
            time,
        )

    # -- resolution -------------------------------------------------------------------

    def _change_state(self, ball: int, time: float) -> None:
        balls = np.array([ball])
        positions, velocities, spins = self.state_at(balls, time)
        state = int(self.state[ball])
        if state == SLIDING:
            # The slip is zero now by construction: roll (rounding removed).
            spins[:, :2] = rolling_spin(velocities, self.radius)
        elif state == ROLLING:
            velocities[:] = 0.0
            spins[:, :2] = 0.0
        else:
            velocities[:] = 0.0
            spins[:] = 0.0
        self._reanchor(balls, time, positions, velocities, spins, transition=True)

    def _resolve_cushion(self, ball: int, time: float) -> None:
        wall = int(self.cushion_wall[ball])
        if wall >= 4:
            self._resolve_pocket_edge(ball, wall - 4, time)
            return
        axis = wall // 2
        balls = np.array([ball])
        positions, velocities, spins = self.state_at(balls, time)
        positions[0, axis] = self.bounds[wall]  # on the cushion line by construction
        into = np.zeros(2)
        into[axis] = 1.0 if wall % 2 else -1.0
        approach = float(dot(velocities[0], into))
        if approach <= ELASTIC_BELOW and float(dot(self._accelerations(balls, time)[0], into)) > 0:
            # Pressed into the cushion by its own slip, at (nearly) no normal speed: the
            # cushion holds it. Its friction takes the slip's normal part (w_y for an x
            # cushion, w_x for a y cushion: only energy is lost) and the normal speed, so
            # the ball slides or rolls on along the cushion instead of bouncing in ever
            # shorter hops (or, at none, crossing it).
            velocities[0, axis] = 0.0
            spins[0, 1 - axis] = 0.0
            if approach > 0:
                self._record(time, "cushion", (ball,), approach)
            self._reanchor(balls, time, positions, velocities, spins)
            return
        if self.spin_cushion_law is not None:
            bounced, spins, approach = self._grip(ball, velocities, spins, into)
        else:
            assert self.cushion_law is not None
            bounced, approaches = self.cushion_law(
                velocities, np.array([axis]), self.setup.retention
            )
            approach = float(approaches[0])
        if approach == 0:
            self.cushion_time[ball] = np.inf
            return
        self._record(time, "cushion", (ball,), approach)
        self._reanchor(balls, time, positions, bounced, spins)

    def _grip(
        self, ball: int, velocities: FloatArray, spins: FloatArray, into: FloatArray
    ) -> tuple[FloatArray, FloatArray, float]:
        """The spin cushion law (han2005) on one ball (rows of 1) against a cushion or
        jaw whose unit normal `into` points into it: (velocities, spins, approach)."""
        assert self.spin_cushion_law is not None
        setup = self.setup
        velocity, spin, approach = self.spin_cushion_law(
            velocities[0],
            spins[0],
            into,
            self.radius,
            float(setup.masses[ball]),
            setup.cushion_restitution,
            setup.cushion_friction,
            setup.cushion_height,
        )
        return velocity[None], spin[None], approach

    def _resolve_pocket_edge(self, ball: int, edge: int, time: float) -> None:
        """A jaw contact (edge < number of jaws) or a drop past a capture line: the
        rolling calendar's rules, with the spin model's cushion law at the jaw."""
        pockets = self.pockets
        assert pockets is not None
        balls = np.array([ball])
        positions, velocities, spins = self.state_at(balls, time)
        jaw_count = len(pockets.jaws)
        if edge >= jaw_count:
            pocket = edge - jaw_count
            speed = length(velocities[0, 0], velocities[0, 1])
            self._record(time, "pocket", (ball,), speed, pockets.names[pocket])
            # Gone: at rest where it crossed (so no edge), and out of every pair.
            self.gone[ball] = True
            self._reanchor(balls, time, positions, np.zeros((1, 2)), np.zeros((1, 3)))
            return
        into = pockets.jaws[edge] - positions[0]
        into /= length(into[0], into[1])
        closing = float(dot(velocities[0], into))
        if closing <= ELASTIC_BELOW and float(dot(self._accelerations(balls, time)[0], into)) > 0:
            # Pressed into the jaw by its own slip at (nearly) no normal speed, as at a
            # cushion: the jaw takes the normal speed and the slip's normal part, so the
            # ball goes on along the tangent instead of curving into the jaw.
            along = np.array([-into[1], into[0]])
            velocities[0] -= closing * into
            spins[0, :2] -= float(dot(spins[0, :2], along)) * along
            if closing > 0:
                name = pockets.names[pockets.jaw_pocket[edge]]
                self._record(time, "cushion", (ball,), closing, name)
            # With no normal velocity or acceleration left, its path keeps its distance
            # from the jaw's centre (|D + v t + a t^2/2|^2 = |D|^2 + |v t + a t^2/2|^2):
            # that jaw is skipped until the ball's next anchor.
            self._reanchor(balls, time, positions, velocities, spins, skip=(ball, 4 + edge))
            return
        if self.spin_cushion_law is not None:
            bounced, spins, approach = self._grip(ball, velocities, spins, into)
        else:
            assert self.jaw_law is not None
            bounced, approaches = self.jaw_law(velocities, into[None], self.setup.retention)
            approach = float(approaches[0])
        if approach <= 0:
            # A tangent graze: no contact; the ball is asked again for every other edge.
            self._reanchor(balls, time, positions, velocities, spins, skip=(ball, 4 + edge))
            return
        self._record(time, "cushion", (ball,), approach, pockets.names[pockets.jaw_pocket[edge]])
        self._reanchor(balls, time, positions, bounced, spins)

    def _resolve_pair(self, first: int, second: int, time: float) -> None:
        balls = np.array([first, second])
        positions, velocities, spins = self.state_at(balls, time)
        accelerations = self._accelerations(balls, time)
        masses = self.setup.masses
        normal = line_of_centres(positions[0], positions[1])
        after_first, after_second, approach = self.ball_law(
            normal,
            velocities[0],
            float(masses[first]),
            velocities[1],
            float(masses[second]),
            self.setup.restitution
            if self.contact_time[first] != time and self.contact_time[second] != time
            else 1.0,
        )
        # As in the rolling calendar (docs/touching.md): a closing speed within the
        # rounding of the run's speeds has no sign; a touching pair that its
        # accelerations press together parts by the pressed law, and so does a soft
        # contact that would leave it parting slower than they close it again.
        scale = total(np.abs(velocities)) + self.speed_scale
        rounding = 8 * np.finfo(np.float64).eps * scale + 1e-290
        if approach <= rounding:
            relative = velocities[0] - velocities[1]
            separation = positions[0] - positions[1]
            curvature = float(
                dot(relative, relative) + dot(separation, accelerations[0] - accelerations[1])
            )
            if (
                length(relative[0], relative[1]) <= rounding
                or self.pressed_at.get((first, second)) == time
                or curvature >= 0
            ):
                # Moving together to rounding, already parted at this instant, or
                # parting: no contact now; asked again for its return after parting.
                self.pair_time[first, second] = self._pair_contacts(
                    balls[:1], balls[1:], time, parting=True
                )[0]
                if self.pair_time[first, second] <= time:
                    self.pair_time[first, second] = np.inf
                return
            after_first, after_second = pressed_separation(
                normal, velocities[0], float(masses[first]), velocities[1], float(masses[second])
            )
            approach = max(approach, 0.0)
            self.pressed_at[first, second] = time
        elif ContactCalendar._pressed_back(positions, after_first - after_second, accelerations):
            after_first, after_second = pressed_separation(
                normal, after_first, float(masses[first]), after_second, float(masses[second])
            )
        self._record(time, "ball", (first, second), approach)
        velocities[0] = after_first
        velocities[1] = after_second
        # Frictionless contact: the spins pass through unchanged.
        self._reanchor(balls, time, positions, velocities, spins)

    def _accelerations(self, balls: IntArray, time: float) -> FloatArray:
        """The balls' accelerations at `time` (zero once their state has run out)."""
        running = time - self.t0[balls] < self.duration[balls]
        return np.where(running[:, None], self.acceleration[balls], 0.0)

    def _record(
        self,
        time: float,
        kind: str,
        balls: tuple[int, ...],
        speed: float,
        pocket: str | None = None,
    ) -> None:
        if kind == "ball":
            self.contact_time[list(balls)] = time
        self.log.contact(time, kind, balls, speed, pocket)
        self.event_count += 1

    def _reanchor(
        self,
        balls: IntArray,
        time: float,
        positions: FloatArray,
        velocities: FloatArray,
        spins: FloatArray,
        *,
        transition: bool = False,
        skip: tuple[int, int] | None = None,
    ) -> None:
        states, velocities, spins = classify(velocities, spins, self.radius)
        setup = self.setup
        acceleration, angular, duration = state_laws(
            states,
            velocities,
            spins,
            self.radius,
            setup.slide_decel,
            setup.decel,
            setup.spin_decel,
        )
        if transition:
            # The end of a motion state (a contact's new state is in its anchor).
            self.log.transitions.append((time, int(balls[0]), int(states[0])))
        self.speed_scale = max(self.speed_scale, float(norm(velocities).max()))
        self.t0[balls] = time
        self.p0[balls] = positions
        self.v0[balls] = velocities
        self.w0[balls] = spins
        self.state[balls] = states
        self.acceleration[balls] = acceleration
        self.angular[balls] = angular
        self.duration[balls] = duration
        self.change_time[balls] = np.where(states == REST, np.inf, time + duration)
        log = self.log
        for row, ball in enumerate(balls.tolist()):
            log.segment_ball.append(ball)
            log.segment_t0.append(time)
            log.segment_p0.append(positions[row].copy())
            log.segment_v0.append(velocities[row].copy())
            log.segment_w0.append(spins[row].copy())
            log.segment_state.append(int(states[row]))
        self._refresh(balls, time, skip)

    # -- the calendar -----------------------------------------------------------------

    def _refresh(self, balls: IntArray, now: float, skip: tuple[int, int] | None = None) -> None:
        """Recompute the cushion and pair entries of freshly anchored balls."""
        times, walls = cushion_contacts(
            self.p0[balls],
            self.v0[balls],
            self.acceleration[balls],
            self.t0[balls],
            self.duration[balls],
            self.state[balls],
            self.bounds,
            self.pockets,
            self.setup.max_time,
            None if skip is None else (balls == skip[0], skip[1]),
        )
        self.cushion_time[balls] = times
        self.cushion_wall[balls] = walls
        count = len(self.cushion_time)
        if len(balls) == count:
            lower, higher = np.triu_indices(count, k=1)
        else:
            others = np.ones(count, dtype=bool)
            firsts = []
            seconds = []
            for ball in balls.tolist():
                others[ball] = False
                partner = others.nonzero()[0]
                firsts.append(np.minimum(partner, ball))
                seconds.append(np.maximum(partner, ball))
            lower, higher = np.concatenate(firsts), np.concatenate(seconds)
        found = self._pair_contacts(lower, higher, now)
        if self.pockets is not None:
            found[self.gone[lower] | self.gone[higher]] = np.inf
        self.pair_time[lower, higher] = found

    def _pair_contacts(
        self, first: IntArray, second: IntArray, now: float, *, parting: bool = False
    ) -> FloatArray:
        """spin_contact_times.pair_contacts for these pairs, from every ball's state now."""
        position, velocity, _ = self.state_at(np.arange(len(self.t0)), now)
        return pair_contacts(
            first,
            second,
            now,
            position,
            velocity,
            self.acceleration,
            self.state,
            self.change_time,
            self.cushion_time,
            self.radius,
            self.setup.max_time,
            parting,
        )
