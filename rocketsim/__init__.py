"""rocketsim: a headless six-degree-of-freedom rocket flight and mission simulator.

The front door, for scripts and notebooks::

    import rocketsim
    run = rocketsim.fly("scenarios/falcon9-leo.yaml", duration=60)      # in memory
    run.bodies["falcon9-block5"].table()                                # a pandas DataFrame
    heavier = rocketsim.load("scenarios/falcon9-hop.yaml",
                             overrides={"vehicle.stages[booster].structure_mass": "26 t"})

* :func:`load` (path or mapping, overrides) -> a validated scenario;
* :func:`fly` (scenario, telemetry=None or an MCAP path, step, duration, progress,
  program, programs) -> a :class:`Run`;
* :func:`open_run` (an MCAP path) -> the same :class:`Run`, executing nothing;
* :func:`campaign` (a campaign file or mapping, directory, workers, scheduler) -> a
  Monte Carlo campaign's results as a pandas DataFrame (:mod:`rocketsim.campaigns`);
* :func:`review` (a vehicle or scenario file or mapping, or what ``load`` returned) -> the
  pre-flight design review: centre of pressure and static margin at liftoff and burnout,
  thrust-to-weight, rail-exit speed, peak axial load against the limit, how each stage
  steers, and ``.warnings``; :func:`design_warnings` -> those warnings alone (none for a
  rigid body, a site or a mission file) (:mod:`rocketsim.scenario.preflight`);
* :class:`InputError`: what bad input raises (file, line, field, or path).

These are :mod:`rocketsim.api`'s, which has the rest of the front door (what every
command of the command line calls). The names load on first use
(:mod:`rocketsim.exports`), so ``import rocketsim.constants`` or the command line's
light commands do not import the flight's compiled kernels.
"""

from rocketsim.exports import lazy
from rocketsim.version import __version__

__all__ = ["__version__", "load", "fly", "open_run", "Run", "InputError", "campaign", "review",
           "design_warnings"]

__getattr__, __dir__ = lazy(globals(), {name: "rocketsim.api" for name in __all__[1:]})
