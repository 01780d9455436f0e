"""Inputs: the debris catalog and its file formats, the mission, candidate selection."""
