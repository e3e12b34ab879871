"""Exact rolling-ball physics: numpy and the standard library only, never GL. The package
imports nothing itself, so that reading the events type loads none of the simulation."""
