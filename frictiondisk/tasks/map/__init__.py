"""The `map` task: the motion of every cell of a plane of two scene keys."""
