"""Pictures without GL: the top view."""
