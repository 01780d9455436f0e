"""Study: scenario files (and the checks of their tables), parameter studies (sweeps),
their worker, executors, runner, results and figure."""
