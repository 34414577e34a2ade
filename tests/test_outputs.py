"""Outputs and the dashboard process (issue 21): what the package writes, where it refuses to write, and
that ``pounding dashboard`` leaves nothing behind.

Every test here failed before: ``report -o`` renamed its temporary file over anything (as root, a device
node became a regular file), read-only and full-disk errors were tracebacks, a killed write's temporary file
stayed for ever, reports had mode 0600, SIGTERM left the dashboard's server running and ``--port 70000``
exited 0. The device refused is a node made here (``mknod``, as /dev/null: 1, 3), not /dev/null itself, so
that a regression cannot destroy the system's /dev/null.
"""

from __future__ import annotations

import errno
import os
import signal
import socket
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from pounding.cli.commands import main
from pounding.output import remove_stale

ROOT = Path(__file__).resolve().parent.parent
PRESET = "section5-T2-0.4"
SWEEP = ("sweep", PRESET, "--vary", "contact.gap=0.5,1", "--records", "2", "--scheduler", "serial", "--no-chart")


def _one_line(text: str) -> str:
    lines = text.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in text, text
    assert len(lines[0]) <= 260, lines[0]  # 200 characters of message after "pounding report: error: " and the path
    return lines[0]


def _pounding(*args, stdout=subprocess.PIPE) -> subprocess.CompletedProcess:
    """``pounding`` in a subprocess, as a user runs it (a traceback would show on its stderr)."""
    return subprocess.run([sys.executable, "-m", "pounding", *args], stdout=stdout, stderr=subprocess.PIPE, text=True,
                          timeout=120, cwd=ROOT)


def _dead_pid() -> int:
    """The pid of a process that has ended (a killed writer's)."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


@pytest.fixture
def device(tmp_path) -> Path:
    """A character device like /dev/null, in ``tmp_path``."""
    node = tmp_path / "null"
    try:
        os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except (PermissionError, AttributeError):
        pytest.skip("needs mknod (root): a device node to refuse")
    return node


def test_report_refuses_a_device_and_leaves_it_a_device(device, capsys):
    assert main(["report", PRESET, "-o", str(device)]) == 2
    assert "--output" in _one_line(capsys.readouterr().err)
    assert stat.S_ISCHR(os.lstat(device).st_mode) and os.stat(device).st_rdev == os.makedev(1, 3)
    link = device.parent / "link.html"  # a symlink to the device: the same
    link.symlink_to(device)
    assert main(["report", PRESET, "-o", str(link)]) == 2
    assert "--output" in _one_line(capsys.readouterr().err)
    assert link.is_symlink() and stat.S_ISCHR(os.lstat(device).st_mode)


def test_report_to_dev_stdout_into_a_pipe_names_the_pipe():
    """Issue 33: /dev/stdout into a pipe resolves to no path (pipe:[...]); it failed with exit 1, "No such file or
    directory". It is a pipe, not a file: exit 2 naming --output and what it is; into a file, the file is written."""
    run = subprocess.run([sys.executable, "-m", "pounding", "report", PRESET, "-o", "/dev/stdout"], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 2 and run.stdout == ""
    assert "--output" in _one_line(run.stderr) and "is a pipe, not a regular file" in run.stderr


@pytest.mark.parametrize("kind", ["folder", "symlink to a folder", "empty"])
def test_report_refuses_a_folder_or_an_empty_name(tmp_path, capsys, kind):
    folder = tmp_path / "folder"
    folder.mkdir()
    target = {"folder": str(folder), "empty": ""}.get(kind)
    if target is None:
        (tmp_path / "link").symlink_to(folder)
        target = str(tmp_path / "link")
    assert main(["report", PRESET, "-o", target]) == 2
    assert "--output" in _one_line(capsys.readouterr().err)
    assert folder.is_dir() and list(folder.iterdir()) == []
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".tmp")] == []


def test_sweep_refuses_a_bad_folder_and_a_bad_table_target(tmp_path, device, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # -o "" once wrote here
    (tmp_path / "file").write_text("x")
    for target in (str(device), "", str(tmp_path / "file" / "below")):
        assert main([*SWEEP, "-o", target]) == 2
        assert "--output" in _one_line(capsys.readouterr().err)
    out = tmp_path / "out"
    (out / "sweep.csv").mkdir(parents=True)  # the table's name taken by a folder: refused before any work
    assert main([*SWEEP, "-o", str(out)]) == 2
    assert "--output" in _one_line(capsys.readouterr().err) and not (out / "points").exists()
    assert stat.S_ISCHR(os.lstat(device).st_mode)


@pytest.mark.parametrize("command", ["report", "sweep"])
def test_a_folder_that_cannot_be_written_ends_in_one_line(command):
    # Root ignores permission bits: /proc takes no new file whoever asks.
    args = ("report", PRESET, "-o", "/proc/pounding-report.html") if command == "report" else (*SWEEP, "-o", "/proc/pounding-sweep")
    result = _pounding(*args)
    assert result.returncode not in (0, 2) and "/proc/pounding-" in _one_line(result.stderr)


@pytest.mark.slow
def test_a_full_standard_output_ends_in_one_line():
    with open("/dev/full", "w") as full:
        result = _pounding("estimate", PRESET, "--json", stdout=full)
    assert result.returncode == 1
    assert "No space left on device" in _one_line(result.stderr)


@pytest.mark.slow
def test_an_error_in_the_middle_of_a_write_leaves_no_temporary_file(tmp_path, monkeypatch, capsys):
    target = tmp_path / "report.html"
    for error, expected in ((OSError(errno.ENOSPC, "No space left on device"), 1), (KeyboardInterrupt(), 130)):

        def fails(descriptor, error=error):
            assert [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]  # in the middle: the temporary file is there
            raise error

        monkeypatch.setattr(os, "fsync", fails)
        assert main(["report", PRESET, "-o", str(target)]) == expected
        line = _one_line(capsys.readouterr().err)
        assert list(tmp_path.iterdir()) == []
        if expected == 1:  # the target named, not the temporary file
            assert str(target) in line and "No space left on device" in line and ".tmp" not in line


def test_a_stale_temporary_file_of_a_killed_run_is_removed(tmp_path, capsys):
    target = tmp_path / "report.html"
    dead, alive = _dead_pid(), os.getpid()
    stale = tmp_path / f".report.html.{dead}.abcd_123.tmp"
    legacy = tmp_path / ".report.html.k2j4h5g6.tmp"  # named as mkstemp did before pids were named, an hour old
    running = tmp_path / f".report.html.{alive}.zzzzzzzz.tmp"  # a write in progress: kept
    other = tmp_path / f".other.html.{dead}.abcdefgh.tmp"  # another target's: left to that target's writes
    for path in (stale, legacy, running, other):
        path.write_text("partial")
    os.utime(legacy, (time.time() - 3600,) * 2)
    assert main(["report", PRESET, "-o", str(target)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, running.name, other.name])
    assert remove_stale(tmp_path) == 1 and not other.exists() and running.exists()


def test_a_sweep_removes_the_temporary_files_of_a_killed_sweep(tmp_path):
    out = tmp_path / "out"
    assert main([*SWEEP, "-o", str(out)]) == 0
    point = next((out / "points").iterdir())
    dead = _dead_pid()
    stale = [out / f".sweep.json.{dead}.abcdefgh.tmp", point / f".chunk-000000000-9.json.{dead}.abcdefgh.tmp"]
    for path in stale:
        path.write_text("{")
    assert main([*SWEEP, "-o", str(out)]) == 0  # everything found done: only sweep.json and the table rewritten
    assert not any(path.exists() for path in stale)


def test_files_get_the_usual_mode(tmp_path, capsys):
    previous = os.umask(0o022)
    try:
        assert main(["report", PRESET, "-o", str(tmp_path / "report.html")]) == 0
        os.umask(0o027)
        assert main([*SWEEP, "-o", str(tmp_path / "out")]) == 0
    finally:
        os.umask(previous)
    assert stat.S_IMODE(os.stat(tmp_path / "report.html").st_mode) == 0o644
    for path in (tmp_path / "out" / "sweep.csv", tmp_path / "out" / "sweep.json"):
        assert stat.S_IMODE(os.stat(path).st_mode) == 0o640


def test_dashboard_refuses_a_bad_port(capsys):
    for port in ("70000", "65536", "-1", "http"):
        with pytest.raises(SystemExit) as stop:
            main(["dashboard", "--port", port])
        assert stop.value.code == 2
        assert "--port" in _one_line(capsys.readouterr().err)


def _group(pgid: int) -> list[int]:
    """The processes of process group ``pgid`` still alive (zombies are gone already)."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[2]) == pgid and fields[0] != "Z":
                found.append(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _children(pid: int) -> list[int]:
    try:
        import psutil

        return [child.pid for child in psutil.Process(pid).children(recursive=True)]
    except ImportError:
        return [p for p in _group(pid) if p != pid]


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")
@pytest.mark.parametrize("ending", [signal.SIGTERM, signal.SIGKILL], ids=["SIGTERM", "SIGKILL"])
def test_an_ended_dashboard_leaves_no_process_and_frees_the_port(ending):
    """Its server runs in several processes (one per core): however ``pounding dashboard`` ends, none is left serving."""
    process = subprocess.Popen([sys.executable, "-m", "pounding", "dashboard", "--port", "0"], cwd=ROOT,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True)
    children: list[int] = []
    try:
        port = None
        deadline = time.monotonic() + 60
        while port is None and time.monotonic() < deadline:  # "Bokeh app running at: http://localhost:PORT/app"
            line = process.stderr.readline()
            assert line or process.poll() is None, "the dashboard ended before serving"
            if "running at" in line:
                port = int(line.rsplit(":", 1)[1].split("/")[0])
        assert port is not None
        time.sleep(1)  # the server's forked processes start beside the first
        children = _children(process.pid)
        assert children, "the server runs as child processes"
        with socket.create_connection(("127.0.0.1", port), timeout=5):
            pass
        process.send_signal(ending)
        process.wait(timeout=10)
        deadline = time.monotonic() + 10
        while (_group(process.pid) or any(_alive(pid) for pid in children)) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert _group(process.pid) == [] and not any(_alive(pid) for pid in children)
        with pytest.raises(OSError):
            socket.create_connection(("127.0.0.1", port), timeout=2).close()
    finally:
        for pid in _group(process.pid) + [pid for pid in children if _alive(pid)]:  # what a failure left: this test's own
            os.kill(pid, signal.SIGKILL)
        if process.poll() is None:
            process.kill()
        process.wait()
        process.stderr.close()
