"""The compiled step: runs of steps, their twins of the Python side's decisions, a sample's figures.

Pure kernels over flat arrays, no world: :mod:`~rocketsim.stepping.runs` flies a
vehicle, a tumbling part or a coasting body many steps in one call, testing
after each step (:mod:`~rocketsim.stepping.quiet`) whether the Python side of
:mod:`rocketsim.sim` (its checks and events) could have anything to do there,
as :mod:`~rocketsim.stepping.twins` maps them; :mod:`~rocketsim.stepping.checked_step`
is a vehicle's step with its checks' figures; :mod:`~rocketsim.stepping.sample_figures`
is every number of a telemetry sample. The world in :mod:`rocketsim.sim` drives
them and does what they hand back.
"""
