"""GLSL shader sources, shipped inside the package."""
