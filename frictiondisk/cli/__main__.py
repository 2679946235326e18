"""`python -m frictiondisk.cli`: the command line."""

from frictiondisk.cli.entry import run

run()
