"""The trajectory: what the physics hands to whoever draws (file format, sampling, orientations, the film's window)."""
