"""Monte Carlo campaigns: many runs of one scenario with dispersed inputs, and their report."""
