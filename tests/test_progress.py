"""Progress off a terminal is plain log lines, never carriage returns (frictiondisk/engine/progress.py)."""

import io

from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.engine.progress import LogLines, progress_bar


class FakeTerminal(io.StringIO):
    def isatty(self):
        return True


def test_a_terminal_gets_a_bar_and_anything_else_log_lines():
    assert type(progress_bar(5, "x", "point", stream=FakeTerminal())).__name__ == "tqdm"
    assert isinstance(progress_bar(5, "x", "point", stream=io.StringIO()), LogLines)
    assert progress_bar(5, "x", "point", disable=True) is None


def test_log_lines_are_throttled_and_the_last_state_is_always_printed():
    out = io.StringIO()
    bar = LogLines(4, "line", "point", stream=out, every=3600.0)
    bar.update()  # the first line goes out at once
    bar.set_postfix(runs=7, in_flight=2)
    bar.update()
    bar.update()  # throttled: an hour has not passed
    bar.close()  # the final state, once
    bar.close()
    lines = out.getvalue().splitlines()
    assert len(lines) == 2
    assert lines[0].startswith("line: 1/4 point (25%), ")
    assert lines[1].startswith("line: 3/4 point (75%), ") and lines[1].endswith(
        "in_flight=2, runs=7"
    )
    assert "\r" not in out.getvalue()


CAMPAIGN = """\
name: log_line
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along: {params.x_ms: [0.08, 0.1]}
"""


def test_a_campaign_with_its_stderr_in_a_file_logs_lines(tmp_path):
    spec = tmp_path / "c.yaml"
    spec.write_text(CAMPAIGN)
    result = CliRunner().invoke(main, ["run", str(spec), "-o", str(tmp_path / "o")])
    assert result.exit_code == 0, result.output
    assert "\r" not in result.output
    assert "log_line: 2/2 point (100%)" in result.output


DASHBOARD_CAMPAIGN = """\
name: dash_line
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-8
  lanes: 1
  along: {params.x_ms: {start: 0.05, stop: 0.15, num: 40}}
"""


def test_dashboard_serves_a_page_while_the_campaign_runs(tmp_path):
    import signal
    import subprocess
    import sys
    import urllib.request

    spec = tmp_path / "d.yaml"
    spec.write_text(DASHBOARD_CAMPAIGN)
    cmd = [sys.executable, "-m", "frictiondisk.cli", "run", str(spec), "-o", str(tmp_path / "o")]
    proc = subprocess.Popen(
        [*cmd, "--dashboard"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        link = None
        for line in proc.stderr:
            if line.startswith("Dask dashboard: "):
                link = line.split(": ", 1)[1].strip()
                break
        assert link and link.startswith("http"), link
        with urllib.request.urlopen(link, timeout=30) as page:
            body = page.read().decode("utf-8", "replace")
            assert page.status == 200
        assert "<html" in body.lower() and "dask" in body.lower()
    finally:
        proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=120)
    assert proc.returncode in (0, 130)
