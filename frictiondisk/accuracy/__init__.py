"""Accuracy study of the jump search: mu* against numerics and regularization settings."""
