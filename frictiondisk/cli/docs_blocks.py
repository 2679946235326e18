"""The lists of the documentation that the code knows, generated from it: the outcomes
(verdict/outcomes.py), the tasks (tasks/registry.py), the commands (the click group) and
the verdict's parameters (verdict/params.py). It lives in cli, the top layer, because it
reads the click commands as well as every layer below.

A markdown file holds a block between two markers,

    <!-- generated: outcomes -->
    ... (the block, rewritten by this module; do not edit by hand)
    <!-- end generated -->

`python -m frictiondisk.cli.docs_blocks` rewrites every block of README.md and docs/*.md
from the code; `--check` only reports the stale ones (exit 1), as tests/test_docs.py does.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable
from pathlib import Path

__all__ = ["BLOCKS", "block_text", "documents", "refresh", "stale_blocks"]

START = "<!-- generated: {name} -->"
END = "<!-- end generated -->"
_BLOCK = re.compile(r"<!-- generated: ([a-z-]+) -->\n(.*?)<!-- end generated -->", re.S)


def _cell(text: str) -> str:
    """Text for one cell of a markdown table (a | inside would split the row)."""
    return " ".join(text.split()).replace("|", "\\|")


def outcomes_table() -> str:
    """Every outcome in listing order (verdict/outcomes.py RECORDS): what it means, and its
    side of the jump."""
    from frictiondisk.verdict import outcomes

    sides = {
        outcomes.STICK: outcomes.STICK,
        outcomes.NOT_STICK: "not stick",
        outcomes.UNDETERMINED: "—",
    }
    lines = ["| outcome | what the run showed | side of the jump |", "|---|---|---|"]
    for record in outcomes.RECORDS:
        lines.append(f"| `{record.name}` | {_cell(record.description)} | {sides[record.side]} |")
    return "\n".join(lines)


def tasks_table() -> str:
    """Every campaign task of the registry with its one-line description."""
    from frictiondisk.tasks.campaign import CampaignFile
    from frictiondisk.tasks.registry import TASKS

    lines = ["| task | what it computes |", "|---|---|"]
    for name in TASKS:
        description = CampaignFile.model_fields[name].description or ""
        lines.append(f"| `{name}` | {_cell(description.removeprefix('task: '))} |")
    return "\n".join(lines)


def commands_table() -> str:
    """Every command of the `frictiondisk` group with its short help."""
    from frictiondisk.cli.main import main

    lines = ["| command | what it does |", "|---|---|"]
    for name, command in main.commands.items():
        lines.append(f"| `frictiondisk {name}` | {_cell(command.get_short_help_str(limit=300))} |")
    return "\n".join(lines)


def verdict_params_table() -> str:
    """Every field of VerdictParams with unit, default and reason."""
    from frictiondisk.verdict.params import markdown_table

    return markdown_table()


BLOCKS: dict[str, Callable[[], str]] = {
    "outcomes": outcomes_table,
    "tasks": tasks_table,
    "commands": commands_table,
    "verdict-params": verdict_params_table,
}


def block_text(name: str) -> str:
    """The block `name` with its markers, as it stands in a document."""
    return f"{START.format(name=name)}\n{BLOCKS[name]()}\n{END}"


def documents(root: Path) -> list[Path]:
    """README.md and every markdown page of docs/ (the notes included)."""
    return [root / "README.md", *sorted((root / "docs").rglob("*.md"))]


def _refreshed(text: str, where: Path) -> str:
    def one(match: re.Match[str]) -> str:
        name = match.group(1)
        if name not in BLOCKS:
            raise ValueError(f"{where}: unknown generated block {name!r}; known: {list(BLOCKS)}")
        return block_text(name)

    return _BLOCK.sub(one, text)


def stale_blocks(root: Path) -> list[str]:
    """The documents whose generated blocks differ from the code (empty: all current)."""
    return [
        str(path.relative_to(root))
        for path in documents(root)
        if _refreshed(text := path.read_text(), path) != text
    ]


def refresh(root: Path) -> list[str]:
    """Rewrite every stale generated block; returns the documents changed."""
    changed = stale_blocks(root)
    for name in changed:
        path = root / name
        path.write_text(_refreshed(path.read_text(), path))
    return changed


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    root = Path(__file__).resolve().parents[2]
    if "--check" in args:
        stale = stale_blocks(root)
        for name in stale:
            print(f"stale generated block in {name}")
        return 1 if stale else 0
    for name in refresh(root):
        print(f"rewrote the generated blocks of {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
