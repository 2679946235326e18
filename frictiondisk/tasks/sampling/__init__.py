"""Runs of the cells of a grid from sampled initial states, shared by the tasks that take
them (basin, map): which start sample j of a cell gets (draws.py), a cell's runs
(runs.py), the spec of a sampled key and its checks (distribution.py), and the columns
every such task's runs.nc shares (columns.py). Not a task: no registry entry."""
