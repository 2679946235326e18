"""The warm server (`frictiondisk serve`, cli/warm_server.py): a `run` handed to it gives
the same files as one run on its own, with the same exit codes, output and signals; a
client of another environment never reaches it; it stops when idle or asked."""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
from conftest import LONG_CAMPAIGN, start_campaign_until

from frictiondisk.cli.warm_control import answers
from frictiondisk.cli.warm_protocol import (
    NO_SERVER_ENV,
    SERVER_DIR_ENV,
    UnsafeServerDir,
    environment_key,
    private_dir,
    receive_message,
    send_message,
)

ROOT = Path(__file__).resolve().parents[1]
SHORT = """\
name: warm
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-3
  along: {params.x_ms: [0.08, 0.12]}
"""


def _cli(*args, env, cwd=ROOT, wrapper=()) -> subprocess.CompletedProcess:
    """`frictiondisk *args` in a process of its own (behind `wrapper`, e.g. nice)."""
    return subprocess.run(
        [*wrapper, sys.executable, "-m", "frictiondisk.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=600,
    )


def _served(log: Path) -> list[str]:
    """The commands the server's log says it ran."""
    lines = log.read_text().splitlines() if log.exists() else []
    started = [line for line in lines if re.search(r": pid \d+: ", line)]
    return [
        line.split(": ", 2)[2] for line in started if not re.search(r": exit -?\d+ after ", line)
    ]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """(environment with the server's directory, its log): a detached server, stopped
    after the module."""
    directory = tmp_path_factory.mktemp("servers")
    os.chmod(directory, 0o700)
    env = _server_env(directory)
    pid, log = _detached(_cli("serve", "--detach", "--idle-timeout", "300", env=env))
    yield env, log
    stopped = _cli("serve", "--stop", env=env)
    assert stopped.returncode == 0, stopped.stderr
    _wait_gone(pid)


def _server_env(directory: Path) -> dict:
    """This environment, with its servers' sockets in `directory` and none bypassed."""
    env = {**os.environ, SERVER_DIR_ENV: str(directory)}
    env.pop(NO_SERVER_ENV, None)
    return env


def _detached(done: subprocess.CompletedProcess) -> tuple[int, Path]:
    """(pid, log) that a successful `serve --detach` printed."""
    assert done.returncode == 0, done.stderr
    pid = int(done.stdout.split("(pid ")[1].split(")")[0])
    return pid, Path(done.stdout.strip().split("log: ")[1])


def _wait_gone(pid: int, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        time.sleep(0.05)
    raise AssertionError(f"process {pid} still runs after {timeout} s")


def _open(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def test_a_served_run_writes_what_a_run_on_its_own_writes(server, tmp_path):
    env, log = server
    spec = tmp_path / "c.yaml"
    spec.write_text(SHORT)
    served = _cli("run", str(spec), "-o", str(tmp_path / "served"), env=env)
    alone = _cli("run", str(spec), "-o", str(tmp_path / "alone"), env={**env, NO_SERVER_ENV: "1"})
    assert served.returncode == alone.returncode == 0, served.stderr + alone.stderr
    commands = _served(log)
    assert f"run {spec} -o {tmp_path / 'served'}" in commands
    assert not any("alone" in command for command in commands)
    # the summary reaches the client's own stdout through the descriptors it passed
    assert "done: 2 points (0 failed)" in served.stdout
    for name in ("results.nc", "runs.nc"):
        a, b = _open(tmp_path / "served" / name), _open(tmp_path / "alone" / name)
        drop = [v for v in a.variables if v == "wall_s"]  # measured, never equal
        xr.testing.assert_identical(a.drop_vars(drop), b.drop_vars(drop))


def test_exit_codes_and_errors_arrive_from_the_server(server, tmp_path):
    env, log = server
    missing = _cli("run", str(tmp_path / "missing.yaml"), "-o", str(tmp_path / "o"), env=env)
    assert missing.returncode == 2
    assert "missing.yaml" in missing.stderr
    assert any("missing.yaml" in command for command in _served(log))
    # relative paths are the client's: it runs in the client's directory
    (tmp_path / "c.yaml").write_text(SHORT)
    relative = _cli("run", "c.yaml", "-o", "out", env=env, cwd=tmp_path)
    assert relative.returncode == 0, relative.stderr
    assert (tmp_path / "out" / "results.nc").exists()


@pytest.mark.parametrize(
    ("sig", "code", "word"),
    [
        (signal.SIGTERM, 143, "terminated"),
        (signal.SIGINT, 130, "interrupted"),
        (signal.SIGHUP, 129, "hung up"),
    ],
)
def test_a_signal_to_the_client_stops_the_served_campaign_gracefully(
    server, tmp_path, sig, code, word
):
    env, _ = server
    spec = tmp_path / "long.yaml"
    spec.write_text(LONG_CAMPAIGN)
    out = tmp_path / "stopped"
    proc = start_campaign_until(spec, out, env=env, cwd=ROOT)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == code, err
    assert word in err and "frictiondisk resume" in err
    with xr.open_dataset(out / "results.nc") as part:
        assert part.attrs["partial"] == 1
        assert part.attrs["points_done"] >= 2


def test_a_client_that_dies_stops_its_campaign_gracefully(server, tmp_path):
    env, log = server
    spec = tmp_path / "long.yaml"
    spec.write_text(LONG_CAMPAIGN)
    out = tmp_path / "orphan"
    proc = start_campaign_until(spec, out, env=env, cwd=ROOT)
    proc.kill()  # SIGKILL: the client cannot forward anything
    proc.communicate(timeout=60)
    t0 = time.time()
    while time.time() - t0 < 60:
        status = json.loads((out / "status.json").read_text())
        if status["state"] != "running":
            break
        time.sleep(0.05)
    assert status["state"] == "interrupted"
    with xr.open_dataset(out / "results.nc") as part:
        assert part.attrs["partial"] == 1
    assert "its client went away; sending SIGTERM" in log.read_text()


def test_another_environment_never_reaches_the_server(server, tmp_path):
    env, log = server
    spec = tmp_path / "c.yaml"
    spec.write_text(SHORT)
    other = {**env, "NUMBA_OPT": "2"}  # numba reads it at import: not what the server has
    done = _cli("run", str(spec), "-o", str(tmp_path / "other"), env=other)
    assert done.returncode == 0, done.stderr
    assert not any("other" in command for command in _served(log))
    _assert_still_serving(env, log, tmp_path)


def test_the_key_follows_variables_read_at_import_and_nothing_else(monkeypatch):
    base = environment_key()
    monkeypatch.setenv("FRICTIONDISK_UNRELATED_TO_IMPORTS", "1")
    with_frictiondisk = environment_key()
    monkeypatch.setenv("SOME_UNRELATED_VARIABLE", "1")
    assert environment_key() == with_frictiondisk != base
    monkeypatch.setenv("DASK_DISTRIBUTED__WORKER__DAEMON", "False")
    assert environment_key() != with_frictiondisk
    monkeypatch.setenv(NO_SERVER_ENV, "1")  # says whether to use one, not which
    monkeypatch.setenv(SERVER_DIR_ENV, "/elsewhere")
    assert environment_key() == environment_key()


def test_a_socket_directory_others_may_enter_is_refused(tmp_path, monkeypatch):
    shared = tmp_path / "shared"
    shared.mkdir(mode=0o755)
    os.chmod(shared, 0o755)
    monkeypatch.setenv(SERVER_DIR_ENV, str(shared))
    with pytest.raises(UnsafeServerDir, match="0755"):
        private_dir(create=False)
    link = tmp_path / "link"
    link.symlink_to(shared)
    monkeypatch.setenv(SERVER_DIR_ENV, str(link))
    with pytest.raises(UnsafeServerDir, match="symbolic link"):
        private_dir(create=False)
    done = _cli("serve", env={**os.environ, SERVER_DIR_ENV: str(shared)})
    assert done.returncode == 2
    assert str(shared) in done.stderr and "chmod 700" in done.stderr


def test_an_idle_server_stops_and_removes_its_socket(tmp_path):
    directory = tmp_path / "idle"
    env = _server_env(directory)
    pid, _ = _detached(_cli("serve", "--detach", "--idle-timeout", "1", env=env))
    assert stat.S_IMODE(os.stat(directory).st_mode) == 0o700
    _wait_gone(pid, timeout=30)
    assert not list(directory.glob("*.sock"))
    assert "idle for 1 s; stopping" in next(directory.glob("*.log")).read_text()
    nothing = _cli("serve", "--stop", env=env)
    assert nothing.returncode == 0
    assert "no server serves this environment" in nothing.stdout


# ---- clients that misbehave: found by review, each failed before its fix -------------


def _server_pid(log: Path) -> int:
    return int(answers(log.with_suffix(".sock"))["pong"])


def _open_fds(pid: int) -> int:
    return len(os.listdir(f"/proc/{pid}/fd"))


def _raw_client(log: Path) -> socket.socket:
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    conn.settimeout(60)
    conn.connect(str(log.with_suffix(".sock")))
    return conn


def _request(args: list[str], env: dict) -> dict:
    return {"argv": args, "cwd": str(ROOT), "env": env, "umask": 0o022, "ignored_signals": []}


def _devnull_fds() -> list[int]:
    return [os.open(os.devnull, os.O_RDWR) for _ in range(3)]


@pytest.mark.skipif(not Path("/proc/self/fd").exists(), reason="counts /proc/PID/fd")
def test_bad_requests_leave_no_descriptor_behind(server):
    env, log = server
    pid = _server_pid(log)
    t0 = time.monotonic()  # commands of earlier tests hold a connection each
    while answers(log.with_suffix(".sock"))["running"] and time.monotonic() - t0 < 60:
        time.sleep(0.05)
    before = _open_fds(pid)
    for payload in (b"\x00\x00\x00\x04[1] ", b"\x00\x00\x00\x05{bad}", b"\xff\xff\xff\xff"):
        fds = _devnull_fds()
        with _raw_client(log) as conn:
            socket.send_fds(conn, [payload], fds)
            conn.recv(1)  # the server closes a bad request at once
        for fd in fds:
            os.close(fd)
    _server_pid(log)  # answered after all of them
    t0 = time.monotonic()  # it closes the ping's connection just after its answer
    while _open_fds(pid) != before and time.monotonic() - t0 < 5:
        time.sleep(0.05)
    assert _open_fds(pid) == before


def test_a_silent_client_delays_nobody(server, tmp_path):
    """A client that sends its request a byte a second (or never) holds up no other."""
    import threading

    env, log = server
    spec = tmp_path / "c.yaml"
    spec.write_text(SHORT)
    stop = threading.Event()

    def dribble(conn: socket.socket) -> None:
        conn.send((1000).to_bytes(4, "big"))  # a request of 1000 bytes, sent over 30 s
        for _ in range(30):
            if stop.wait(1.0):
                return
            conn.send(b" ")

    with _raw_client(log) as slow:
        dribbler = threading.Thread(target=dribble, args=(slow,), daemon=True)
        dribbler.start()
        done = _cli("run", str(spec), "-o", str(tmp_path / "o"), env=env)
        still_dribbling = dribbler.is_alive()
        stop.set()
        dribbler.join()
    assert done.returncode == 0, done.stderr
    assert f"run {spec} -o {tmp_path / 'o'}" in _served(log)
    assert still_dribbling  # it was served while the slow one was still sending


def test_a_client_gone_before_its_answer_does_not_stop_the_server(server, tmp_path):
    env, log = server
    spec = tmp_path / "c.yaml"
    spec.write_text(SHORT)
    fds = _devnull_fds()
    with _raw_client(log) as conn:
        send_message(conn, _request(["run", str(spec), "-o", str(tmp_path / "gone")], env), fds)
    for fd in fds:
        os.close(fd)
    done = _cli("run", str(spec), "-o", str(tmp_path / "next"), env=env)
    assert done.returncode == 0, done.stderr
    assert f"run {spec} -o {tmp_path / 'next'}" in _served(log)
    assert "Traceback" not in log.read_text()


def test_a_sigterm_at_once_after_the_pid_is_not_lost(server, tmp_path):
    """The command's pid reaches the client before the forked copy has the client's
    signal handlers: a signal in between must wait for them, not meet the server's."""
    env, log = server
    spec = tmp_path / "long.yaml"
    spec.write_text(LONG_CAMPAIGN)
    fds = _devnull_fds()
    with _raw_client(log) as conn:
        send_message(conn, _request(["run", str(spec), "-o", str(tmp_path / "o")], env), fds)
        reply, _ = receive_message(conn)
        os.kill(reply["pid"], signal.SIGTERM)
        for fd in fds:
            os.close(fd)
        ended, _ = receive_message(conn)
    # stopped by it: gracefully (143) once the campaign's handlers are in, else killed by
    # it (-15) as a process of its own would be during its start-up; never run to the end
    assert ended["exit"] in (143, -signal.SIGTERM)


def _served_long_campaign(server, tmp_path: Path, name: str):
    """A long campaign handed to the server, past its second point: (its client, the
    command's pid, its folder)."""
    env, log = server
    spec = tmp_path / "long.yaml"
    spec.write_text(LONG_CAMPAIGN)
    out = tmp_path / name
    proc = start_campaign_until(spec, out, env=env, cwd=ROOT)
    child = int(re.findall(rf"pid (\d+): run {re.escape(str(spec))}", log.read_text())[-1])
    return proc, child, out


def _suspend(proc: subprocess.Popen, child: int) -> None:
    """Ctrl-Z to the client; returns once it has stopped the command, then itself."""
    proc.send_signal(signal.SIGTSTP)
    t0 = time.monotonic()
    while time.monotonic() - t0 < 30 and (_state(child), _state(proc.pid)) != ("T", "T"):
        time.sleep(0.02)
    assert _state(child) == "T"  # stopped with its client


def test_ctrl_z_suspends_the_served_campaign_too(server, tmp_path):
    proc, child, out = _served_long_campaign(server, tmp_path, "suspended")
    _suspend(proc, child)
    proc.send_signal(signal.SIGCONT)  # as `fg` does once the shell saw the client stop
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    with xr.open_dataset(out / "results.nc") as ds:
        assert "partial" not in ds.attrs


def _state(pid: int) -> str:
    """The state letter of /proc/PID/stat (T: stopped), '' once the process is gone."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return ""


def test_a_client_with_other_process_limits_is_not_served(server, tmp_path):
    """A forked copy would keep the server's nice, affinity, limits and cgroup."""
    env, log = server
    spec = tmp_path / "c.yaml"
    spec.write_text(SHORT)
    nice = ("nice", "-n", "3")
    done = _cli("run", str(spec), "-o", str(tmp_path / "nice"), env=env, wrapper=nice)
    assert done.returncode == 0, done.stderr
    assert not any("nice" in command for command in _served(log))
    _assert_still_serving(env, log, tmp_path)


def _assert_still_serving(env: dict, log: Path, tmp_path: Path) -> None:
    """The control of a 'not served' check: the server does serve this environment."""
    spec = tmp_path / "control.yaml"
    spec.write_text(SHORT)
    done = _cli("run", str(spec), "-o", str(tmp_path / "control"), env=env)
    assert done.returncode == 0, done.stderr
    assert f"run {spec} -o {tmp_path / 'control'}" in _served(log)


def test_a_request_nested_too_deeply_is_refused_not_fatal(server):
    env, log = server
    deep = b"[" * 200_000
    fds = _devnull_fds()
    with _raw_client(log) as conn:
        socket.send_fds(conn, [len(deep).to_bytes(4, "big")], fds)
        conn.sendall(deep)
        assert conn.recv(1) == b""  # dropped
    for fd in fds:
        os.close(fd)
    assert answers(log.with_suffix(".sock")) is not None  # and still serving


def test_a_command_gets_none_of_another_clients_descriptors(server, tmp_path):
    env, log = server
    read_end, write_end = os.pipe()
    with _raw_client(log) as pending:  # a request still arriving, with its descriptors
        socket.send_fds(pending, [b"\x00\x00"], [write_end] * 3)
        proc, child, _ = _served_long_campaign(server, tmp_path, "o")
        links = {os.readlink(f"/proc/{child}/fd/{fd}") for fd in os.listdir(f"/proc/{child}/fd")}
        assert f"pipe:[{os.fstat(write_end).st_ino}]" not in links
        assert os.getsid(child) == child  # a session of its own, not the server's
        proc.terminate()
        proc.communicate(timeout=120)
    os.close(read_end)
    os.close(write_end)


def test_a_suspended_command_whose_client_dies_still_stops(server, tmp_path):
    proc, child, out = _served_long_campaign(server, tmp_path, "suspended")
    _suspend(proc, child)
    proc.kill()
    proc.communicate(timeout=60)
    _wait_gone(child)  # stopped forever before the fix, holding the campaign's lock
    assert json.loads((out / "status.json").read_text())["state"] == "interrupted"


def test_a_failed_fork_leaves_the_signal_mask_as_it_was(monkeypatch):
    from frictiondisk.cli import warm_child

    def no_fork():
        raise BlockingIOError(11, "Resource temporarily unavailable")

    monkeypatch.setattr(warm_child.os, "fork", no_fork)
    before = signal.pthread_sigmask(signal.SIG_BLOCK, [])
    with pytest.raises(OSError):
        warm_child.fork_command({}, [], [], [], None)
    assert signal.pthread_sigmask(signal.SIG_BLOCK, []) == before


def test_writing_into_a_folder_on_the_path_keeps_the_key(monkeypatch, tmp_path):
    """PYTHONPATH=. and a campaign written below it: the server must stay reachable."""
    import site

    monkeypatch.setattr(sys, "path", [*sys.path, str(tmp_path)])
    before = environment_key()
    (tmp_path / "out").mkdir()
    assert environment_key() == before
    monkeypatch.setattr(site, "getsitepackages", lambda: [str(tmp_path)])
    installed = environment_key()
    (tmp_path / "new_package").mkdir()  # an install into site-packages
    assert environment_key() != installed


def test_a_stopping_server_starts_nothing_new_and_lets_a_new_one_start(tmp_path):
    env = _server_env(tmp_path / "servers")
    first_pid, log = _detached(_cli("serve", "--detach", "--idle-timeout", "300", env=env))
    spec = tmp_path / "long.yaml"
    spec.write_text(LONG_CAMPAIGN.replace("num: 48", "num: 400"))  # outlives the steps below
    proc = start_campaign_until(spec, tmp_path / "long", env=env, cwd=ROOT)
    try:
        stopping = _cli("serve", "--stop", env=env)
        assert "once its 1 running command(s) end" in stopping.stdout
        (tmp_path / "c.yaml").write_text(SHORT)
        alone = _cli("run", str(tmp_path / "c.yaml"), "-o", str(tmp_path / "o"), env=env)
        assert alone.returncode == 0, alone.stderr  # ran by itself
        assert not any(str(tmp_path / "o") in command for command in _served(log))
        second_pid, _ = _detached(_cli("serve", "--detach", "--idle-timeout", "300", env=env))
        assert proc.poll() is None  # the old server's command still runs
        assert second_pid != first_pid
    finally:
        proc.terminate()
        proc.communicate(timeout=120)
        _cli("serve", "--stop", env=env)
    _wait_gone(first_pid)


def test_detach_starts_the_package_it_runs_not_one_in_the_working_directory(tmp_path):
    shadow = tmp_path / "shadow"
    (shadow / "frictiondisk").mkdir(parents=True)
    (shadow / "frictiondisk" / "__init__.py").write_text("raise ImportError('a shadow')\n")
    env = _server_env(tmp_path / "servers")
    script = Path(sys.executable).parent / "frictiondisk"  # finds the installed package
    started = subprocess.run(
        [str(script), "serve", "--detach", "--idle-timeout", "60"],
        capture_output=True,
        text=True,
        cwd=shadow,
        env=env,
        timeout=600,
    )
    pid, _ = _detached(started)
    subprocess.run([str(script), "serve", "--stop"], cwd=shadow, env=env, timeout=60)
    _wait_gone(pid)
