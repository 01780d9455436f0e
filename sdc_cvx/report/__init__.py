"""Report: figures and the run folder."""
