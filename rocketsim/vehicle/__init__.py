"""Vehicles at run time: flat arrays built once from a spec, and the compiled
kernels the derivative calls at every RK4 stage (mass properties, engines)."""
