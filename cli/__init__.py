"""The rocketsim command line (installed as ``rocketsim_cli``)."""
