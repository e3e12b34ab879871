"""The package's version: a leaf, so the commands can say it without importing the
package's facade (billiards/__init__.py, which offers the whole library)."""

__version__ = "0.1.0"
