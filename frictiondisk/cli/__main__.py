"""`python -m frictiondisk.cli`: the command line."""

from frictiondisk.cli.main import main

main()
