"""The `find_jump` task: the jump mu* at every point of a line or grid of scene keys."""
