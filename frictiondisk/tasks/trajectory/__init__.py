"""The `trajectory` task: one recorded run of the base scene (paper Figs 4-5)."""
