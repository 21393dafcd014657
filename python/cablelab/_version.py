"""The version of cablelab (read by pyproject.toml without importing the package)."""
__version__ = "0.39.0"
