"""The `scan` task: one run at every point of a grid of mu (and one more key)."""
