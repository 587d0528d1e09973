"""``python -m rocketsim``: the command line, as the ``rocketsim`` command runs it."""

from rocketsim_cli.main import main

if __name__ == "__main__":
    main(prog_name="rocketsim")
