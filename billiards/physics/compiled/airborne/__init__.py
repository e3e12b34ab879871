"""Off the cloth (issue 45), compiled: the pieces the event loop will call for a ball in
the air, each a kernel of plain numbers in and out (nothing here keeps state).

- flight: the parabola of a ball's centre under gravity (spin constant) and its landing
  time, the root of a quadratic in the stable form;
- bed: the ball-table impact, frictionless and frictional (TP A-14's oblique impact with
  spin), and the jump stroke (TP A-30/31 with the vertical part kept);
- bounces: the hops that follow a landing, their count found by a bounded loop and
  their time in the air summed;
- contacts: the contact times in 3D of a flying ball, with a ball (a quartic) and with a
  cushion's nose (a cylinder along the wall at the cushion's height, a quartic), and
  whether it clears the rail;
- ball_ball: the frictionless contact of two balls along a 3D line of centres;
- probe: entries that run rows of inputs through the kernels, for the tests (an inner
  kernel has no wrapper for Python).

Only + - * / sqrt and comparisons, in written order (compiled.jit's options): the same
bits on every machine.
"""
