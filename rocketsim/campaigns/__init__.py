"""Monte Carlo campaigns: many runs of a scenario with dispersed inputs.

A campaign file (:mod:`.spec`) names a base scenario, a number of runs, a seed
and dispersions of its fields; every run's inputs derive from the seed and the
run's number alone (:mod:`.sampling`, :mod:`.cases`); the runs fly through the
front door in this process or on Dask (:mod:`.execute`; each run a task,
:mod:`.run_task`, on a cluster, :mod:`.cluster`), each giving one row of results
(:mod:`.outputs`) written to the campaign directory as it finishes
(:mod:`.store`); :mod:`.report` reads that directory back into statistics,
landing dispersions and sensitivities (:mod:`.statistics`, :mod:`.landing`), and
:func:`rocketsim.plots.campaign` draws them. :func:`rocketsim.campaign` is the Python entry point,
``rocketsim campaign run`` and ``rocketsim campaign report`` the command line's.
"""
