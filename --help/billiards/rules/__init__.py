"""The rules and numbers the scene reader and the physics share (numpy and the standard library only)."""
