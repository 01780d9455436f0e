"""Study: scenario files, parameter studies (sweeps), their worker, runner and results."""
