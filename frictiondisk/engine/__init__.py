"""Running campaigns: the Dask driver over the tasks' planners, the workers, budgets,
signals, progress and status. The only package that knows Dask."""
