"""Reference frames: quaternions, ECI <-> Earth-fixed, WGS84 geodetic, orbital elements.

Modules: :mod:`~rocketsim.frames.quaternion` (compiled, scalar first),
:mod:`~rocketsim.frames.earth_fixed`, :mod:`~rocketsim.frames.geodetic`,
:mod:`~rocketsim.frames.elements`, :mod:`~rocketsim.frames.vectors` (the cross product of
two 3-vectors, from Python and compiled). Import functions from the module that computes them.
"""
