"""The version of rocketsim (the distribution's, as pyproject.toml states it)."""

__version__ = "0.2.0"
