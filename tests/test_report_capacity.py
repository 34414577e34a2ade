"""The gap sized to a capacity in the report (issue 34): ``pounding report --capacity F`` (F in kN, or kgf with
``--units kgf-cm-s``, as ``estimate --capacity``) and the dashboard's export state P(F_max > F) and the gap for F
(``Estimate.gap_for_capacity``) in the summary, with the Monte Carlo at that gap on the check's records
(``check_gap_for_capacity``); a bad value exits 2 naming ``--capacity``."""

from __future__ import annotations

import html
import json
import re

import pytest

from pounding import load_case
from pounding.cli.commands import main
from pounding.closed_form.estimator import estimate
from pounding.display_units import display
from pounding.studies.check import capacity_check_sentence, check_estimate, check_gap_for_capacity

SECTION5 = "section5-T2-0.4"


def _paragraph(page: str, css: str) -> str:
    found = re.search(rf'<p class="{css}">(.*?)</p>', page, flags=re.DOTALL)
    assert found, css
    return html.unescape(re.sub(r"<[^>]+>", "", found.group(1)))


def _row(page: str, quantity: str) -> list[str]:
    found = re.search(rf"<tr><th>{re.escape(html.escape(quantity))}</th>(.*?)</tr>", page, flags=re.DOTALL)
    assert found, quantity
    return [html.unescape(cell) for cell in re.findall(r"<td[^>]*>([^<]*)</td>", found.group(1))]


@pytest.mark.parametrize("units, typed", [("SI", 300.0), ("kgf-cm-s", 30591.5)])
def test_report_capacity_states_the_librarys_gap_for_it_and_its_monte_carlo(tmp_path, capsys, units, typed):
    path = tmp_path / "r.html"
    assert main(["report", SECTION5, "-o", str(path), "--records", "16", "--seed", "2", "--capacity", f"{typed:g}",
                 "--units", units, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    shown = display(units)
    capacity = typed * shown.force_scale  # N: typed in kN, or kgf
    result = estimate(load_case(SECTION5))
    gap = result.gap_for_capacity(capacity)  # the library, directly
    at_gap = check_gap_for_capacity(result, capacity, check_estimate(result, records=16, seed=2))
    assert out["capacity"] == pytest.approx(capacity, rel=1e-12)
    assert out["gap_for_capacity"] == pytest.approx(gap, rel=1e-12) and 0 < gap < result.required_gap
    assert out["gap_for_capacity_check"] == json.loads(json.dumps(at_gap))
    assert out["probability_exceeding"] == pytest.approx(result.probability_exceeding(capacity), rel=1e-12)

    page = path.read_text()
    force, length = shown.force(capacity), shown.length(gap)
    assert force == ("300 kN" if units == "SI" else "30,592 kgf") and length.endswith(" mm" if units == "SI" else " cm")
    sentence = _paragraph(page, "gap-adequate")
    assert (f"For a capacity of {force}, the probability that the largest force exceeds it is "
            f"{100 * result.probability_exceeding(capacity):.3g} % at the gap entered; a gap of {length} keeps it at "
            "or below 5 %, so the gap entered is not enough for that force.") in sentence
    assert _paragraph(page, "capacity-check") == capacity_check_sentence(at_gap, capacity, 0.95, shown.force, shown.length)
    assert _row(page, f"gap for P(F_max > {force}) at most 5 %")[0] == length
    assert _row(page, f"probability that F_max exceeds {force}")[0] == f"{100 * result.probability_exceeding(capacity):.3g} %"
    assert f"--capacity {typed:g}" in page  # the command that made it


def test_without_a_capacity_the_report_says_nothing_of_one(tmp_path, capsys):
    path = tmp_path / "r.html"
    assert main(["report", SECTION5, "-o", str(path), "--records", "8", "--json"]) == 0
    assert "capacity" not in json.loads(capsys.readouterr().out)
    page = path.read_text()
    assert "For a capacity" not in page and 'class="capacity-check"' not in page and "--capacity" not in page


@pytest.mark.parametrize("value", ["0", "-3e5", "abc", "inf", "nan"])
def test_a_bad_capacity_exits_2_with_one_line_naming_it(tmp_path, capsys, value):
    path = tmp_path / "r.html"
    with pytest.raises(SystemExit) as stopped:
        main(["report", SECTION5, "-o", str(path), f"--capacity={value}"])
    assert stopped.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--capacity" in err and "Traceback" not in err
    assert not path.exists()


def test_one_definition_of_capacity_for_every_command():
    """``--capacity`` reads the same on every command that takes it: one argument definition (arguments.add_capacity)."""
    import argparse

    from pounding.cli.parser import parser

    commands = next(a for a in parser()._actions if isinstance(a, argparse._SubParsersAction)).choices
    found = {name: next(a for a in sub._actions if "--capacity" in a.option_strings)
             for name, sub in commands.items() if any("--capacity" in a.option_strings for a in sub._actions)}
    assert set(found) == {"estimate", "simulate", "report", "fragility"}
    assert len({a.type for a in found.values()}) == 1
    assert all(a.help.startswith("a capacity F (kN; kgf with --units kgf-cm-s)") for a in found.values())


def test_the_dashboards_report_carries_the_pages_capacity():
    """The page's Export report: the capacity in the page's units (kN here) goes into the report's summary, as the
    headline shows it."""
    from dashboard.view import PoundingDashboard

    page = PoundingDashboard()
    model = page.model
    model.capacity = 250.0  # kN
    text = open(page._export(), encoding="utf-8").read()
    gap = estimate(load_case(SECTION5)).gap_for_capacity(250e3)
    sentence = _paragraph(text, "gap-adequate")
    assert "For a capacity of 250 kN" in sentence and f"a gap of {display('SI').length(gap)} keeps it" in sentence
    assert _paragraph(text, "capacity-check").startswith(f"At the gap for 250 kN, {display('SI').length(gap)}:")
    page.close()
