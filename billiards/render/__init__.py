"""Headless OpenGL rendering of a recorded trajectory to frames and films."""
