"""Every picture rocketsim draws, for a notebook and for the command line alike.

* :func:`run` (a :class:`~rocketsim.api.run.Run` or its MCAP file): altitude, speed,
  q, acceleration, throttle and propellant, Mach, attitude, the ground track
  (``rocketsim replay --plot``; ``Run.plot()`` draws the same);
* :func:`campaign` (a campaign's :class:`~rocketsim.campaigns.report.Report`): the
  landing map, the output histograms, the tornado of sensitivities, into a folder
  (``rocketsim campaign report --plot``);
* :func:`porkchop` (the :class:`~rocketsim.api.window_search.LaunchWindows` of a search):
  C3 and arrival v-infinity over departure and arrival dates (``rocketsim windows --plot``);
* :func:`vehicle` (a :class:`~rocketsim.api.vehicle_figures.VehicleReport`): the stack to
  scale, tanks, engines, centres of mass (``rocketsim vehicle --plot``);
* :func:`atmosphere` (an :class:`~rocketsim.api.air_profile.AirProfile`): temperature,
  pressure, density and wind against height (``rocketsim atmosphere --plot``).

Given a path ``out``, each writes a PNG there and returns the path; without one it
returns a :class:`Picture`, which a notebook shows inline. matplotlib is imported
when a picture is drawn (:mod:`rocketsim.plots.canvas`), the modules when their
name is first read (:mod:`rocketsim.exports`).
"""

from rocketsim.exports import lazy

_HOMES = {
    "run": "rocketsim.plots.flight_panels",
    "campaign": "rocketsim.plots.campaign_figures",
    "vehicle": "rocketsim.plots.vehicle_stack",
    "atmosphere": "rocketsim.plots.air_panels",
    "porkchop": "rocketsim.plots.porkchop_contours",
    "Picture": "rocketsim.plots.canvas",
}
__all__ = list(_HOMES)

__getattr__, __dir__ = lazy(globals(), _HOMES)
