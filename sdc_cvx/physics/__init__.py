"""Physics: orbits under J2, the drift transfers between debris, plan evaluation (numpy only)."""
