"""Running a campaign: planners, worker tasks, the Dask driver, budgets, progress.
The only package that knows Dask."""
