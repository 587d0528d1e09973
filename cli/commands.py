"""The list of commands: one import per command module."""

from rocketsim_cli.atmosphere import atmosphere
from rocketsim_cli.campaign import campaign
from rocketsim_cli.classic_range import classic_range
from rocketsim_cli.compile_kernels import compile_kernels
from rocketsim_cli.ephemeris import ephemeris
from rocketsim_cli.fly import fly
from rocketsim_cli.replay import replay
from rocketsim_cli.validate import schema, validate
from rocketsim_cli.vehicle import vehicle
from rocketsim_cli.windows import windows

ALL = [fly, compile_kernels, validate, schema, atmosphere, ephemeris, vehicle, windows, replay, classic_range,
       campaign]
