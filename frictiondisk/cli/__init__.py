"""The click commands: a thin layer over the public API.
`python -m frictiondisk.cli` runs them."""

import sys
import types

__all__ = ["main"]


# `main` (the click group) is imported on first use, so that the console script installs its
# Ctrl-C handling (cli/entry.py) before the commands' imports (about a second).
class _Commands(types.ModuleType):
    @property
    def main(self):
        """The click group `frictiondisk` (frictiondisk/cli/main.py)."""
        from frictiondisk.cli.main import main

        return main

    @main.setter
    def main(self, module) -> None:
        """Importing frictiondisk.cli.main would bind the submodule here; the group stays."""


sys.modules[__name__].__class__ = _Commands
