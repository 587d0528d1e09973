"""Atmospheres: the 1976 standard, the day's weather, Mars, and 50 m tables."""
