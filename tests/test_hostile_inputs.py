"""Hostile inputs (issue 14): every case of the adversarial probe ends in exit 2 with a
message naming the field or path, or in a correct result, within a bounded time, and never
in a traceback. Plus a property-based fuzz of scene and campaign YAML.

Most cases must be refused before the kernel runs; they run in-process (CliRunner) with
the simulation replaced by a tripwire. The integrity cases share one small finished
campaign (2 points, 14 runs). Ctrl-C and the scheduler use real processes and sockets.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner
from conftest import HANG_S, wait_for_cpu
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictiondisk.cli import main
from frictiondisk.engine import budget
from frictiondisk.engine import driver as driver_module
from frictiondisk.model.limits import max_workers
from frictiondisk.model.scene import ConfigError, scene_from_dict
from frictiondisk.model.yamlio import load_yaml_text
from frictiondisk.store import journal_entry as journal_module
from frictiondisk.tasks.campaign import campaign_from_text

REPO = Path(__file__).resolve().parent.parent
BOUND_S = 30.0  # the bound on every case

CAMPAIGN = """\
name: tiny
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along: {params.x_ms: [0.08, 0.1]}
"""


def cli(*args) -> tuple[int, str, float]:
    """(exit code, stdout + stderr, seconds) of `frictiondisk ARGS` run in-process."""
    t0 = time.monotonic()
    result = CliRunner().invoke(main, [str(arg) for arg in args])
    elapsed = time.monotonic() - t0
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise AssertionError(f"uncaught {result.exception!r}:\n{result.output}")
    return result.exit_code, result.output, elapsed


def refused(args, *names) -> str:
    """Run the CLI, assert exit 2, a message with every one of `names`, no traceback."""
    code, output, elapsed = cli(*args)
    assert code == 2, output
    assert "Traceback" not in output
    for name in names:
        assert name in output, output
    assert elapsed < BOUND_S
    return output


@pytest.fixture
def no_kernel(monkeypatch):
    """Fail the test if anything reaches the simulation."""

    def tripwire(*args, **kwargs):
        raise AssertionError("the kernel ran; the input should have been refused first")

    # the module, not the package attribute `frictiondisk.simulation.simulate` (the public function)
    monkeypatch.setattr(
        importlib.import_module("frictiondisk.simulation.simulate"), "simulate", tripwire
    )
    monkeypatch.setattr(driver_module.Driver, "run", tripwire)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


# --- deep nesting -------------------------------------------------------------------------


@pytest.mark.parametrize("depth", [490, 100_000])
def test_deeply_nested_yaml_list_is_refused(tmp_path, no_kernel, depth):
    scene = _write(tmp_path / "s.yaml", "scene: pin\nparams: " + "[" * depth + "]" * depth)
    refused(["simulate", scene], "s.yaml", "nested more than 32 levels")


def test_deeply_nested_yaml_mapping_is_refused(tmp_path, no_kernel):
    flow = "scene: pin\nparams: " + "{a: " * 3000 + "1" + "}" * 3000 + "\n"
    refused(["simulate", _write(tmp_path / "f.yaml", flow)], "nested more than 32 levels")
    lines = ["scene: pin", "params:"] + [" " * i + f"k{i}:" for i in range(1, 500)]
    scene = _write(tmp_path / "s.yaml", "\n".join(lines) + "\n")
    refused(["simulate", scene], "nested more than 32 levels")
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN + "\n".join(lines[1:]) + "\n")
    refused(["run", campaign, "-o", tmp_path / "out"], "nested more than 32 levels")
    assert not (tmp_path / "out").exists()


def test_deep_set_key_and_value_are_refused(tmp_path, no_kernel):
    scene = _write(tmp_path / "s.yaml", "scene: pin\n")
    refused(["simulate", scene, "--set", "a." * 990 + "b=1"], "991 dotted parts")
    deep = "params.mu=" + "[" * 2000 + "]" * 2000
    refused(["simulate", scene, "--set", deep], "--set", "nested more than 32 levels")
    deep = "params.mu=" + "{a: " * 2000 + "1" + "}" * 2000
    refused(["simulate", scene, "--set", deep], "--set", "nested more than 32 levels")


def test_huge_file_is_refused(tmp_path, no_kernel):
    scene = _write(tmp_path / "s.yaml", "scene: pin\n" + "#" * (5 << 20))
    refused(["simulate", scene], "larger than 4 MiB")


# --- bounds -------------------------------------------------------------------------------


def test_integer_beyond_int64_is_refused(tmp_path, no_kernel):
    scene = _write(
        tmp_path / "s.yaml", "scene: pin\nnumerics: {max_steps: 100000000000000000000000}\n"
    )
    refused(["simulate", scene], "numerics.max_steps", "<= 9223372036854775807")
    refused(["simulate", scene, "--set", "numerics.max_events=1" + "0" * 30], "max_events")


def test_absurd_magnitudes_are_refused(tmp_path, no_kernel):
    """x_ms = omega_m = vx0 = 1e300 once 'stuck' after 0 steps; now each is named."""
    params = "params: {x_ms: 1.0e300, omega_m: 1.0e300, vx0: 1.0e300}\n"
    scene = _write(tmp_path / "s.yaml", "scene: pin\n" + params)
    refused(
        ["simulate", scene],
        "params.x_ms: 1e+300 is out of range",
        "params.omega_m",
        "params.vx0",
    )


@pytest.mark.parametrize(
    ("num", "message"),
    [
        ("1000000000", "<= 10000"),
        ("100000000000000000000000", "<= 10000"),
        ("2000000", "<= 10000"),
    ],
)
def test_huge_grid_is_refused_at_once(tmp_path, no_kernel, num, message):
    text = CAMPAIGN.replace("[0.08, 0.1]", "{start: 0.02, stop: 0.2, num: " + num + "}")
    campaign = _write(tmp_path / "c.yaml", text)
    refused(
        ["run", campaign, "-o", tmp_path / "out"],
        "find_jump.along.params.x_ms.num",
        message,
    )
    assert not (tmp_path / "out").exists()


def test_campaign_over_the_size_limits_needs_force(tmp_path, no_kernel):
    grid = (
        "{params.x_ms: {start: 0.02, stop: 0.2, num: 1000}, "
        "params.x0: {start: -0.01, stop: 0.01, num: 1000}}"
    )
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN.replace("{params.x_ms: [0.08, 0.1]}", grid))
    output = refused(
        ["run", campaign, "-o", tmp_path / "out"],
        "find_jump.along.params.x_ms",
        "1000000 points; the limit is 100000",
        "--force",
    )
    assert "runs" in output
    assert not (tmp_path / "out").exists()
    size = budget.estimate(campaign_from_text(campaign.read_text()))
    assert size.points == 10**6 and size.runs == 10**6 * 7  # 2 ends + 5 halvings each


def test_retry_horizon_must_stay_finite(tmp_path, no_kernel):
    text = CAMPAIGN.replace("  tol:", "  horizon_factor: 1.0e308\n  tol:")
    campaign = _write(tmp_path / "c.yaml", text)
    refused(
        ["run", campaign, "-o", tmp_path / "out"],
        "find_jump.horizon_factor: 1e+308 is out of range",
        "max_retries 2",
    )


def test_recording_interval_that_overflows_the_buffer_is_refused(tmp_path, no_kernel):
    scene = _write(tmp_path / "s.yaml", "scene: pin\n")
    refused(
        ["simulate", scene, "--dt-out", "1e-9", "-o", tmp_path / "t.nc"],
        "--dt-out: 1e-09 s is out of range",
        "must be >=",
    )
    text = "name: orbit\nscene: pin\ntrajectory: {dt_out: 1.0e-9}\n"
    campaign = _write(tmp_path / "c.yaml", text)
    refused(["run", campaign, "-o", tmp_path / "out"], "trajectory.dt_out")


def test_too_many_workers_are_refused(tmp_path, no_kernel):
    if max_workers() >= 256:
        pytest.skip("this machine can run 256 workers")
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
    refused(["run", campaign, "-o", tmp_path / "out", "--workers", "256"], "--workers: 256")
    assert not (tmp_path / "out").exists()


# --- output paths -------------------------------------------------------------------------


def test_output_under_a_file_is_refused_before_anything_is_created(tmp_path, no_kernel):
    (tmp_path / "afile").write_text("x")
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
    refused(["run", campaign, "-o", tmp_path / "afile" / "sub"], "afile", "not a directory")
    scene = _write(tmp_path / "s.yaml", "scene: pin\n")
    refused(["simulate", scene, "-o", tmp_path / "afile" / "t.nc"], "afile", "not a directory")
    refused(["simulate", scene, "--plot", tmp_path / "afile" / "d" / "t.png"], "afile")
    refused(["simulate", scene, "-o", tmp_path], str(tmp_path), "is a directory")


@contextlib.contextmanager
def _mounted_tmpfs(path: Path, options: str):
    """A tmpfs at `path` (root only); skips the test where mounting is not allowed."""
    path.mkdir()
    done = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(path)],
        capture_output=True,
        check=False,
    )
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.decode().strip()}")
    try:
        yield path
    finally:
        subprocess.run(["umount", "-l", str(path)], check=False)


@contextlib.contextmanager
def _read_only_dir(tmp_path: Path):
    if os.geteuid() == 0:  # root writes through permissions: use a read-only mount
        with _mounted_tmpfs(tmp_path / "ro", "ro,size=64k") as path:
            yield path
        return
    path = tmp_path / "ro"
    path.mkdir(mode=0o555)
    try:
        yield path
    finally:
        path.chmod(0o755)


def test_read_only_output_is_refused_before_the_work(tmp_path, no_kernel):
    with _read_only_dir(tmp_path) as ro:
        campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
        output = refused(["run", campaign, "-o", ro / "out"], str(ro))
        assert "read-only file system" in output or "permission denied" in output
        scene = _write(tmp_path / "s.yaml", "scene: pin\n")
        refused(["simulate", scene, "-o", ro / "t.nc"], str(ro))
        refused(["simulate", scene, "--plot", ro / "t.png"], str(ro))


def test_unusable_scheduler_is_refused_before_dir_is_created(tmp_path, no_kernel):
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
    for address, words in [
        ("tcp://127.0.0.1:1", "nothing answers at tcp://127.0.0.1:1"),
        ("notanaddress", "not a scheduler address"),
    ]:
        output = refused(["run", campaign, "-o", tmp_path / "out", "--scheduler", address], words)
        assert "--scheduler" in output
        assert not (tmp_path / "out").exists()


# --- a finished campaign: integrity ---------------------------------------------------------


@pytest.fixture(scope="module")
def finished(tmp_path_factory) -> Path:
    """A finished 2-point find_jump campaign (14 runs, ~2 s once the kernel is cached)."""
    root = tmp_path_factory.mktemp("finished")
    campaign = _write(root / "c.yaml", CAMPAIGN)
    code, output, _ = cli("run", campaign, "-o", root / "dir", "--workers", "1")
    assert code == 0, output
    return root / "dir"


@pytest.fixture
def campaign_dir(finished, tmp_path) -> Path:
    """A private copy of the finished campaign."""
    copy = tmp_path / "dir"
    shutil.copytree(finished, copy)
    return copy


def _brackets(directory: Path) -> tuple:
    with xr.open_dataset(directory / "results.nc") as ds:
        return tuple(ds["mu_lo"].values.tolist()), tuple(ds["mu_hi"].values.tolist())


def _entries(directory: Path) -> list[Path]:
    return sorted((directory / "journal").glob("??/*.json"))


@pytest.mark.parametrize("name", ["lock", "journal/computed.log", "status.json", "results.nc"])
def test_resume_never_writes_through_a_symlink(campaign_dir, tmp_path, name):
    outside = tmp_path / "outside.txt"
    outside.write_text("precious\n")
    link = campaign_dir / name
    link.unlink()
    link.symlink_to(outside)
    output = refused(["resume", campaign_dir], str(link), "symbolic link")
    assert outside.read_text() == "precious\n"
    assert "Traceback" not in output


def test_symlinked_entry_or_shard_is_never_followed(campaign_dir, finished, tmp_path):
    outside = tmp_path / "outside.json"
    entry = _entries(campaign_dir)[0]
    original = entry.read_bytes()
    outside.write_bytes(original)
    entry.unlink()
    entry.symlink_to(outside)
    code, output, _ = cli("resume", campaign_dir)
    assert code == 0, output
    assert "a symbolic link (never followed)" in output and "1 computed now" in output
    assert outside.read_bytes() == original  # the link was moved aside, a new file written
    assert not entry.is_symlink()
    assert _brackets(campaign_dir) == _brackets(finished)

    shard = _entries(campaign_dir)[0].parent
    shutil.move(shard, tmp_path / "shard")
    shard.symlink_to(tmp_path / "shard")
    refused(["resume", campaign_dir], str(shard), "symbolic link")


def test_forged_and_corrupt_entries_are_reported_rejected_and_recomputed(campaign_dir, finished):
    first, second, third = _entries(campaign_dir)[:3]
    forged = json.loads(first.read_text())
    forged["inputs"] = json.loads(second.read_text())["inputs"]  # another run's inputs
    forged["sha256"] = journal_module.entry_digest(
        forged["key"], forged["inputs"], forged["result"]
    )
    first.write_text(json.dumps(forged))
    third.write_text('{"truncated')

    code, status, _ = cli("status", campaign_dir)
    assert code == 0, status
    assert "2 entries fail verification" in status
    assert f"{first.stem}: its inputs give key" in status
    assert f"{third.stem}: truncated or not JSON" in status

    code, output, _ = cli("resume", campaign_dir)
    assert code == 0, output
    assert "rejected and recomputed" in output and "2 computed now" in output
    assert "its inputs give key" in output
    assert _brackets(campaign_dir) == _brackets(finished)

    code, status, _ = cli("status", campaign_dir)
    assert "2 entries were moved aside" in status and "its inputs give key" in status
    assert "fail verification" not in status


def test_hand_edited_campaign_yaml_is_refused(campaign_dir):
    stored = campaign_dir / "campaign.yaml"
    original = stored.read_text()
    stored.write_text(original.replace("tol: 1.0e-2", "tol: 2.0e-2"))
    refused(["resume", campaign_dir], "was edited", "find_jump.tol: 0.01 -> 0.02")
    code, status, _ = cli("status", campaign_dir)
    assert code == 0 and "resume will refuse" in status and "find_jump.tol" in status
    stored.write_text(original + "# a comment changes nothing\n")
    code, output, _ = cli("resume", campaign_dir)
    assert code == 0 and "0 computed now" in output, output


def test_full_disk_is_named_and_resumable(finished, tmp_path):
    with _mounted_tmpfs(tmp_path / "small", "size=256k") as small:
        directory = small / "dir"
        shutil.copytree(finished, directory)
        for path in [*(directory / "journal").iterdir(), directory / "results.nc"]:
            shutil.rmtree(path) if path.is_dir() else path.unlink()
        (small / "fill").write_bytes(b"\0" * (shutil.disk_usage(small).free - (4 << 10)))
        output = refused(["resume", directory], str(directory), "no space left on the device")
        assert "frictiondisk resume" in output
        (small / "fill").unlink()
        code, output, _ = cli("resume", directory)
        assert code == 0, output
        assert _brackets(directory) == _brackets(finished)


def test_scheduler_without_workers_warns_then_fails(tmp_path, monkeypatch):
    from distributed import LocalCluster

    monkeypatch.setattr(driver_module, "POLL", 0.2)
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
    with LocalCluster(
        n_workers=0, processes=False, protocol="tcp", dashboard_address=None
    ) as cluster:
        args = ["run", campaign, "-o", tmp_path / "out", "--worker-wait", "1"]
        output = refused(
            [*args, "--scheduler", cluster.scheduler_address], "no worker alive", "resume"
        )
    assert "warning: no worker is alive" in output


# --- bounded runs ---------------------------------------------------------------------------


def test_recording_stops_when_its_buffer_is_full():
    """The kernel once kept evaluating dense output after the buffer was full."""
    from frictiondisk.simulation.simulate import simulate

    config = scene_from_dict({"scene": "pin", "numerics": {"t_decide": 2.0}})
    t0 = time.monotonic()
    result = simulate(config, record=True, dt_out=1e-9)  # bypasses the CLI's check
    assert time.monotonic() - t0 < BOUND_S
    assert result.trajectory.truncated
    assert result.trajectory.t[-1] < 0.01  # stopped recording, not stopped the run
    assert result.t_end > 1.0


@pytest.mark.parametrize("rule", ["contacts", "corotation"])
def test_stick_after_zero_steps_is_undetermined(rule):
    """Past validation (model_copy skips it), x_ms = omega_m = vx0 = 1e300 made a revolution
    of 6e-300 s and 'stuck' at t = 0; a stick needs steps, so it is undetermined (under
    `corotation` the first step, cut at that revolution, already underflows)."""
    from frictiondisk.simulation.simulate import simulate

    config = scene_from_dict({"scene": "pin", "numerics": {"stick_rule": rule}})
    huge = {"omega_m": 1e300, "x_ms": 1e300, "vx0": 1e300}
    config = config.model_copy(update={"params": config.params.model_copy(update=huge)})
    result = simulate(config)
    assert result.outcome == "undetermined" and result.n_steps == 0
    expected = "0 steps" if rule == "contacts" else "step size underflow"
    assert expected in result.reason


def test_ctrl_c_stops_simulate_within_two_seconds(tmp_path):
    scene = _write(
        tmp_path / "s.yaml",
        "scene: disk\ncontact: {points: 200}\n"
        "numerics: {t_decide: 100000.0, stop_on_stick: false, max_steps: 1000000000}\n",
    )
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    process = subprocess.Popen(
        [sys.executable, "-m", "frictiondisk.cli", "simulate", str(scene)],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # an ignored SIGINT is inherited across exec (and some earlier test in the same
        # pytest process leaves it ignored): give the child the default, like a terminal
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    # Wait until the kernel runs: `simulate` starts it in a second (daemon) thread after its
    # imports; a SIGINT during the imports would test the imports, not the kernel.
    child = psutil.Process(process.pid)
    deadline = time.monotonic() + HANG_S
    while child.num_threads() < 2 and time.monotonic() < deadline:
        time.sleep(0.2)
    # the cached kernel loads, then runs for minutes: 2 s of the child's CPU time, not of
    # the clock (on a busy machine 2 s of the clock may not reach the kernel)
    wait_for_cpu(process.pid, 2.0)
    assert process.poll() is None
    process.send_signal(signal.SIGINT)
    t0 = time.monotonic()
    said = _stderr_until(process, "interrupted", timeout=10.0)  # the stop's message
    stopped_in = time.monotonic() - t0
    try:
        _, err = process.communicate(timeout=10)
    finally:
        process.kill()
    assert "interrupted" in said, said
    assert stopped_in < 2.0, stopped_in
    assert process.returncode == 130 and "Traceback" not in said + err


def _stderr_until(process, word: str, timeout: float) -> str:
    """What `process` writes to its (text) stderr up to the first line with `word` (all of
    it if the stream ends first; what came within `timeout` s)."""
    import select

    said, deadline = "", time.monotonic() + timeout
    while word not in said and time.monotonic() < deadline:
        if not select.select([process.stderr], [], [], deadline - time.monotonic())[0]:
            break
        line = process.stderr.readline()
        if not line:
            break
        said += line
    return said


# --- fuzz -----------------------------------------------------------------------------------

_SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=8),
)
_VALUES = st.recursive(
    _SCALARS,
    lambda inner: st.one_of(
        st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=6), inner, max_size=4)
    ),
    max_leaves=12,
)
_SCENE_KEYS = {
    "params": ["mu", "x_ms", "omega_m", "vx0", "m_s", "F_n"],
    "contact": ["points", "stiffness", "eps", "ring_radius"],
    "numerics": ["max_steps", "t_decide", "rtol", "method", "mode", "preset"],
}


@st.composite
def _scenes(draw):
    data = {"scene": draw(st.sampled_from(["pin", "disk", "ring", 3]))}
    for section, keys in _SCENE_KEYS.items():
        if draw(st.booleans()):
            chosen = draw(st.lists(st.sampled_from(keys), max_size=3, unique=True))
            data[section] = {key: draw(_VALUES) for key in chosen}
    if draw(st.booleans()):
        data[draw(st.text(max_size=6))] = draw(_VALUES)
    return data


_AXIS = st.one_of(
    st.lists(st.floats(-1.0, 1.0), min_size=0, max_size=4),
    st.fixed_dictionaries(
        {
            "start": st.floats(allow_nan=True, allow_infinity=True),
            "stop": st.floats(-1.0, 1.0),
            "num": st.one_of(st.integers(-2, 20), st.sampled_from([10**9, 10**23])),
        }
    ),
    _VALUES,
)


@st.composite
def _campaigns(draw):
    data = {"name": draw(st.sampled_from(["fz", "", "a b", 1])), **draw(_scenes())}
    task = draw(st.sampled_from(["find_jump", "scan", "trajectory", "other"]))
    if task == "find_jump":
        data[task] = {
            "bracket": draw(st.one_of(st.lists(st.floats(0.0, 1.0), max_size=3), _VALUES)),
            "horizon_factor": draw(st.one_of(st.floats(0.5, 1e308), _SCALARS)),
            "max_retries": draw(st.integers(-1, 12)),
            "along": {draw(st.sampled_from(["params.x_ms", "params.mu", "nope"])): draw(_AXIS)},
        }
    elif task == "scan":
        data[task] = {"mu": draw(_AXIS), "mode": draw(st.sampled_from(["decide", "x"]))}
    else:
        data[task] = {"dt_out": draw(st.one_of(st.floats(), _SCALARS))}
    return data


_FUZZ = settings(
    max_examples=100,
    deadline=2000,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
    database=None,
)


@_FUZZ
@given(_scenes())
def test_fuzzed_scene_is_valid_or_a_config_error(data):
    text = yaml.safe_dump(data)
    with contextlib.suppress(ConfigError):
        scene_from_dict(load_yaml_text(text, "fuzz.yaml"), source="fuzz.yaml")


@_FUZZ
@given(_campaigns())
def test_fuzzed_campaign_is_valid_or_a_config_error(data):
    text = yaml.safe_dump(data)
    try:
        campaign = campaign_from_text(text, "fuzz.yaml")
    except ConfigError as err:
        assert err.problems and all(isinstance(p, str) and p for p in err.problems)
        return
    assert isinstance(budget.check(campaign), list)


@_FUZZ
@given(st.text(max_size=200))
def test_fuzzed_text_is_yaml_or_a_config_error(text):
    with contextlib.suppress(ConfigError):
        load_yaml_text(text, "fuzz.yaml")


# --- bounded errors -------------------------------------------------------------------------

ALIAS_BOMB = """\
name: bomb
scene: pin
a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]
b: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]
c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]
d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]
e: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]
f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]
params: {x0: *f}
find_jump: {bracket: [0.04, 0.3], along: {params.x_ms: [0.05]}}
"""


def _bounded(output: str, max_lines: int = 14, max_line: int = 400) -> None:
    lines = output.splitlines()
    assert len(lines) <= max_lines, f"{len(lines)} lines"
    assert max(map(len, lines)) <= max_line, max(map(len, lines))


def test_an_alias_bomb_is_refused_in_one_short_line(tmp_path, no_kernel):
    campaign = _write(tmp_path / "bomb.yaml", ALIAS_BOMB)
    output = refused(["run", campaign, "-o", tmp_path / "out"], "bomb.yaml", "params.x0")
    assert "aliases (*name) repeat more than 100000 values" in output
    assert len(output.encode()) < 2048 and len(output.splitlines()) == 2, output
    assert not (tmp_path / "out").exists()
    # a smaller one (6 561 values) reaches the validator, which shows the value in short
    lines = ALIAS_BOMB.splitlines()
    small = "\n".join([*lines[:6], "params: {x0: *d}", lines[-1]]) + "\n"
    output = refused(["run", _write(tmp_path / "w.yaml", small), "-o", tmp_path / "o"], "x0")
    _bounded(output)


def test_a_recursive_alias_is_refused(tmp_path, no_kernel):
    scene = _write(tmp_path / "s.yaml", "scene: pin\nparams: &p {x0: *p}\n")
    output = refused(["simulate", scene], "s.yaml", "recursive alias")
    _bounded(output, max_lines=2)


@pytest.mark.parametrize(
    ("text", "names"),
    [
        ("params: {x0: '" + "v" * 3_000_000 + "'}\n", ["params.x0", "is a string"]),
        ("params: {x0: *" + "q" * 100_000 + "}\n", ["undefined alias"]),
        ("".join(f"junk{i}: 1\n" for i in range(5000)), ["junk0", "... and 4989 more problems"]),
        ("params: {mu: 0.1}\n" * 3000, ["params: duplicate key", "more problems"]),
        ("params:\n" + "".join(f"  mu{i}: 1\n" for i in range(2000)), ["params.mu0"]),
    ],
    ids=["huge_scalar", "huge_alias_name", "many_unknown_keys", "many_duplicates", "many_keys"],
)
def test_any_config_error_is_a_few_short_lines(tmp_path, no_kernel, text, names):
    scene = _write(tmp_path / "s.yaml", "scene: pin\n" + text)
    output = refused(["simulate", scene], "s.yaml", *names)
    _bounded(output)


def test_a_nested_value_is_shown_in_a_few_characters():
    nested = [[[[list(range(50))] * 50] * 50] * 50]
    with pytest.raises(ConfigError) as caught:
        scene_from_dict({"scene": "pin", "params": {"x0": nested}})
    assert len(str(caught.value)) < 300, str(caught.value)


# --- a tol out of reach -------------------------------------------------------------------


def _tol_campaign(tol: str) -> str:
    return (
        "name: t\nscene: pin\nparams: {x0: 0.0}\nnumerics: {mode: decide, t_decide: 30.0}\n"
        f"find_jump:\n  bracket: [0.04, 0.3]\n  tol: {tol}\n  along:\n    params.x_ms: [0.05]\n"
    )


@pytest.mark.parametrize("tol", ["1.0e-14", "1.0e-300"])
def test_a_tol_the_numerics_cannot_reach_is_refused_on_run_and_resume(tmp_path, no_kernel, tol):
    from frictiondisk.engine.directory import prepare_directory

    text = _tol_campaign(tol)
    floor = campaign_from_text(text, "<test>").numerics_choice.floor
    campaign = _write(tmp_path / "t.yaml", text)
    words = [f"find_jump.tol {float(tol):g}", f"the smallest tol they reach is {floor:.2g}"]
    refused(["run", campaign, "-o", tmp_path / "out"], *words, "--tol-floor")
    assert not (tmp_path / "out").exists()
    # a folder started before the refusal existed
    prepare_directory(tmp_path / "old", campaign_from_text(text, "<test>"))
    refused(["resume", tmp_path / "old"], *words, "--tol-floor -o NEW_DIR")
    assert not (tmp_path / "old" / "journal").exists()


# --- config messages ----------------------------------------------------------------------


def test_a_longer_or_american_name_gets_a_did_you_mean(tmp_path, no_kernel):
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN.replace("tol:", "tolerance:"))
    refused(
        ["run", campaign, "-o", tmp_path / "o"],
        "find_jump.tolerance: unknown key",
        "(did you mean 'tol'?)",
    )
    between = CAMPAIGN.replace("  tol:", "  between: [self_centering, slide_cycle]\n  tol:")
    campaign = _write(tmp_path / "b.yaml", between)
    refused(
        ["run", campaign, "-o", tmp_path / "o"],
        "find_jump.between[0]: 'self_centering' is not an outcome",
        "(did you mean 'self_centring'?)",
    )
    scene = _write(tmp_path / "s.yaml", "scene: pin\nnumerics: {mode: decid}\n")
    refused(
        ["simulate", scene], "numerics.mode: 'decid' is not allowed", "(did you mean 'decide'?)"
    )


def test_a_pins_unknown_key_lists_only_the_keys_a_pin_takes(tmp_path, no_kernel):
    scene = _write(tmp_path / "s.yaml", "scene: pin\nparams: {bogus: 1}\n")
    output = refused(["simulate", scene], "params.bogus: unknown key; allowed keys under params:")
    allowed = next(line for line in output.splitlines() if "params.bogus" in line)
    assert "x_ms" in allowed and not {"J_s", "beta_b", "phidot0"} & set(
        allowed.replace(",", " ").split()
    )
    disk = _write(tmp_path / "d.yaml", "scene: disk\nparams: {bogus: 1}\n")
    assert "phidot0" in refused(["simulate", disk], "params.bogus: unknown key")


@pytest.mark.parametrize("command", ["status", "resume"])
def test_a_path_that_does_not_exist_says_so(tmp_path, no_kernel, command):
    output = refused([command, tmp_path / "nowhere"], f"{tmp_path / 'nowhere'} does not exist")
    assert "not a campaign directory" not in output


# --- status -------------------------------------------------------------------------------


def test_status_answers_starting_while_a_run_holds_an_empty_dir(tmp_path):
    from frictiondisk.store.lock import CampaignLock

    with CampaignLock(tmp_path):
        code, output, _ = cli("status", tmp_path)
    assert code == 0, output
    assert f"starting (pid {os.getpid()})" in output
    code, output, _ = cli("status", tmp_path)  # released: nothing there
    assert code == 2 and "not a campaign directory" in output


def test_status_counts_only_journal_entries_and_reads_the_campaign_without_its_records(
    campaign_dir, finished
):
    entries = len(_entries(finished))
    for stray in (
        "journal/ab/notakey.json",
        "journal/zz.json",
        "journal/ab/" + "cd" * 32 + ".json",
    ):
        (campaign_dir / stray).parent.mkdir(parents=True, exist_ok=True)
        (campaign_dir / stray).write_text("{}")
    (campaign_dir / "status.json").unlink()
    (campaign_dir / "campaign.record.json").unlink()
    code, output, _ = cli("status", campaign_dir)
    assert code == 0, output
    assert "campaign:  tiny in" in output and "state:     complete" in output
    assert "points:    2 of 2 done" in output
    assert f"runs:      {entries} done; 0 tasks in flight" in output


def test_status_says_1_task(campaign_dir):
    from frictiondisk.store.lock import CampaignLock

    info = json.loads((campaign_dir / "status.json").read_text())
    info.update(state="running", jobs_in_flight=1)
    (campaign_dir / "status.json").write_text(json.dumps(info))
    with CampaignLock(campaign_dir):
        code, output, _ = cli("status", campaign_dir)
    assert code == 0 and "running (pid" in output and "1 task in flight" in output, output


# --- Ctrl-C from the first moment ----------------------------------------------------------


def test_the_notice_before_the_imports_is_the_one_after_them():
    from frictiondisk.cli.entry import EARLY_NOTICE
    from frictiondisk.engine.signals import stop_notice

    assert stop_notice(KeyboardInterrupt()) == EARLY_NOTICE


def test_ctrl_c_during_the_imports_exits_130_with_the_notice(tmp_path):
    """The first second of `run` imports the commands: a Ctrl-C there said "Aborted!" and
    exited 1 (click), or left a traceback."""
    campaign = _write(tmp_path / "c.yaml", CAMPAIGN)
    process = subprocess.Popen(
        [sys.executable, "-m", "frictiondisk.cli", "run", str(campaign), "-o", str(tmp_path / "o")],
        env={**os.environ, "PYTHONPATH": str(REPO)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    wait_for_cpu(process.pid, 0.15)  # past the interpreter's start, in our imports
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=HANG_S)
    assert process.returncode == 130, err
    assert "error: interrupted; no finished run is lost" in err
    assert "Aborted!" not in err and "Traceback" not in err


def test_a_stop_a_library_turned_into_its_own_error_still_exits_130(capsys):
    """numba's C extensions turn a KeyboardInterrupt during their import into an
    ImportError: the stop the signal handler noted still decides the exit."""
    import click

    from frictiondisk.cli import run_and_exit as entry_point
    from frictiondisk.engine.signals import clear_stop_requests, request_stop

    @click.command()
    def interrupted_import():
        request_stop(KeyboardInterrupt)
        raise ImportError("numba._devicearray failed to import")

    @click.command()
    def plain_failure():
        raise ImportError("a real one")

    previous = signal.getsignal(signal.SIGINT)
    try:
        assert entry_point._run(lambda: interrupted_import, []) == 130
        assert "error: interrupted; no finished run is lost" in capsys.readouterr().err
        clear_stop_requests()
        with pytest.raises(ImportError, match="a real one"):
            entry_point._run(lambda: plain_failure, [])
    finally:
        clear_stop_requests()
        signal.signal(signal.SIGINT, previous)


def test_a_stop_a_library_swallowed_still_exits_130(capsys):
    """A Ctrl-C that lands in a library's teardown and is swallowed there (the command then
    returns normally) still ends in the stop's notice and exit code 130."""
    import click

    from frictiondisk.cli import run_and_exit as entry_point
    from frictiondisk.engine.signals import clear_stop_requests, request_stop

    @click.command()
    def swallowed():
        request_stop(KeyboardInterrupt)  # noted by the handler, the exception lost

    @click.command()
    def finished():
        pass

    previous = signal.getsignal(signal.SIGINT)
    try:
        assert entry_point._run(lambda: swallowed, []) == 130
        assert "error: interrupted; no finished run is lost" in capsys.readouterr().err
        clear_stop_requests()
        assert entry_point._run(lambda: finished, []) == 0
    finally:
        clear_stop_requests()
        signal.signal(signal.SIGINT, previous)


def test_a_stop_during_the_teardown_is_noted_not_raised():
    """While Dask's client and cluster close, Ctrl-C is noted, not raised (an exception
    inside their close can leave it hung); the handler before it is restored after."""
    import os

    from frictiondisk.engine.signals import clear_stop_requests, noted_stop, stops_noted_only

    def raising(signum, frame):
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, raising)
    try:
        clear_stop_requests()
        with stops_noted_only():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)  # the handler runs here, in the main thread
        assert noted_stop() is KeyboardInterrupt
        assert signal.getsignal(signal.SIGINT) is raising
    finally:
        clear_stop_requests()
        signal.signal(signal.SIGINT, previous)
