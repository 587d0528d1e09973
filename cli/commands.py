"""The list of commands: one import per command module."""

ALL = []
