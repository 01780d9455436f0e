"""Network: the pre-optimised edge table between debris and its dominance bounds."""
