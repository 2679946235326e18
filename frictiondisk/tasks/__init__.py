"""Tasks as plug-ins: one package per task (its spec, planner, datasets, table lines and
figure), found through one registry (registry.py) by code that never names a task."""
