"""Exact rolling-ball physics: numpy and the standard library only, never GL.

The package imports nothing itself: each user imports the module it needs (the stepper's
`run`, the result, the setup), so that reading the events type (`physics.events`), as
the trajectory and the renderer do, loads none of the simulation.
"""
