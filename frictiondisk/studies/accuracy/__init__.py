"""The accuracy study of a find_jump campaign (`frictiondisk accuracy`, docs/accuracy.md)."""
