"""Exact rolling-ball physics: numpy and the standard library only, never GL."""
