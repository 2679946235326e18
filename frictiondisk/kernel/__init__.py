"""Numerical kernel: numba only. Never imports orchestration (dask, xarray, click)."""
