"""Physics (numpy only): orbits under J2, the drift transfers between debris and plan
evaluation (Part III); the transfer models (impulsive, low thrust) with their exact leg
costs and box bounds for the certified search; eccentricity, mean elements, phasing and
impulses as vectors for the flight."""
