"""The seed break's numbers: the defaults of every scene key and of every physics Setup.

The source report's table 2.1 (docs and MODEL.md), with the WPA's pockets and the
spin model's constants beside it. One home, read by both the scene reader
(billiards.scene.reader) and the physics (billiards.physics.engine.setup and .pockets): a leaf of
the bottom floor like billiards.rules.pocket_rule (tests/test_floors.py), the standard
library only and nothing of the package, so neither imports the other for them.
"""

from __future__ import annotations

# The table: the playing surface between the cushion noses, (L, W) in m.
TABLE_SIZE = (2.13, 1.065)
RETENTION = 0.75  # share of kinetic energy a cushion keeps
# WPA equipment specifications: corner mouths 4.5-4.625 in, side mouths 5-5.125 in,
# between the points where the cushion noses end. The lower ends, in metres.
CORNER_POCKET_WIDTH = 0.1143
SIDE_POCKET_WIDTH = 0.127
# The rounding of a cushion's end (pooltool's side jaw radius, 0.0159 / 2 m).
JAW_RADIUS = 0.008  # m

# The balls.
RADIUS = 0.0286  # m, one radius for every ball
MASS = 0.165  # kg, an object ball
CUE_MASS = 0.170  # kg
CUE_SPEED = 3.0  # m/s, from the head spot along +x
RACK_GAP = 0.0001  # m between rack neighbours

# A cue that strikes ([[ball]] cue = {...}; billiards.scene.stroke): pooltool's generic
# pool cue, 20 oz, whose tip end moves sideways like 1/30 of a 6 oz ball's mass (its
# squirt "end mass", Alciatore's TP A-31: typical shafts 4-9 g).
STICK_MASS = 0.567  # kg
STICK_END_MASS = 0.170097 / 30  # kg (0.00567)
# The bed's restitution for a ball driven down into it or landing on it (pooltool's
# ball-table e_t, Dr. Dave's figure), and the bounce height below which a ball stops
# hopping and slides (pooltool's min_bounce_height): issue 45's flight.
TABLE_RESTITUTION = 0.5
SETTLE_HEIGHT = 0.005  # m

# The cloth and the contacts.
GRAVITY = 9.81  # m/s^2
ROLLING_FRICTION = 0.01  # mu: a rolling ball slows at mu g
RESTITUTION = 1.0  # ball-ball, 1 = elastic
SLIDING_FRICTION = 0.2  # mu_s: a sliding ball's contact point slips against mu_s g
# mu_sp, a plain number (pooltool's u_sp = 10/9 * 2/5 R, a length there, evaluated at
# R = 0.0286 m): the vertical spin decays at 5 mu_sp g / (2R) rad/s^2, so, with mu_sp
# fixed, as 1/R when the radius changes (docs/explanation/spin.md, Defaults).
SPINNING_FRICTION = 0.0127
# Han 2005 cushions (the spin model's cushion law "han2005"; pooltool's defaults for e
# and mu): the nose at 63.5% of the ball's diameter, the WPA's specification.
CUSHION_RESTITUTION = 0.85
CUSHION_FRICTION = 0.2
CUSHION_HEIGHT = 0.635 * 2 * RADIUS  # m above the cloth (0.036322)
# Mathavan et al. 2010's fit to their rebounds (the cushion law "mathavan2010"): e_e and
# mu_w, that law's defaults for cushion_restitution and cushion_friction.
MATHAVAN_RESTITUTION = 0.98
MATHAVAN_FRICTION = 0.14
# The same impact with a restitution that falls with the normal speed v_n (the law
# "mathavan2010_ev"): e_e = e_0 / sqrt(1 + (v_n / v_c)^4), e_0 and v_c fitted to all 19
# of Mathavan 2010's rebounds (scripts/validation_measured.py, docs/validation.md).
MATHAVAN_EV_RESTITUTION = 0.9975
MATHAVAN_EV_SPEED = 4.15  # m/s, v_c
# Ball-ball friction (the spin model's ball law "frictional"): mu = a + b exp(-c s) at
# the contact point's slip speed s (m/s), Alciatore's fit to Marlow's measurements
# (TP ), as pooltool uses it.
BALL_FRICTION_A = 9.951e-3
BALL_FRICTION_B = 0.108
BALL_FRICTION_C = 1.088  # s/m

# The run.
DT = 1.0 / 240.0  # s, the fixed step of "exact" and "naive"
MAX_TIME = 120.0  # s
MAX_EVENTS = 100_000  # guard against inelastic collapse in a frozen cluster


def head_spot(table_size: tuple[float, float]) -> tuple[float, float]:
    """(L/4, W/2): where the seed's cue ball starts."""
    length, width = table_size
    return (0.25 * length, 0.5 * width)


def foot_spot(table_size: tuple[float, float]) -> tuple[float, float]:
    """(3L/4, W/2): where the rack's apex ball sits, unless [rack] apex says otherwise."""
    length, width = table_size
    return (0.75 * length, 0.5 * width)
