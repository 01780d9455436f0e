"""Network: the pre-optimised edge table between debris and its dominance bounds, and the
certified search's cheapest paths through its time-expanded network (labels, ng-routes)."""
