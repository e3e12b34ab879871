"""The contact calendar: every ball's next cushion contact and every pair's next contact.

A ball's entries are recomputed only when the ball is re-anchored (at its own
contact); everything else keeps its cached time. Balls at rest cost nothing, and
pairs of rolling balls that cannot touch are ruled out by the quartic's cheap
certificate (roots.first_downward_root) before any cubic is solved. What a contact
does to velocities is a law looked up by name in physics.laws.

Ties. Contacts at exactly the same time are resolved one after another in this
order: cushion contacts before ball-ball contacts; among cushion contacts the lower
ball index first, and for one ball the x cushions before the y cushions (a corner
hit is two cushion contacts at the same instant); among ball-ball contacts the pair
with the lower first index, then the lower second index. A contact created by a
resolution (a touching neighbour now closing) happens at that same instant and
joins the order.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from billiards.physics.arithmetic import dot, length, total
from billiards.physics.contact_times import cushion_contacts, pair_contacts
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS, JAW_LAWS
from billiards.physics.laws.ball_ball import ELASTIC_BELOW, line_of_centres, pressed_separation
from billiards.physics.motion import Anchors, FloatArray, IntArray, state_at
from billiards.physics.pocket_times import edge_contacts
from billiards.physics.setup import Setup


@dataclass
class ContactLog:
    """What happened: contacts that changed velocities, and every anchor (path segment)."""

    times: list[float] = field(default_factory=list)
    kinds: list[str] = field(default_factory=list)
    balls: list[tuple[int, ...]] = field(default_factory=list)
    impact_speeds: list[float] = field(default_factory=list)
    pockets: list[str | None] = field(default_factory=list)  # the pocket, where one
    segment_ball: list[int] = field(default_factory=list)
    segment_t0: list[float] = field(default_factory=list)
    segment_p0: list[FloatArray] = field(default_factory=list)
    segment_v0: list[FloatArray] = field(default_factory=list)

    def contact(
        self, time: float, kind: str, balls: tuple[int, ...], speed: float, pocket: str | None
    ) -> None:
        self.times.append(time)
        self.kinds.append(kind)
        self.balls.append(balls)
        self.impact_speeds.append(speed)
        self.pockets.append(pocket)

    def anchor(
        self, balls: IntArray, time: float, positions: FloatArray, velocities: FloatArray
    ) -> None:
        for ball, position, velocity in zip(balls.tolist(), positions, velocities, strict=True):
            self.segment_ball.append(ball)
            self.segment_t0.append(time)
            self.segment_p0.append(position)
            self.segment_v0.append(velocity)


class ContactCalendar:
    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.ball_law = BALL_LAWS[setup.ball_law]
        # Each ball's latest ball-ball contact: a second one at the same instant is
        # elastic (Luding and McNamara's TC model with a contact duration of zero).
        self.contact_time = np.full(len(setup.positions), -np.inf)
        # Pairs parted by the pressed law, and when: never twice at one instant.
        self.pressed_at: dict[tuple[int, int], float] = {}
        # The fastest any ball has gone: the scale of the velocities' rounding errors.
        self.speed_scale = 0.0
        self.cushion_law = CUSHION_LAWS[setup.cushion_law]
        count = len(setup.positions)
        self.bounds = setup.bounds
        self.anchors = Anchors.start(setup.positions, setup.velocities, setup.decel)
        self.speed_scale = float(self.anchors.speed.max(initial=0.0))
        self.cushion_time = np.full(count, np.inf)
        self.cushion_wall = np.zeros(count, dtype=np.intp)
        # pair_time[i, j] for i < j; the rest stays inf.
        self.pair_time = np.full((count, count), np.inf)
        self.log = ContactLog()
        self.event_count = 0
        # A table with pockets (physics.pockets): its balls' entries reach the jaws and
        # capture lines too, and a pocketed ball is gone (no later contact involves it).
        self.pockets = setup.pockets
        self.gone = np.zeros(count, dtype=bool)
        self.jaw_law = JAW_LAWS[setup.cushion_law] if setup.pockets is not None else None
        every = np.arange(count)
        self.log.anchor(every, 0.0, self.anchors.p0.copy(), self.anchors.v0.copy())
        self._refresh(every, 0.0)

    # -- the next contact -------------------------------------------------------------

    def next_time(self) -> float:
        return min(
            float(self.cushion_time.min(initial=np.inf)), float(self.pair_time.min(initial=np.inf))
        )

    def resolve_next(self) -> float:
        """Resolve the earliest contact (by the tie rule); returns its time."""
        cushion_ball = int(self.cushion_time.argmin())
        cushion_time = float(self.cushion_time[cushion_ball])
        flat = int(self.pair_time.argmin())
        pair_time = float(self.pair_time.flat[flat])
        if cushion_time <= pair_time:
            self._resolve_cushion(cushion_ball, cushion_time)
            return cushion_time
        first, second = divmod(flat, len(self.cushion_time))
        self._resolve_pair(first, second, pair_time)
        return pair_time

    def latest_stop(self) -> float:
        return float(self.anchors.stop_time.max(initial=0.0))

    # -- resolution -------------------------------------------------------------------

    def _resolve_cushion(self, ball: int, time: float) -> None:
        wall = int(self.cushion_wall[ball])
        if wall >= 4:
            self._resolve_pocket_edge(ball, wall - 4, time)
            return
        axis = wall // 2
        balls = np.array([ball])
        positions, velocities, _ = state_at(self.anchors, balls, np.array([time]))
        # The centre is on the cushion line by construction; snap away the rounding.
        positions[0, axis] = self.bounds[wall]
        bounced, approaches = self.cushion_law(velocities, np.array([axis]), self.setup.retention)
        approach = float(approaches[0])
        if approach == 0:
            # It came to rest exactly on the cushion line: nothing to bounce.
            self.cushion_time[ball] = np.inf
            return
        self._record(time, "cushion", (ball,), approach)
        self._reanchor(balls, time, positions, bounced)

    def _resolve_pocket_edge(self, ball: int, edge: int, time: float) -> None:
        """A jaw contact (edge < number of jaws) or a drop past a capture line."""
        pockets = self.pockets
        assert pockets is not None and self.jaw_law is not None
        balls = np.array([ball])
        positions, velocities, _ = state_at(self.anchors, balls, np.array([time]))
        jaw_count = len(pockets.jaws)
        if edge >= jaw_count:
            pocket = edge - jaw_count
            speed = length(velocities[0, 0], velocities[0, 1])
            self._record(time, "pocket", (ball,), speed, pockets.names[pocket])
            # Gone: at rest where it crossed (so no edge), and out of every pair.
            self.gone[ball] = True
            self._reanchor(balls, time, positions, np.zeros((1, 2)))
            return
        into = pockets.jaws[edge] - positions[0]
        into /= length(into[0], into[1])
        bounced, approaches = self.jaw_law(velocities, into[None], self.setup.retention)
        approach = float(approaches[0])
        if approach <= 0:
            # A tangent graze (a ball leaving the cushion's end along it): no contact;
            # the ball is asked again for every other edge.
            self._reanchor(balls, time, positions, velocities, skip=(ball, 4 + edge))
            return
        self._record(time, "cushion", (ball,), approach, pockets.names[pockets.jaw_pocket[edge]])
        self._reanchor(balls, time, positions, bounced)

    def _resolve_pair(self, first: int, second: int, time: float) -> None:
        balls = np.array([first, second])
        positions, velocities, accelerations = state_at(self.anchors, balls, np.array([time, time]))
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
        # The closing speed (v1 - v2).n carries a rounding error of a few ulps of the
        # speeds it was computed from: the pair's own, and, through every impulse
        # that made them, the run's fastest (speed_scale). Below that it has no sign.
        # Resolving such a contact changes the velocities by less than their own
        # rounding, so the same pair, or a ball squeezed between two, is found closing
        # again an ulp of time later, thousands of times (a touching line at 30
        # degrees, a ball squeezed at 1.7e-17 m/s in a 0.2 m/s scene). The floor does
        # the same for subnormal speeds (5e-324 m/s), where 8 eps |v| underflows.
        scale = total(np.abs(velocities)) + self.speed_scale
        rounding = 8 * np.finfo(np.float64).eps * scale + 1e-290
        if approach <= rounding:
            if not self._touching_without_closing(
                first, second, time, positions, velocities, accelerations, rounding
            ):
                return
            after_first, after_second = pressed_separation(
                normal, velocities[0], float(masses[first]), velocities[1], float(masses[second])
            )
            approach = max(approach, 0.0)
            self.pressed_at[first, second] = time
        elif self._pressed_back(positions, after_first - after_second, accelerations):
            # A soft contact that leaves the pair parting slower than its decelerations
            # close it again would be followed by a return too shallow to see (nm/s
            # apart, then pressed back unseen): part it by the pressed law instead.
            after_first, after_second = pressed_separation(
                normal, after_first, float(masses[first]), after_second, float(masses[second])
            )
        self._record(time, "ball", (first, second), approach)
        velocities[0] = after_first
        velocities[1] = after_second
        self._reanchor(balls, time, positions, velocities)

    def _touching_without_closing(
        self,
        first: int,
        second: int,
        time: float,
        positions: FloatArray,
        velocities: FloatArray,
        accelerations: FloatArray,
        rounding: float,
    ) -> bool:
        """A touching pair with a rounding-level approach: True if it is pressed (its
        decelerations push it together now, or it returns within this tick of the
        clock) and needs the pressed law; otherwise its entry is set to its return
        after parting, or to never."""
        relative = velocities[0] - velocities[1]
        separation = positions[0] - positions[1]
        if (
            length(relative[0], relative[1]) <= rounding
            or self.pressed_at.get((first, second)) == time
        ):
            # Moving together to rounding (so both stop within rounding / (mu g) and
            # cannot overlap by more than rounding^2 / (mu g)), or already parted by
            # the pressed law at this instant: nothing more to do now.
            self.pair_time[first, second] = np.inf
            return False
        # d^2(|p1 - p2|^2)/dt^2 / 2 = |w|^2 + D.(a1 - a2): below zero the pair's
        # decelerations press it together; otherwise it parts, and may come back.
        curvature = float(
            dot(relative, relative) + dot(separation, accelerations[0] - accelerations[1])
        )
        if curvature < 0:
            return True
        # A rounding-level graze: no contact now, but the pair is asked again for its
        # return after parting (never dropped: the calendar must not lose a pair).
        balls = np.array([first, second])
        returns = pair_contacts(
            self.anchors,
            balls[:1],
            balls[1:],
            time,
            self.cushion_time,
            self.setup.radius,
            parting=True,
        )[0]
        if returns > time:
            self.pair_time[first, second] = returns
            return False
        return True  # it returns within this tick of the clock: pressed after all

    @staticmethod
    def _pressed_back(
        positions: FloatArray, relative: FloatArray, accelerations: FloatArray
    ) -> bool:
        """Whether a pair leaving a contact with relative velocity `relative` parts
        slower than min(ELASTIC_BELOW, |w|) while its decelerations press it back."""
        separation = positions[0] - positions[1]
        distance = length(separation[0], separation[1])
        parting = float(dot(relative, separation)) / distance
        speed = length(relative[0], relative[1])
        if parting >= min(ELASTIC_BELOW, speed):
            return False
        pressing = float(dot(separation, accelerations[0] - accelerations[1]))
        return speed * speed + pressing < 0

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
        skip: tuple[int, int] | None = None,
    ) -> None:
        self.anchors.set(balls, time, positions, velocities)
        self.speed_scale = max(self.speed_scale, float(self.anchors.speed[balls].max()))
        self.log.anchor(balls, time, self.anchors.p0[balls].copy(), self.anchors.v0[balls].copy())
        self._refresh(balls, time, skip)

    # -- the calendar -----------------------------------------------------------------

    def _refresh(self, balls: IntArray, now: float, skip: tuple[int, int] | None = None) -> None:
        """Recompute the cushion and pair entries of freshly anchored balls."""
        if self.pockets is None:
            times, walls = cushion_contacts(self.anchors, balls, self.bounds)
        else:
            times, walls = edge_contacts(self.anchors, balls, self.bounds, self.pockets, skip)
        self.cushion_time[balls] = times
        self.cushion_wall[balls] = walls

        count = len(self.cushion_time)
        lower, higher = _pairs_with(balls, count)
        found = pair_contacts(
            self.anchors, lower, higher, now, self.cushion_time, self.setup.radius
        )
        if self.pockets is not None:
            found[self.gone[lower] | self.gone[higher]] = np.inf
        self.pair_time[lower, higher] = found


def _pairs_with(balls: IntArray, count: int) -> tuple[IntArray, IntArray]:
    """Every pair (lower, higher index) with at least one of `balls` in it, once."""
    if len(balls) == count:
        return np.triu_indices(count, k=1)
    firsts = []
    seconds = []
    others = np.ones(count, dtype=bool)
    for ball in balls.tolist():
        others[ball] = False
        partner = others.nonzero()[0]  # skips balls of the set already paired
        firsts.append(np.minimum(partner, ball))
        seconds.append(np.maximum(partner, ball))
    return np.concatenate(firsts), np.concatenate(seconds)
