"""Sphinx configuration of the documentation site: `make docs` builds it into
build/docs/html with warnings as errors. The pages are the markdown files of docs/ (read
by myst-parser); api.md documents the public API from its docstrings (autodoc) and cli.md
the click commands (sphinx-click), so both references follow the code."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from frictiondisk.version import __version__  # noqa: E402

project = "frictiondisk"
release = __version__
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx_click"]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
root_doc = "index"
# GitHub-style anchors, so that links such as model.md#6-outcomes-and-rules resolve
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath"]
suppress_warnings = []
autodoc_member_order = "bysource"
# keep "--set" and straight quotes as the code and the shell spell them
smartquotes = False
autodoc_typehints = "description"
html_theme = "alabaster"
html_title = f"frictiondisk {release}"
