"""Guidance a flight program imports: an upper stage's insertion into orbit, and the
building blocks of a booster's return and landing.

Pure functions and small classes over the numbers a flight computer reads
(``fc``: the navigation estimate, never the truth, and the day's forecast
``fc.forecast``); docs/guidance-ascent.md and docs/guidance.md explain each
algorithm, its parameters and when it cannot succeed;
``scenarios/programs/orbit_ascent.py`` and ``scenarios/programs/booster_return.py``
fly them.

* :mod:`~rocketsim.guidance.ascent` -- an upper stage's insertion into its target
  orbit flown through ``fc``, a mission's target orbit and the launch azimuth;
* :mod:`~rocketsim.guidance.peg` -- Powered Explicit Guidance: one cycle of the
  linear-tangent law to the cut-off state, re-solved from the navigation state;
* :mod:`~rocketsim.guidance.target_orbit` -- the target orbit (osculating or Kozai
  mean elements, node fixed or free) and the cut-off state it asks for;
* :mod:`~rocketsim.guidance.apsis` -- the velocity at an apsis of the orbit whose
  other apsis is given (insertion and circularisation burns);
* :mod:`~rocketsim.guidance.landing_point` -- where a falling stage comes down,
  through the day's air and wind with the body's own drag and lift, the entry
  and landing burns as planned (compiled);
* :mod:`~rocketsim.guidance.drag` -- the body's drag area, learnt in flight from
  the accelerometers and the air data;
* :mod:`~rocketsim.guidance.boostback` -- the velocity to gain that puts the
  predicted landing point on the target, and the burn's cut-off;
* :mod:`~rocketsim.guidance.descent` -- the lean (of the entry burn's thrust, of
  the body on its grid fins) that flies the predicted point onto the target;
* :mod:`~rocketsim.guidance.powered_descent` -- the landing burn: its ignition from
  the throttle margin, the vertical profile, Apollo's quadratic guidance to a
  gate above the pad, the vertical descent and the cut-off;
* :mod:`~rocketsim.guidance.pad` -- the landing pad's frame and the estimate seen
  from it;
* :mod:`~rocketsim.guidance.rate` -- how often guidance must wake as a reading
  nears the limit it acts at.
"""
