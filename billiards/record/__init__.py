"""The trajectory: what the physics hands to whoever draws (file format, pockets as drawn, drops, sampling, orientations, the film's window)."""
