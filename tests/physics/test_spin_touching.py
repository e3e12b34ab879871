"""Issue 22's scenes: touching balls in the spin model, and a single ball that did not
finish. Each is held to every invariant of tests/hard_checks.check_spin_case.

The first two failed on the spin model's own calendar: a touching pair at rest whose
slips press it together was never a contact (taken for a pair "moving together to
rounding", which in the rolling model cannot press); y went 0.253 mm into x, and the
three balls ended 0.379 mm into each other. They are held now (docs/touching.md,
section 6).
"""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.roots import first_downward_root
from billiards.scene.reader import parse_scene
from billiards.simulation import setup_from_scene
from tests.hard_checks import check_spin_case

TWO_AT_REST = """
[physics]
model = "spin"
ball_restitution = 0.5
cushion_model = "han2005"
[[ball]]
id = "x"
position = [1.4634587983792422, 0.7731646415730445]
spin = [0.0, 0.0, -215.5834081424195]
[[ball]]
id = "y"
position = [1.4899156823171593, 0.7224510014720266]
spin = [-60.38198093592194, 93.09545069765771, 61.806152796460346]
"""

THREE_ON_A_TINY_TABLE = """
[table]
length = 0.22364046957260397
width = 0.0899834807689177
cushion_retention = 0.0
pockets = true
corner_pocket_width = 0.0635643650813896
side_pocket_width = 0.059200059199999995
jaw_radius = 0.001
[physics]
model = "spin"
[[ball]]
id = "t0"
position = [0.12445378004993918, 0.035891241301997494]
velocity = [-0.00553618253514426, 0.015296781824840669]
tip = [-0.9854287975385204, -0.17008258283194586]
[[ball]]
id = "t1"
position = [0.06830694851134106, 0.04681705057070994]
spin = [-65.47580791621559, 70.09073889406508, 0.7359581044391283]
[[ball]]
id = "t2"
position = [0.1865427785071903, 0.0485944169692807]
"""

SINGLE_BALL_WITH_POCKETS = """
[table]
pockets = true
[physics]
model = "spin"
cushion_model = "han2005"
cushion_restitution = 0.1822843768847925
cushion_friction = 0.9988546629627264
cushion_height = 0.0571999999428
[[ball]]
id = "g"
position = [1.5200491206665914, 0.9212300248909371]
velocity = [-4.514462732570447, 1.310461340912146]
tip = [-0.045096742820072144, -0.7268940560574465]
"""


def setup_of(text: str) -> Setup:
    return setup_from_scene(parse_scene(text, "issue22.toml"))


def test_two_balls_at_rest_touching_and_spinning_never_overlap() -> None:
    result = check_spin_case(setup_of(TWO_AT_REST))
    # y is held by x at once: a contact at t = 0 that changes no velocity.
    first = result.events[0]
    assert (first.time, first.kind, first.impact_speed) == (0.0, "ball", 0.0)


def test_three_balls_on_a_tiny_table_never_overlap() -> None:
    check_spin_case(setup_of(THREE_ON_A_TINY_TABLE))


def test_a_single_ball_with_pockets_and_han2005_finishes() -> None:
    # Before the IEEE-only arithmetic (dc7d064) it met the side-top jaw at t = 0.1097 s
    # and then again and again at that instant, each time at 6.9e-18 m/s (see
    # test_a_han2005_jaw_contact_that_leaves_no_normal_speed_is_not_met_again).
    result = check_spin_case(setup_of(SINGLE_BALL_WITH_POCKETS))
    assert [event.kind for event in result.events] == ["cushion", "cushion", "pocket"]


# The same loop on the current arithmetic: a ball into the side-top pocket's jaw with
# the nose near the top of the ball (cos theta = 6.3e-5), so Han 2005 cannot stop its
# normal speed and leaves it none ("cannot be driven on into the cushion"). Rebuilt from
# the jaw's frame that none is 2.8e-17 m/s into the jaw; its slip curves it away
# (a . n < 0, so it is not held as pressed), and the jaw quartic, f'(0) < 0 by those
# ulps, put the same contact at the same instant again, for ever (max_events).
NO_NORMAL_SPEED_AT_A_JAW = """
[table]
pockets = true
[physics]
model = "spin"
cushion_model = "han2005"
cushion_restitution = 0.16699225911742321
cushion_friction = 0.39074832379523616
cushion_height = 0.0571999999428
[simulation]
max_events = 1000
[[ball]]
id = "g"
position = [0.7226056935708695, 0.8400468453730737]
velocity = [4.200410119594729, 2.475537083855125]
tip = [0.0885342519393526, -0.5910831068247074]
"""


def test_a_han2005_jaw_contact_that_leaves_no_normal_speed_is_not_met_again() -> None:
    result = check_spin_case(setup_of(NO_NORMAL_SPEED_AT_A_JAW))
    at_the_jaw = [e for e in result.events if e.pocket == "side-top" and e.kind == "cushion"]
    assert len(at_the_jaw) == 1
    assert at_the_jaw[0].impact_speed > 4.0


def test_the_never_falls_certificate_takes_a_denormal_cubic_term_without_overflow() -> None:
    # A ball at 1e-310 m/s with a large spin: its quartics have a denormal t^3 term, and
    # the certificate's vertex -b2 / (2 b3) overflowed (a RuntimeWarning, an error here).
    coefficients = np.array([[1.0, 0.0, -1.0, 1e-310, 0.0]])
    found = first_downward_root(coefficients, np.array([1.0]), np.array([1e-12]))
    assert found[0] == pytest.approx(1.0, rel=1e-12)
