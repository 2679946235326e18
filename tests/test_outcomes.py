"""The outcome names and their class (frictiondisk/verdict/outcomes.py)."""

import pytest

from frictiondisk.store import cf
from frictiondisk.verdict import outcomes as oc


def test_every_outcome_has_one_class_and_only_stick_is_the_stick_side():
    assert set(oc.OUTCOME_CLASS.values()) == set(oc.CLASSES)
    assert [o for o in oc.OUTCOMES if oc.is_stick(o)] == ["stick"]
    assert [o for o in oc.OUTCOMES if not oc.is_stick(o) and not oc.is_not_stick(o)] == [
        "undetermined"
    ]


def test_the_sliding_motions_refine_not_stick():
    for name in (*oc.SLIDING_MOTIONS, "slide", "stick_slip", "creep"):
        assert oc.is_not_stick(name)
    assert oc.OUTCOMES.index("slide") > max(oc.OUTCOMES.index(m) for m in oc.SLIDING_MOTIONS)


def test_an_unknown_name_is_refused_not_guessed():
    with pytest.raises(ValueError, match="unknown outcome 'whirl'"):
        oc.outcome_class("whirl")


def test_the_stored_attribute_lists_the_same_names():
    assert cf.OUTCOMES.split() == list(oc.OUTCOMES)


def test_every_outcome_has_a_figure_style_and_a_label():
    """A new outcome in verdict/outcomes.py must be drawn: the scan figure and the run dots
    take their markers and legend text from these, and would skip a name they lack."""
    from frictiondisk.figures.shared import OUTCOME_LABEL, OUTCOME_STYLE
    from frictiondisk.verdict.outcomes import OUTCOMES

    assert set(OUTCOME_STYLE) == set(OUTCOMES)
    assert set(OUTCOME_LABEL) == set(OUTCOMES)


def test_every_name_comes_from_one_record_that_figures_cf_and_help_read():
    """One row of RECORDS names, describes and draws a motion: the figure styles, the CF
    comment of `outcome` and the CLI help are built from it, not spelled again."""
    from click.testing import CliRunner

    from frictiondisk.cli.main import main
    from frictiondisk.figures.shared import OUTCOME_LABEL, OUTCOME_STYLE

    assert [r.name for r in oc.RECORDS] == list(oc.OUTCOMES)
    for r in oc.RECORDS:
        assert oc.record(r.name) is r
        assert OUTCOME_STYLE[r.name] == {"color": r.color, "edge": r.edge, "marker": r.marker}
        assert OUTCOME_LABEL[r.name] == r.legend
        assert f"{r.name}: {r.description}" in cf.TEXT["outcome"][1]
    help_text = " ".join(CliRunner().invoke(main, ["--help"]).output.split())
    assert oc.names_text() in help_text
    # distinct looks: no two outcomes share both colour and marker
    looks = {(r.color, r.marker) for r in oc.RECORDS}
    assert len(looks) == len(oc.RECORDS)


def test_a_record_with_a_side_that_is_no_side_is_refused():
    with pytest.raises(ValueError, match="side 'sticky'"):
        oc.Outcome("glue", "sticky", "d", "k", "k", "o", "glue")
