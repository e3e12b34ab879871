"""Example scenes and other data files, shipped inside the package."""
