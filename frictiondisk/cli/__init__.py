"""The click commands: a thin layer over the public API.
`python -m frictiondisk.cli` runs them."""

from frictiondisk.cli.main import main

__all__ = ["main"]
