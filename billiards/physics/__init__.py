"""Exact rolling-ball physics: numpy and the standard library only, never GL."""

from billiards.physics.result import SimulationResult
from billiards.physics.simulate import METHODS, simulate, simulate_setup

__all__ = ["METHODS", "SimulationResult", "simulate", "simulate_setup"]
