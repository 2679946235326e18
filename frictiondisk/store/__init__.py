"""What is kept: the append-only journal, results.nc/runs.nc Datasets with CF metadata,
atomic files, checked paths."""
