"""Parametric sweeps on Dask: exact agreement with serial runs and with
``simulate``, independence from chunking, resuming after an interruption or
a killed client, bad --vary specs."""

import argparse
import contextlib
import importlib
import json
import math
import signal
import subprocess
import sys
import textwrap
import time
import tomllib
from fractions import Fraction
from pathlib import Path

import pandas as pd
import pytest

from pounding import ArgumentError, CaseError, InputError
from pounding.case.case import case_from_dict
from pounding.cli.parser import error_line
from pounding.cli.sweep import add_arguments, run
from pounding.closed_form.estimator import estimate
from pounding.presets import preset_text
from pounding.simulation.monte_carlo import Settings, simulate
from pounding.studies.sweeps import SweepInterrupted, parse_values, parse_vary, sweep

ROOT = Path(__file__).resolve().parents[1]
VARY = {"contact.gap": "0.5:1.5:3", "buildings.2.storeys.1.period": [0.4, 0.6]}  # 6 points, kgf-cm-s
RECORDS, SEED = 6, 3


def short_case() -> dict:
    """Section 5's case file with 5 s records (long enough for the closed form)."""
    data = tomllib.loads(preset_text("section5-T2-0.4"))
    data["excitation"]["duration"] = 5.0
    return data


def chunk_files(folder: Path) -> list[Path]:
    return sorted(folder.glob("points/*/chunk-*.json"))


def run_sweep(folder: Path, **options) -> pd.DataFrame:
    arguments = dict(records=RECORDS, seed=SEED, output_dir=folder, scheduler="serial", chunk_records=2, chart=False)
    return sweep(short_case(), VARY, **(arguments | options))


@pytest.fixture(scope="module")
def serial_table(tmp_path_factory) -> pd.DataFrame:
    return run_sweep(tmp_path_factory.mktemp("serial"))


# --- --vary specs ---------------------------------------------------------------------------------


def test_values_of_a_range_and_of_a_list():
    assert parse_values("0:0.05:11") == tuple(round(0.005 * i, 12) for i in range(11))
    assert parse_values("0:0.05:11")[3] == 0.015
    assert parse_values("0.4,0.6,0.8") == (0.4, 0.6, 0.8)
    assert parse_values("2") == (2.0,)
    assert parse_vary("buildings.2.storeys.1.period=0.4,0.6") == ("buildings.2.storeys.1.period", (0.4, 0.6))


@pytest.mark.parametrize(
    "spec, message",
    [
        ("contact.gap", "expected PATH=VALUES"),
        ("=1,2", "no key path"),
        ("contact..gap=1", "empty part"),
        ("contact.gap=", "no values"),
        ("contact.gap=0:1", "three parts"),
        ("contact.gap=0:1:x", "count must be a whole number"),
        ("contact.gap=0:1:0", "count must be a whole number >= 1"),
        ("contact.gap=a,b", "'a' is not a number"),
        ("contact.gap=1,,2", "empty value"),
        ("contact.gap=1,nan", "not a finite number"),
        ("contact.gap=1,1", "appears twice"),
    ],
)
def test_bad_specs_name_the_problem(spec, message):
    with pytest.raises(ArgumentError, match=message) as error:
        parse_vary(spec)
    assert error.value.field == "vary"


@pytest.mark.parametrize(
    "vary, field, message",
    [
        ({"buildings.3.storeys.1.period": [0.4]}, "vary", "buildings has 2 entries, counted from 1; got '3'"),
        ({"buildings.0.damping_ratio": [0.05]}, "vary", "counted from 1"),
        ({"contact.model": [1.0]}, "vary", "not a number"),
        ({"contact.gap.x": [1.0]}, "vary", "is a value, not a table"),
        ({"exitation.G0": [1.0]}, "vary", "has no 'exitation'"),
        ({"contact.gapp": [1.0]}, "contact.gapp", "unknown key"),
        ({"contact.gap": [1.0, -1.0]}, "contact.gap", r"\(at contact.gap=-1\)"),
        ({"contact.gap": "1:2"}, "vary", "three parts"),
        (["contact.gap=1", "contact.gap=2"], "vary", "varied twice"),
    ],
)
def test_bad_paths_and_values_are_refused_before_any_work(tmp_path, vary, field, message):
    """A malformed ``vary`` is an ArgumentError naming it; a point whose case is invalid, a CaseError naming the key."""
    with pytest.raises(ArgumentError if field == "vary" else CaseError, match=message) as error:
        sweep(short_case(), vary, records=2, output_dir=tmp_path / "out", scheduler="serial")
    assert error.value.field == field
    assert not (tmp_path / "out").exists()


def test_parquet_is_written_or_refused_in_one_line(tmp_path):
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        with pytest.raises(ArgumentError, match="parquet needs pyarrow") as error:
            run_sweep(tmp_path / "parquet", table_format="parquet")
        assert error.value.field == "table_format"
    else:
        table = run_sweep(tmp_path / "parquet", records=2, table_format="parquet")
        pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "parquet" / "sweep.parquet"), table, check_like=True)


# --- the numbers ------------------------------------------------------------------------------------


def test_serial_sweep_equals_simulate_and_estimate_at_every_point(serial_table):
    table = serial_table
    assert len(table) == 6
    assert list(table["contact.gap"]) == [0.5, 0.5, 1.0, 1.0, 1.5, 1.5]
    for row in table.itertuples(index=False):
        data = short_case()
        data["contact"]["gap"] = row[1]
        data["buildings"][1]["storeys"][0]["period"] = row[2]
        case = case_from_dict(data)
        result = simulate(case, records=RECORDS, seed=SEED, settings=Settings(workers=1))
        forces = [Fraction(float(f)) for f in result.force_max]
        assert row.mc_force_mean_N == float(sum(forces) / RECORDS)  # exactly: the exact mean, rounded once
        assert row.mc_force_mean_N == pytest.approx(result.force_max_mean, rel=1e-14)
        assert row.mc_force_std_error_N == pytest.approx(result.force_max_std_error, rel=1e-12)
        low, high = result.force_max_confidence_interval
        assert (row.mc_force_ci_low_N, row.mc_force_ci_high_N) == (pytest.approx(low, rel=1e-12), pytest.approx(high, rel=1e-12))
        assert row.mc_pounding_fraction == result.pounding_fraction
        assert row.mc_impacts_mean == result.impacts_mean
        assert row.mc_force_max_N == result.force_max.max()
        closed_form = estimate(case)
        assert row.estimate_force_N == closed_form.force_expected
        assert row.paper_force_N == closed_form.paper.force_expected
        assert row.estimate_pounding_probability == closed_form.pounding_probability
        assert row.required_gap_m == closed_form.required_gap


def test_the_table_does_not_depend_on_chunking(tmp_path, serial_table):
    for chunk_records in (1, 4, RECORDS):
        other = run_sweep(tmp_path / f"chunks-{chunk_records}", chunk_records=chunk_records)
        pd.testing.assert_frame_equal(other, serial_table, check_exact=True)


@pytest.mark.slow
def test_two_worker_local_cluster_equals_serial_exactly(tmp_path, serial_table):
    """Also while another cluster holds Dask's port 8787 (here a socket): the local cluster's scheduler serves
    its HTTP routes on a free port, with no "Port 8787 is already in use" warning on the user's terminal."""
    import socket
    import warnings

    with contextlib.ExitStack() as stack, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        holder = stack.enter_context(socket.socket(socket.AF_INET, socket.SOCK_STREAM))
        with contextlib.suppress(OSError):  # already held by another cluster on this machine: as well
            holder.bind(("", 8787))
            holder.listen()
        table = run_sweep(tmp_path / "local", scheduler=None, workers=2, chunk_records=2)  # the default: a LocalCluster
    assert not [w for w in caught if "already in use" in str(w.message)]
    assert table.attrs["chunks_computed"] == 6 * 3
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)


@pytest.mark.slow
def test_a_cluster_given_by_its_scheduler_address(tmp_path, serial_table):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        table = run_sweep(tmp_path / "address", scheduler=cluster.scheduler_address, chunk_records=4)
        assert list(client.run(lambda: importlib.import_module("pounding.studies.sweeps.work")._WARM).values()) == [True, True]  # both warmed
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)


# --- resuming -----------------------------------------------------------------------------------------


def test_interrupted_sweep_resumes_with_only_the_missing_chunks(tmp_path, serial_table):
    folder = tmp_path / "resumed"
    with pytest.raises(SweepInterrupted) as stopped:
        run_sweep(folder, max_chunks=7)
    assert (stopped.value.chunks_computed, stopped.value.chunks_missing) == (7, 11)
    assert len(chunk_files(folder)) == 7
    assert not (folder / "sweep.csv").exists()
    before = {path: path.stat().st_mtime_ns for path in chunk_files(folder)}
    table = run_sweep(folder)
    assert (table.attrs["chunks_computed"], table.attrs["chunks_reused"]) == (11, 7)
    assert all(path.stat().st_mtime_ns == mtime for path, mtime in before.items())  # kept, not recomputed
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)
    again = run_sweep(folder)
    assert (again.attrs["chunks_computed"], again.attrs["chunks_reused"]) == (0, 18)
    assert pd.read_csv(folder / "sweep.csv")["mc_force_mean_N"].tolist() == pytest.approx(serial_table["mc_force_mean_N"].tolist(), rel=1e-15)


def test_ctrl_c_keeps_the_finished_chunks(tmp_path, serial_table):
    folder = tmp_path / "ctrl-c"

    def interrupt(done, total):
        if done >= 3 * 2:  # after the third chunk of 2 records
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(folder, progress=interrupt)
    assert len(chunk_files(folder)) == 3
    table = run_sweep(folder)
    assert (table.attrs["chunks_computed"], table.attrs["chunks_reused"]) == (15, 3)
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)


def test_a_damaged_chunk_file_is_recomputed(tmp_path, serial_table):
    folder = tmp_path / "damaged"
    run_sweep(folder)
    damaged = chunk_files(folder)[4]
    damaged.write_text(damaged.read_text()[:40])
    table = run_sweep(folder)
    assert (table.attrs["chunks_computed"], table.attrs["chunks_reused"]) == (1, 17)
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)


@pytest.mark.slow
def test_a_killed_client_loses_only_its_chunks_in_flight(tmp_path, serial_table):
    folder = tmp_path / "killed"
    script = textwrap.dedent(f"""
        import sys, time, tomllib
        sys.path.insert(0, {str(ROOT / "tests")!r})
        from test_sweep import run_sweep
        from pathlib import Path
        run_sweep(Path({str(folder)!r}), progress=lambda done, total: time.sleep(0.3))
    """)
    client = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT)
    try:
        deadline = time.monotonic() + 40
        while len(chunk_files(folder)) < 4:
            assert client.poll() is None and time.monotonic() < deadline, "the sweep ended before it could be killed"
            time.sleep(0.02)
        client.send_signal(signal.SIGKILL)
        client.wait(10)
    finally:
        if client.poll() is None:
            client.kill()
    assert client.returncode == -signal.SIGKILL
    kept = len(chunk_files(folder))
    assert 4 <= kept < 18
    assert not (folder / "sweep.csv").exists()
    table = run_sweep(folder)
    assert (table.attrs["chunks_computed"], table.attrs["chunks_reused"]) == (18 - kept, kept)
    pd.testing.assert_frame_equal(table, serial_table, check_exact=True)


# --- the command line -------------------------------------------------------------------------------


def tiny_cli(argv: list[str]) -> int:
    """What ``pounding.cli.commands.main`` does with ``run``: InputError -> one line naming the option typed, exit 2."""
    parser = argparse.ArgumentParser(prog="pounding")
    commands = parser.add_subparsers(dest="command", required=True)
    add_arguments(commands.add_parser("sweep"))
    args = parser.parse_args(argv)
    try:
        return run(args)
    except InputError as error:
        print(f"pounding sweep: error: {error_line('sweep', error)}", file=sys.stderr)
        return 2


def write_case(tmp_path: Path) -> Path:
    text = preset_text("section5-T2-0.4").replace("duration = 20.0", "duration = 5.0")
    path = tmp_path / "short.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "vary, message",
    [
        ("contact.gap=0:1", "--vary: 'contact.gap=0:1': a range is start:stop:count"),
        ("contact.gap", "expected PATH=VALUES"),
        ("buildings.3.storeys.1.period=0.4", "buildings has 2 entries"),
        ("contact.gap=-1,1", "contact.gap: must be"),
    ],
)
def test_bad_vary_on_the_command_line_exits_2_with_one_line(tmp_path, capsys, vary, message):
    case = write_case(tmp_path)
    assert tiny_cli(["sweep", str(case), "--vary", vary, "-o", str(tmp_path / "out"), "--scheduler", "serial"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err


def test_command_line_sweep_prints_the_table_and_writes_the_chart(tmp_path, capsys):
    case = write_case(tmp_path)
    out = tmp_path / "out"
    argv = ["sweep", str(case), "--vary", "contact.gap=0.5,1.5", "--records", "4", "--seed", "2", "-o", str(out),
            "--scheduler", "serial", "--chunk-records", "3"]
    assert tiny_cli(argv + ["--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert [row["contact.gap"] for row in result["rows"]] == [0.5, 1.5]
    assert result["chunks_computed"] == 4 and result["case_units"] == "kgf-cm-s"
    assert all(math.isfinite(row["mc_force_mean_N"]) and row["records"] == 4 for row in result["rows"])
    assert Path(result["table"]) == out / "sweep.csv" and Path(result["chart"]) == out / "sweep.html"
    assert "bokeh" in (out / "sweep.html").read_text().lower()
    assert tiny_cli(argv) == 0  # resumed: nothing to compute
    text = capsys.readouterr().out
    assert "0 chunk(s) computed, 4 found done" in text and "sweep.csv" in text


@pytest.mark.slow
def test_the_module_is_light_and_the_chart_only_imported_when_asked(tmp_path):
    case = write_case(tmp_path)
    code = textwrap.dedent(f"""
        import sys, argparse
        import pounding.studies.sweeps, pounding.cli.sweep
        heavy = [name for name in ("dask", "distributed", "pandas", "bokeh") if name in sys.modules]
        assert not heavy, heavy
        parser = pounding.cli.sweep.add_arguments(argparse.ArgumentParser())
        pounding.cli.sweep.run(parser.parse_args([{str(case)!r}, "--records", "2", "-o", {str(tmp_path / "out")!r},
                                               "--scheduler", "serial", "--no-chart"]))
        assert "bokeh" not in sys.modules
        import pounding
        assert callable(pounding.sweep)
    """)
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "1 point(s) x 2 records" in done.stdout


def test_pounding_sweep_command_when_wired(tmp_path):
    from pounding.cli import commands

    assert "sweep" in commands._COMMANDS
    done = subprocess.run(
        [sys.executable, "-m", "pounding", "sweep", "section5-T2-0.4", "--vary", "contact.gap=1:2", "-o", str(tmp_path / "out")],
        cwd=ROOT, capture_output=True, text=True, timeout=60,
    )
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "start:stop:count" in done.stderr


def test_points_times_records_beyond_the_limit_are_refused_before_any_work(tmp_path):
    """Issue 33: each factor within its own limit, their product past defaults.MAX_TIME_HISTORIES (1e7) is refused
    naming records, and nothing is written; a run of the same points with fewer records would start."""
    from pounding import defaults
    from pounding.simulation.plan import MonteCarloPlan
    from pounding.studies.fragility import fragility_curve

    vary = {"contact.gap": [0.01 * (1 + i) for i in range(11)]}
    records = defaults.MAX_TIME_HISTORIES // 11 + 1
    assert records <= defaults.MAX_RECORDS
    with pytest.raises(ArgumentError, match="records.*time histories"):
        sweep(short_case(), vary, output_dir=tmp_path / "out", records=records, scheduler="serial")
    assert not (tmp_path / "out" / "sweep.csv").exists()
    with pytest.raises(ArgumentError, match="records.*time histories"):
        fragility_curve("section5-T2-0.4", 4.0e5, [0.1 * (1 + i) for i in range(11)], MonteCarloPlan(records=records))
