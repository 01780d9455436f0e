"""Report: a run's figures and run folder (read through :mod:`.plan_record`), a
campaign's folder and figures, the clusters' figure, the policy of the output folders and
the one atomic writer."""
