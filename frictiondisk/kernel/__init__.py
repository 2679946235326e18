"""The numbers of one run: equations of motion, RODAS4 steps, events, energy, run loop.
numba only: never imports orchestration (dask, xarray, click) nor the rest of frictiondisk."""
