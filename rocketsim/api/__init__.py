"""The front door: what a notebook or a script imports to fly and read runs."""
