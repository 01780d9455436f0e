"""Inputs: the debris catalog (its file formats, RAAN rates fitted to SGP4, synthetic
catalogs, dense clusters), the mission, the campaign, the vehicle, the debris' values and
criticality, candidate selection."""
