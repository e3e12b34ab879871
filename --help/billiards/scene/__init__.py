"""The scene reader: TOML tables to a typed, checked Scene (its bounds, its [render] table, the cue's stroke)."""
