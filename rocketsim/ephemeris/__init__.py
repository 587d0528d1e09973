"""Where the Sun, Earth, Moon and Mars are: truncated VSOP87D and ELP2000-82B.

``solar_system.state(body, jd_tt, center)`` and ``solar_system.states(jd_tt,
center)`` are the entry points; ``generate`` rebuilds ``_tables.py`` from the
full series (the IMCCE files, read from the folder given to it); the models are
docs/physics.md#ephemerides.
"""
