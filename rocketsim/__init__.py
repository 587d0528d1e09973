"""rocketsim: a headless six-degree-of-freedom rocket flight and mission simulator."""

__version__ = "0.1.0"
