"""rocketsim: a headless six-degree-of-freedom rocket flight and mission simulator."""

from rocketsim.version import __version__

__all__ = ["__version__"]
