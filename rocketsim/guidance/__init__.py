"""Guidance a flight program imports: ascent insertion (:mod:`rocketsim.guidance.ascent`)."""
