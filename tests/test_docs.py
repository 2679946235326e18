"""The documentation lives in the repository: docs/model.md, and `show-defaults`."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.model.scene import Params, load_scene, scene_from_dict
from frictiondisk.verdict.outcomes import OUTCOMES

ROOT = Path(__file__).resolve().parents[1]


def test_model_document_names_every_scene_parameter():
    text = (ROOT / "docs" / "model.md").read_text()
    for section in ("## 3. Friction law", "## 5. Defaults", "## 6. Outcomes"):
        assert section in text
    missing = [key for key in Params.model_fields if f"`params.{key}`" not in text]
    assert not missing, f"docs/model.md section 5 lacks {missing}"
    for outcome in OUTCOMES:
        assert f"`{outcome}`" in text, outcome


def test_nothing_points_outside_the_repository():
    files = subprocess.run(
        ["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=False
    ).stdout.split()
    if not files:
        pytest.skip("not a git checkout")
    bad = []
    for name in files:
        path = ROOT / name
        if (
            path.suffix not in (".py", ".md", ".yaml", ".ipynb", ".toml", ".txt", "")
            or not path.is_file()
        ):
            continue
        text = path.read_text(errors="replace")
        if "shared/MODEL" in text or "MODEL.md" in text or "../shared" in text:
            bad.append(name)
    bad = [b for b in bad if b != "tests/test_docs.py"]
    assert not bad, f"these files point outside the repository: {bad}"


@pytest.mark.parametrize("scene", ["pin", "disk"])
def test_show_defaults_prints_a_loadable_resolved_scene(scene, tmp_path):
    result = CliRunner().invoke(main, ["show-defaults", "--scene", scene])
    assert result.exit_code == 0, result.output
    data = yaml.safe_load(result.output)
    assert data["scene"] == scene
    assert data["contact"]["points"] == (1 if scene == "pin" else 12)
    assert data["params"]["omega_m"] == 1.1 and data["contact"]["stiffness"] == 2.53e5
    path = tmp_path / "defaults.yaml"
    path.write_text(result.output)
    assert load_scene(path).canonical() == scene_from_dict({"scene": scene}).canonical()


def test_show_defaults_rejects_an_unknown_scene():
    result = CliRunner().invoke(main, ["show-defaults", "--scene", "wheel"])
    assert result.exit_code == 2
    assert "--scene" in result.output


def test_show_defaults_is_wired_to_the_console_script():
    out = subprocess.run(
        [sys.executable, "-m", "frictiondisk.cli", "show-defaults"],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    ).stdout
    assert out.startswith("contact:")


def test_reference_document_is_generated_from_the_schemas():
    from frictiondisk.tasks.reference import reference_markdown

    text = (ROOT / "docs" / "reference.md").read_text()
    assert text == reference_markdown(), (
        "docs/reference.md is out of date; regenerate it with: python -c "
        '"from frictiondisk.tasks.reference import reference_markdown; '
        "open('docs/reference.md', 'w').write(reference_markdown())\""
    )
    for key in ("`params.mu`", "`numerics.rtol`", "`find_jump.tol`", "`basin.target_se`"):
        assert key in text


def test_show_defaults_comments_every_key_with_unit_and_description():
    out = CliRunner().invoke(main, ["show-defaults"]).output
    assert "rtol: 1.0e-06  # relative tolerance; auto: from find_jump.tol [1]" in out
    assert "  x_ms: 0.1  # axes offset: the slave's rest position is (x_ms, 0) [m]" in out
    assert all("  # " in line for line in out.splitlines())


@pytest.mark.parametrize("task", ["find_jump", "scan", "trajectory", "basin", "trace"])
def test_show_defaults_prints_a_task_s_keys(task):
    from frictiondisk.tasks.registry import TASKS

    result = CliRunner().invoke(main, ["show-defaults", "--task", task])
    assert result.exit_code == 0, result.output
    assert result.output.startswith(f"{task}:")
    for name in TASKS[task].spec.model_fields:
        assert f" {name}:" in result.output
    assert "find_jump:" not in CliRunner().invoke(main, ["show-defaults"]).output


@pytest.mark.parametrize(
    "task, good",
    [
        ("find_jump", "demo_line"),
        ("scan", "demo_scan"),
        ("trajectory", "fig04_trajectory"),
        ("basin", "basin_pin_x0"),
        ("trace", "trace_fig10_disk_x0"),
    ],
)
def test_show_defaults_task_block_loads_once_its_commented_keys_are_filled(task, good):
    """The printed block, pasted into a campaign with the keys it leaves commented out (the
    required ones, and those without a default) taken from a known-good campaign, loads."""
    from frictiondisk.tasks.campaign import campaign_from_dict

    result = CliRunner().invoke(main, ["show-defaults", "--task", task])
    assert result.exit_code == 0, result.output
    block = yaml.safe_load(result.output)[task] or {}
    data = yaml.safe_load((ROOT / "campaigns" / f"{good}.yaml").read_text())
    filled = {**block, **{k: v for k, v in data[task].items() if k not in block}}
    campaign = campaign_from_dict({**data, task: filled})
    assert campaign.kind == task
    for line in result.output.splitlines()[1:]:  # every key: a value or a commented-out key
        assert line.startswith(("  # ", "    ")) or ": " in line, line


def _links(text: str) -> list[str]:
    """The relative targets of the markdown links and images in `text`."""
    import re

    targets = re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text)
    return [t for t in targets if "://" not in t]


def test_the_readme_is_a_five_minute_start():
    """Issue 29: what the tool does, the two commands, one campaign, the outcomes and where
    the rest is; the quick start fits on one screen before the first link into docs/."""
    text = (ROOT / "README.md").read_text()
    start = text.index("## Quick start")
    quick = text[start : text.index("\n## ", start + 1)]
    assert quick.count("\n") <= 45, f"the quick start is {quick.count(chr(10))} lines"
    assert "docs/" not in text[: start + len(quick)], "a link into docs/ before the quick start"
    for must in ("make demo", "make test"):
        assert must in quick, must
    for section in ("campaign", "outcome", "docs/user-guide.md"):
        assert section in text.lower() or section in text, section
    for outcome in OUTCOMES:
        assert f"`{outcome}`" in text, outcome
    assert len(text) <= 12_000, f"README.md is {len(text)} characters"


@pytest.mark.parametrize("name", ["README.md", "docs/user-guide.md"])
def test_every_relative_link_of_the_guides_resolves(name):
    path = ROOT / name
    missing = [t for t in _links(path.read_text()) if not (path.parent / t).exists()]
    assert not missing, f"{name} links to missing files: {missing}"


# --- the documentation says what the code has, and what the tool does now ----------------

USER_PAGES = ("README.md", "docs/user-guide.md", "docs/model.md", "docs/reference.md")


def _pages_outside_notes() -> list[Path]:
    return [p for p in (ROOT / "docs").rglob("*.md") if "notes" not in p.relative_to(ROOT).parts]


def test_every_generated_block_equals_what_the_code_generates():
    """The outcome, task and command tables of README.md and docs/ come from the code
    (frictiondisk/cli/docs_blocks.py); a renamed outcome or a new option makes them stale."""
    from frictiondisk.cli.docs_blocks import stale_blocks

    stale = stale_blocks(ROOT)
    assert not stale, f"regenerate with `python -m frictiondisk.cli.docs_blocks`: {stale}"


def test_the_outcome_meanings_name_exactly_the_outcomes_of_the_code():
    from frictiondisk.cli.docs_blocks import outcomes_table

    table = outcomes_table()
    assert table.count("\n| `") == len(OUTCOMES)
    for page in ("README.md", "docs/user-guide.md", "docs/model.md"):
        assert table in (ROOT / page).read_text(), page


def test_the_generated_blocks_follow_a_change_of_the_code(monkeypatch):
    """A block is rebuilt from the code, not kept: a new outcome shows up in the table."""
    from frictiondisk.cli import docs_blocks
    from frictiondisk.verdict import outcomes

    wobble = outcomes.Outcome("wobble", "not_stick", "wobbles", "k", "k", "o", "wobble")
    monkeypatch.setattr(outcomes, "RECORDS", (*outcomes.RECORDS, wobble))
    assert "| `wobble` | wobbles | not stick |" in docs_blocks.outcomes_table()
    assert "README.md" in docs_blocks.stale_blocks(ROOT)


def test_the_readme_leads_a_newcomer_in_order():
    """What the tool answers, the two commands, one picture, all eight outcomes, the tasks
    (with `between`), and where the rest is: in that order."""
    from frictiondisk.tasks.registry import TASKS

    text = (ROOT / "README.md").read_text()
    marks = [
        text.index("answers"),
        text.index("make demo"),
        text.index("make test"),
        text.index("!["),
        text.index("<!-- generated: outcomes -->"),
        text.index("<!-- generated: tasks -->"),
        text.index("## Where the rest is"),
    ]
    assert marks == sorted(marks), marks
    assert text.count("![") == 1, "one picture"
    tasks = text[marks[5] : marks[6]]
    for task in (*TASKS, "between"):
        assert f"`{task}`" in tasks, task
    assert {"find_jump", "trace", "map", "basin", "scan", "trajectory"} <= set(TASKS)


@pytest.mark.parametrize("page", USER_PAGES)
def test_user_pages_carry_no_dates_loads_or_issue_history(page):
    import re

    text = (ROOT / page).read_text()
    patterns = (
        r"\b20\d\d-[01]\d",  # a date
        r"\bload (average )?\d",  # a machine load
        r"\bissues? \d+",  # an issue number
        r"NUMERICS_VERSION \d",  # the history of the numerics
        r"this machine",
    )
    found = [m.group(0) for p in patterns for m in re.finditer(p, text, flags=re.IGNORECASE)]
    assert not found, f"{page}: {found} (history goes to docs/notes/ or a commit message)"


def test_no_page_of_docs_names_a_scratch_path_outside_the_repository():
    import re

    bad = {
        str(p.relative_to(ROOT)): re.findall(r"(?:/tmp/|/work/|/home/)\S*", p.read_text())
        for p in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md")]
    }
    bad = {page: paths for page, paths in bad.items() if paths}
    assert not bad, bad


def test_the_user_docs_stay_within_their_length():
    lines = {p.name: p.read_text().count("\n") for p in _pages_outside_notes()}
    assert sum(lines.values()) <= 3500, f"docs/ outside notes/: {sum(lines.values())} lines"
    assert lines["wellposed.md"] <= 300, lines["wellposed.md"]


def test_the_model_has_a_subsection_per_outcome_and_names_every_verdict_parameter_in_a_rule():
    import dataclasses

    from frictiondisk.verdict.params import VerdictParams

    text = (ROOT / "docs" / "model.md").read_text()
    for outcome in OUTCOMES:
        assert f"\n#### `{outcome}`\n" in text, outcome
    rules = text[text.index("### 6.2 The rules") : text.index("### 6.3")]
    assert rules.count("\n#### 6.2.") >= 7
    missing = [f.name for f in dataclasses.fields(VerdictParams) if f"`{f.name}`" not in rules]
    assert not missing, f"no rule of docs/model.md section 6.2 names {missing}"


def test_the_benchmarks_page_has_one_command_per_table_section():
    text = (ROOT / "docs" / "benchmarks.md").read_text()
    sections = text.split("\n## ")[1:]
    assert "Campaign engine (bench_engine)" in text
    for section in sections:
        title = section.splitlines()[0]
        if title.startswith("Campaign engine"):
            continue
        assert "```sh" in section, f"benchmarks.md, '{title}': no command"
        assert section.count("\n| ") >= 2 or "no standing table" in section, title


def test_the_documentation_site_builds_without_a_warning(tmp_path):
    """`make docs` builds the site with -W; here the same sources through the dummy
    builder (every page read, the API and CLI references generated, no HTML written)."""
    result = subprocess.run(
        [sys.executable, "-m", "sphinx", "-b", "dummy", "-W", "--keep-going", "-q", "docs"]
        + [str(tmp_path / "site")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    makefile = (ROOT / "Makefile").read_text()
    assert "-m sphinx -b html -W" in makefile and "\ndocs: $(STAMP)" in makefile


def test_the_site_documents_the_public_api_and_every_command():
    import frictiondisk
    from frictiondisk.cli.main import main

    api = (ROOT / "docs" / "api.md").read_text()
    cli = (ROOT / "docs" / "cli.md").read_text()
    assert ".. automodule:: frictiondisk" in api and ":members:" in api
    assert ".. click:: frictiondisk.cli.main:main" in cli and ":nested: full" in cli
    for name in frictiondisk.__all__:
        if name != "__version__":
            assert getattr(frictiondisk, name).__doc__, f"{name} has no docstring"
    assert all(command.help for command in main.commands.values())
    index = (ROOT / "docs" / "index.md").read_text()
    pages = {p.stem for p in (ROOT / "docs").glob("*.md")} - {"index"}
    assert all(page in index for page in pages), pages - {p for p in pages if p in index}
