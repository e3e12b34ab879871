"""The calendar: every ball's next edge contact, pair contact and change of motion
state, each at its exact time, resolved in order, for every motion model (a
motion_law.MotionLaw moves the balls; a contact law from billiards.physics.laws changes
their velocities). Written here once: the tie rule, the rounding floor, pressed pairs
and soft contacts (docs/touching.md), grazes asked again, held balls, drops, the log.
A ball's entries are recomputed only when it is re-anchored; balls at rest cost
nothing. The entries live in a batch's arrays (engine.batch); the rules are one run's.

Ties. Events at exactly the same time are resolved in this order: motion-state changes
(they move nothing), then edge contacts, then ball-ball contacts; among state changes
and edge contacts the lower ball index first, and for one ball the x cushions before
the y cushions, then the jaws, then the capture lines (a corner hit is two cushion
contacts at one instant); among ball-ball contacts the lower first index, then the
lower second. A contact created by a resolution happens at that instant and joins the
order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from billiards.physics.engine.batch import Batch, NextKind
from billiards.physics.engine.batch_log import ContactLog
from billiards.physics.engine.motion_law import MotionLaw
from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.ball_ball import (
    ELASTIC_BELOW,
    PairContact,
    line_of_centres,
    pressed_separation,
)
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from billiards.physics.laws.held import hold, part, payer_of, push, wedge
from billiards.physics.numerics.arithmetic import at_rows, dot, length, total
from billiards.physics.numerics.arrays import BoolArray, Dynamics, FloatArray, IntArray, Kinematics

__all__ = ["Calendar", "ContactLog"]


class Calendar:
    """One run's rules over its rows of a batch's arrays (a batch of its own if none)."""

    def __init__(self, setup: Setup, batch: Batch | None = None, run: int = 0) -> None:
        if setup.cushion_law not in CUSHION_LAWS:
            raise ValueError(f"unknown cushion law {setup.cushion_law!r}")
        batch = self.batch = Batch([setup]) if batch is None else batch
        self.run = run
        self.setup = setup
        self.law: MotionLaw = batch.law
        self.ball_law = BALL_LAWS[setup.ball_law]
        self.cushion_law = CUSHION_LAWS[setup.cushion_law]
        self.cushion_constants = CushionConstants.of(setup)
        count = self.count = batch.count  # rows a run: its balls, then padding (gone)
        self.base = run * count  # the run's first row in the batch's arrays
        own = slice(self.base, self.base + count)
        self.bounds = setup.bounds
        # Each ball's latest ball-ball contact: a second one at the same instant is
        # elastic (Luding and McNamara's TC model with a contact duration of zero).
        self.contact_time = batch.contact_time[own]
        # Pairs parted by the pressed law, and when: never twice at one instant.
        self.pressed_at: dict[tuple[int, int], float] = {}
        # Balls held by what they press into (laws.held), and when: twice is a wedge;
        # pairs held, when and how many times at that instant.
        self.held_at: dict[int, tuple[float, FloatArray]] = {}  # when, and along what
        self.held_pairs: dict[tuple[int, int], tuple[float, int]] = {}
        self.holds = 0  # how many holds so far
        # The run's rows of the batch's entries (views); pair_time[i, j] for i < j.
        self.edge_time = batch.edge_time[own]
        self.edge = batch.edge[own]
        self.pair_time = batch.pair_time[run]
        self.change_time = self.law.change_time[own]
        # With pockets the edges include the jaws and capture lines; a pocketed ball is gone.
        self.pockets = setup.pockets
        self.jaw_count = 0 if setup.pockets is None else len(setup.pockets.jaws)
        self.gone = batch.gone[own]

    @property
    def log(self) -> ContactLog:
        return self.batch.log.of(self.run)

    @property
    def event_count(self) -> int:
        return int(self.batch.event_count[self.run])

    # -- the next event ---------------------------------------------------------------

    def next_time(self) -> float:
        batch = self.batch
        if not batch.fresh[self.run]:
            batch.select(np.array([self.run]))
        return float(batch.next_time[self.run])

    def resolve_next(self) -> float:
        """Resolve the earliest event (by the tie rule) and re-anchor; returns its time."""
        time = self.resolve_selected()
        self.batch.flush()
        return time

    def resolve_selected(self) -> float:
        """Resolve the earliest event (as the batch's pass picked it); its re-anchoring
        waits for the batch's flush. Returns its time."""
        batch, run = self.batch, self.run
        time = self.next_time()
        batch.fresh[run] = False
        kind, index = int(batch.next_kind[run]), int(batch.next_index[run])
        # The batch's pass evaluated the event's balls at its time, for every run at once.
        at = tuple(part[run] for part in batch.dynamics)
        if kind == NextKind.CHANGE:
            self._change_state(index, time)
        elif kind == NextKind.EDGE:
            self._resolve_edge(index, time, tuple(part[:1] for part in at))
        else:
            self._resolve_pair(*divmod(index, self.count), time, at)
        return time

    def latest_stop(self) -> float:
        batch = self.batch
        if batch.with_stops and batch.fresh[self.run]:
            return float(batch.stops[self.run])
        return self.law.latest_stop(self.run)

    # -- resolution -------------------------------------------------------------------

    def _change_state(self, ball: int, time: float) -> None:
        kinematics = self.law.state_changes(np.array([self.base + ball]), time)
        self.batch.queue(self.run, np.array([ball]), time, kinematics, transitions=(ball,))

    def _resolve_edge(self, ball: int, time: float, at: Dynamics) -> None:
        """A cushion (edge 0-3), a jaw, or a drop past a capture line."""
        edge = int(self.edge[ball])
        balls = np.array([ball])
        positions, velocities, spins, accelerations = at
        now = (positions, velocities, spins)  # velocities and spins changed in place below
        if edge >= 4 + self.jaw_count:  # gone, at rest where it crossed, out of every pair
            assert self.pockets is not None
            speed = length(velocities[0, 0], velocities[0, 1])
            name = self.pockets.names[edge - 4 - self.jaw_count]
            self._record(time, "pocket", (ball,), speed, name)
            self.gone[ball] = True
            stopped = (positions, np.zeros((1, 2)), np.zeros((1, 3)))
            self.batch.queue(self.run, balls, time, stopped)
            return
        # The unit normal into the cushion or jaw, and the jaw's pocket. A cushion contact
        # puts the centre on the cushion line by construction: the rounding is snapped away.
        into, pocket = np.zeros(2), None
        if edge < 4:
            axis = edge // 2
            positions[0, axis] = self.bounds[edge]
            into[axis] = 1.0 if edge % 2 else -1.0
        else:
            pockets, jaw = self.pockets, edge - 4
            assert pockets is not None
            into = pockets.jaws[jaw] - positions[0]
            into /= length(into[0], into[1])
            pocket = pockets.names[pockets.jaw_pocket[jaw]]
        closing = float(dot(velocities[0], into))
        if closing <= ELASTIC_BELOW and float(dot(accelerations[0], into)) > 0:
            # Pressed into the rubber by its own slip at (nearly) no normal speed: held
            # (laws.held), so that it goes on along it instead of bouncing in ever shorter
            # hops (or crossing it); the edge is skipped until its next anchor.
            velocities[0], spins[0] = self._held(ball, time, velocities[0], spins[0], into, 0.0)
            if closing > 0:
                self._record(time, "cushion", (ball,), closing, pocket)
            self.batch.queue(self.run, balls, time, now, skip=(ball, edge))
            return
        masses = self.setup.masses[balls]
        bounced, spins_after, approaches = self.cushion_law(
            CushionContact(velocities, spins, into[None], masses), self.cushion_constants
        )
        approach = float(approaches[0])
        if approach <= 0:
            # No approach (a tangent graze, or a ball come to rest on the line): no
            # contact; the ball is asked again for every other edge.
            self.batch.queue(self.run, balls, time, now, skip=(ball, edge))
            return
        self._record(time, "cushion", (ball,), approach, pocket)
        self.batch.queue(self.run, balls, time, (positions, bounced, spins_after))

    def _resolve_pair(
        self, first: int, second: int, time: float, at: Dynamics | None = None
    ) -> None:
        """A contact of two balls (at: their state now, rows of 2, if known)."""
        balls = np.array([first, second])
        if at is None:
            at = self.law.state_at(self.base + balls, time)
        positions, velocities, spins, accelerations = at
        masses = self.setup.masses
        normal = line_of_centres(positions[0], positions[1])
        elastic = self.contact_time[first] == time or self.contact_time[second] == time
        restitution = 1.0 if elastic else self.setup.restitution
        after, spins_after, approach = self.ball_law(
            PairContact(normal, velocities, spins, masses[balls]), restitution, self.setup
        )
        after_first, after_second = after[0], after[1]
        # (v1 - v2).n carries a few ulps of the pair's speeds and, through every impulse
        # that made them, of the run's fastest (speed_scale): below that it has no sign,
        # and resolving it would find the pair closing again an ulp of time later,
        # thousands of times. The floor covers subnormal speeds, where 8 eps |v| is 0.
        scale = total(np.abs(velocities)) + float(self.batch.speed_scale[self.run])
        rounding = 8 * np.finfo(np.float64).eps * scale + 1e-290
        if approach <= rounding:
            touch = _Touch(balls, time, (positions, velocities, spins), accelerations, normal)
            if self._held_pair(touch, approach) or self._parted(touch, rounding):
                return
            if not self._touching_without_closing(touch, rounding):
                return
            after_first, after_second = pressed_separation(
                normal, velocities[0], float(masses[first]), velocities[1], float(masses[second])
            )
            spins_after = spins  # the pressed law is frictionless
            approach = max(approach, 0.0)
            self.pressed_at[first, second] = time
        elif _pressed_back(positions, after_first - after_second, accelerations):
            # A soft contact whose pair parts slower than its accelerations close it
            # would return too shallowly to see. Where a ball's own slip presses, the
            # bounce would repeat while the slip lasts: held instead, unless the TC rule
            # made it elastic (a ball squeezed between two, held by each in turn, would
            # halve its speed at one instant without end); otherwise pressed apart.
            touch = _Touch(balls, time, (positions, velocities, spins), accelerations, normal)
            if not elastic and self._held_pair(touch, approach):
                return
            after_first, after_second = pressed_separation(
                normal, after_first, float(masses[first]), after_second, float(masses[second])
            )
        velocities[0], velocities[1] = after_first, after_second
        self._pair_contact(balls, time, (positions, velocities, spins_after), approach)

    def _held_pair(self, touch: _Touch, approach: float) -> bool:
        """A sliding ball's own slip presses it into the other: held, or a push (laws.held)."""
        balls, time, normal, (first, second) = touch.balls, touch.time, touch.normal, touch.pair
        positions, velocities, spins = touch.kinematics
        # Held again at the same instant only after another hold (a third ball's, which
        # may have changed it): its own rounding is no reason.
        if touch.curvature() >= 0 or self.held_pairs.get(touch.pair) == (time, self.holds):
            return False
        slipping = self.law.slipping(self.base + balls)
        radius = self.setup.radius
        normals = (-normal, normal)  # each ball's way into the other
        into = (float(dot(touch.accelerations[row], normals[row])) for row in (0, 1))
        pressing = [row for row, pressed in enumerate(into) if slipping[row] and pressed > 0]
        if not pressing:
            return False
        # A plastic normal impulse first (momentum kept): the two at one normal speed.
        masses = self.setup.masses[balls]
        speeds = dot(velocities, normal)
        momentum = float(masses[0] * speeds[0] + masses[1] * speeds[1])
        common = momentum / float(masses[0] + masses[1])
        along = np.array([-normal[1], normal[0]])
        spin_slips = radius * dot(spins[:, :2], along)  # the spins' slips, up to sign
        changed: tuple[int, ...] = ()
        if all(abs(common) <= abs(float(spin_slips[row])) for row in pressing):
            velocities += (common - speeds)[:, None] * normal
            for row in pressing:
                toward = common if row == 1 else -common  # the common speed along its way in
                velocities[row], spins[row] = self._held(
                    int(balls[row]), time, velocities[row], spins[row], normals[row], toward
                )
        else:
            row = pressing[0]
            order = [row, 1 - row]
            both = push(velocities[order], spins[order], masses[order], normals[row], radius)
            if both is None:
                return False
            velocities[order], spins[order] = both
            self.holds += 1
            changed = (first, second)  # a push's cloth impulses
        self.held_pairs[touch.pair] = (time, self.holds)
        kinematics = (positions, velocities, spins)
        return self._pair_contact(balls, time, kinematics, max(approach, 0.0), changed)

    def _parted(self, touch: _Touch, rounding: float) -> bool:
        """A pair pressed with no slip driving it: parted at ELASTIC_BELOW (laws.held.part)."""
        balls, time = touch.balls, touch.time
        positions, velocities, spins = touch.kinematics
        relative = velocities[0] - velocities[1]
        if (
            length(relative[0], relative[1]) > rounding
            or self.pressed_at.get(touch.pair) == time
            or touch.curvature() >= 0
        ):
            return False
        slipping = self.law.slipping(self.base + balls)
        if not slipping.any():
            return False
        radius = self.setup.radius
        payer = payer_of(velocities, spins, slipping, radius)
        masses = self.setup.masses[balls]
        velocities, spins = part(
            velocities, spins, masses, touch.normal, payer, radius, ELASTIC_BELOW
        )
        self.pressed_at[touch.pair] = time
        changed = (int(balls[payer]),)
        return self._pair_contact(balls, time, (positions, velocities, spins), 0.0, changed)

    def _held(
        self,
        ball: int,
        time: float,
        velocity: FloatArray,
        spin: FloatArray,
        into: FloatArray,
        holder_speed: float,
    ) -> tuple[FloatArray, FloatArray]:
        """laws.held.hold, or wedge for a second holder at this instant."""
        radius = self.setup.radius
        velocity, held_spin = hold(velocity, spin, into, holder_speed, radius)
        at, normal = self.held_at.get(ball, (-np.inf, into))
        if at == time and (normal[0] != into[0] or normal[1] != into[1]):
            held_spin = wedge(velocity, held_spin, radius)  # a second holder: wedged
        self.held_at[ball] = (time, into)
        self.holds += 1
        return velocity, held_spin

    def _touching_without_closing(self, touch: _Touch, rounding: float) -> bool:
        """True if pressed; otherwise its entry is set to its return, or to never."""
        (first, second), time, velocities = touch.pair, touch.time, touch.kinematics[1]
        relative = velocities[0] - velocities[1]
        if length(relative[0], relative[1]) <= rounding or self.pressed_at.get(touch.pair) == time:
            # Moving together to rounding, or already pressed apart at this instant.
            self._ask_return(first, second, time)
            return False
        if touch.curvature() < 0:  # pressed together
            return True
        # A graze: asked again for its return (the calendar must never lose a pair).
        return not self._ask_return(first, second, time)

    def _ask_return(self, first: int, second: int, time: float) -> bool:
        """Set a pair's entry to its return; False (and never) if within this tick."""
        pair = (np.array([self.base + first]), np.array([self.base + second]))
        now, run = np.array([time]), np.array([self.run])
        returns = self.law.pair_times(pair, now, self.batch.edge_time, True, run)[0]
        self.pair_time[first, second] = returns if returns > time else np.inf
        return bool(returns > time)

    def _pair_contact(
        self,
        balls: IntArray,
        time: float,
        kinematics: Kinematics,
        speed: float,
        changed: tuple[int, ...] = (),
    ) -> bool:
        """Log a pair's contact and re-anchor it (`changed`: cloth impulses): True."""
        self._record(time, "ball", (int(balls[0]), int(balls[1])), speed)
        self.batch.queue(self.run, balls, time, kinematics, transitions=changed)
        return True

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
        self.batch.log.contact(self.run, (time, kind, balls, speed, pocket))
        self.batch.event_count[self.run] += 1


@dataclass(frozen=True)
class _Touch:
    """A touching pair at a rounding-level or soft contact (normal: second to first)."""

    balls: IntArray
    time: float
    kinematics: Kinematics
    accelerations: FloatArray
    normal: FloatArray

    @property
    def pair(self) -> tuple[int, int]:
        return int(self.balls[0]), int(self.balls[1])

    def curvature(self) -> float:
        """d^2(|p1 - p2|^2)/dt^2 / 2 = |w|^2 + D.(a1 - a2) at the pair's velocities now:
        below zero its accelerations press it together."""
        positions, velocities, _ = self.kinematics
        relative, accelerations = velocities[0] - velocities[1], self.accelerations
        separation = positions[0] - positions[1]
        return float(dot(relative, relative) + dot(separation, accelerations[0] - accelerations[1]))


def _pressed_back(positions: FloatArray, relative: FloatArray, accelerations: FloatArray) -> bool:
    """Whether a pair parts slower than min(ELASTIC_BELOW, |w|) while pressed back."""
    separation = positions[0] - positions[1]
    distance = length(separation[0], separation[1])
    parting = float(dot(relative, separation)) / distance
    speed = length(relative[0], relative[1])
    if parting >= min(ELASTIC_BELOW, speed):
        return False
    pressing = float(dot(separation, accelerations[0] - accelerations[1]))
    return speed * speed + pressing < 0


def resolve_pairs(calendars: list[Calendar], runs: IntArray) -> IntArray:
    """Calendar._resolve_pair, bit for bit, for all of `runs` at once: their plain contacts
    (frictionless, leaving the pair parting) and grazes (a frozen rack is full of them).
    Returns the runs whose contact is neither, for their calendars."""
    if runs.size == 0:
        return runs
    batch = calendars[0].batch
    count = batch.count
    flat = batch.next_index[runs]
    rows = runs * count
    first, second = rows + flat // count, rows + flat % count
    time = batch.next_time[runs]
    positions, velocities, _, accelerations = (part[runs] for part in batch.dynamics)
    contact = batch.contact_time
    elastic = (contact[first] == time) | (contact[second] == time)
    # line_of_centres, then the frictionless law (frictionless_impulse), row by row.
    separation = positions[:, 0] - positions[:, 1]
    normal = separation / np.sqrt(dot(separation, separation))[:, None]
    closing = dot(velocities[:, 0] - velocities[:, 1], normal)
    plain = closing < 0
    with np.errstate(divide="ignore"):
        raised = np.minimum(1.0, ELASTIC_BELOW / -closing)
    own = at_rows(batch.constants.restitution, runs)
    restitution = np.maximum(np.where(elastic, 1.0, own), raised)
    m1, m2 = batch.masses[first], batch.masses[second]
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    after_first = velocities[:, 0] - (impulse / m1)[:, None] * normal
    after_second = velocities[:, 1] + (impulse / m2)[:, None] * normal
    approach = -closing
    # The rounding floor (Calendar._resolve_pair), each run's own.
    sizes = np.abs(velocities).reshape(len(runs), 4).tolist()
    scale = np.array([math.fsum(row) for row in sizes]) + batch.speed_scale[runs]
    rounding = 8 * np.finfo(np.float64).eps * scale + 1e-290
    rounding_level = ~(approach > rounding)
    plain &= ~rounding_level
    # _Touch.curvature, row by row, of the velocities before the contact.
    before = velocities[:, 0] - velocities[:, 1]
    curvature = dot(before, before) + dot(separation, accelerations[:, 0] - accelerations[:, 1])
    grazing = rounding_level & (curvature >= 0)
    if grazing.any():
        grazing[grazing] = _grazes(
            calendars,
            runs[grazing],
            flat[grazing],
            time[grazing],
            before[grazing],
            rounding[grazing],
        )
    # _pressed_back, row by row.
    relative = after_first - after_second
    parting = dot(relative, separation) / np.sqrt(dot(separation, separation))
    speed = np.sqrt(dot(relative, relative))
    pressing = dot(separation, accelerations[:, 0] - accelerations[:, 1])
    plain &= (parting >= np.minimum(ELASTIC_BELOW, speed)) | ~(speed * speed + pressing < 0)
    done = plain.nonzero()[0]
    velocities[:, 0], velocities[:, 1] = after_first, after_second
    spins = batch.dynamics[2][runs]
    contact[first[done]] = time[done]  # Calendar._record's, for all at once
    contact[second[done]] = time[done]
    pairs = np.stack((flat // count, flat % count), axis=1)[done]
    runs_done, times_done = runs[done], time[done]
    batch.log.contacts(runs_done, times_done, "ball", pairs, approach[done])
    batch.event_count[runs_done] += 1
    kinematics = (positions[done], velocities[done], spins[done])
    batch.queue_rows(runs_done, pairs, times_done, kinematics)
    return runs[~plain & ~grazing]


def _grazes(
    calendars: list[Calendar],
    runs: IntArray,
    flat: IntArray,
    time: FloatArray,
    relative: FloatArray,
    rounding: FloatArray,
) -> BoolArray:
    """Calendar._touching_without_closing for all `runs` at once: True where done."""
    batch = calendars[0].batch
    count = batch.count
    first, second = flat // count, flat % count
    rows = runs * count
    returns = batch.law.pair_times((rows + first, rows + second), time, batch.edge_time, True, runs)
    back = returns > time
    batch.pair_time[runs, first, second] = np.where(back, returns, np.inf)
    # Moving together to rounding, or pressed apart at this instant: the entry is all.
    together = np.sqrt(dot(relative, relative)) <= rounding
    done = back | together
    for row in (~done).nonzero()[0].tolist():
        pair = (int(first[row]), int(second[row]))
        done[row] = calendars[int(runs[row])].pressed_at.get(pair) == float(time[row])
    batch.fresh[runs[done]] = False  # asked again at the next pass
    return done


def resolve_cushions(calendars: list[Calendar], runs: IntArray) -> IntArray:
    """Calendar._resolve_edge, bit for bit, for all of `runs`' plain cushion contacts (a
    cushion, approaching, not held) at once. Returns the other runs."""
    if runs.size == 0:
        return runs
    batch = calendars[0].batch
    constants = batch.constants.of(runs)
    ball = batch.next_index[runs]
    edge = batch.edge[runs * batch.count + ball]
    cushion = edge < 4  # not a jaw or a capture line
    axis = np.where(cushion, edge // 2, 0)
    every = np.arange(len(runs))
    positions, velocities, spins, accelerations = (part[runs, :1] for part in batch.dynamics)
    wall = np.minimum(edge, 3)
    bounds = constants.bounds
    line = bounds[wall] if bounds.ndim == 1 else bounds[every, wall]
    positions[every, 0, axis] = np.where(cushion, line, 0.0)
    into = np.zeros((len(runs), 1, 2))
    into[every, 0, axis] = np.where(edge % 2 == 1, 1.0, -1.0)
    closing = dot(velocities, into)[:, 0]
    held = (closing <= ELASTIC_BELOW) & (dot(accelerations, into)[:, 0] > 0)
    with np.errstate(divide="ignore", invalid="ignore"):  # rows not a cushion's: unused
        bounced, turned, approach = calendars[0].cushion_law(
            CushionContact(
                velocities[:, 0], spins[:, 0], into[:, 0], batch.masses[runs * batch.count + ball]
            ),
            CushionConstants.of(constants),
        )
    plain = cushion & ~held & (approach > 0)
    time = batch.next_time[runs]
    done = plain.nonzero()[0]
    runs_done, times_done, hit = runs[done], time[done], ball[done][:, None]
    batch.log.contacts(runs_done, times_done, "cushion", hit, approach[done])
    batch.event_count[runs_done] += 1
    kinematics = (positions[done], bounced[done][:, None], turned[done][:, None])
    batch.queue_rows(runs_done, hit, times_done, kinematics)
    return runs[~plain]


def resolve_changes(calendars: list[Calendar], runs: IntArray) -> None:
    """Resolve, for all of `runs` at once, their motion-state changes (Calendar.
    _change_state)."""
    if runs.size == 0:
        return
    batch = calendars[0].batch
    ball = batch.next_index[runs]
    time = batch.next_time[runs]
    positions, velocities, spins = batch.law.state_changes(runs * batch.count + ball, time)
    kinematics = (positions[:, None], velocities[:, None], spins[:, None])
    batch.queue_rows(runs, ball[:, None], time, kinematics, transitions=True)
