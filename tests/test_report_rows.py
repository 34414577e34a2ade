"""Issue 35: the report of a case of several contacts lists every contact with the library's numbers, names the
governing contact and draws each contact's force in one record; ``pounding report CASE`` makes it."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib

from pounding import estimate
from pounding.case.case import case_from_dict, contact_label
from pounding.display_units import display
from tests.test_dashboard_rows_model import ROW_FILE

from .browser import ROOT


def test_pounding_report_of_a_row_lists_every_contact_with_the_librarys_numbers(tmp_path):
    path = tmp_path / "row.toml"
    path.write_text(ROW_FILE)
    out = tmp_path / "row.html"
    done = subprocess.run([sys.executable, "-m", "pounding", "report", str(path), "-o", str(out), "--records", "20", "--json"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    text = out.read_text()
    result = estimate(case_from_dict(tomllib.loads(ROW_FILE)))
    check = json.loads(done.stdout.splitlines()[-1])["check"]
    shown = display("SI")
    governing = contact_label(result.case.contacts[result.governing])
    assert f"Governing: <b>{governing}</b>" in text
    assert text.count('<tr class="contact') == len(result.case.contacts) == 2
    for number, (contact, one) in enumerate(zip(result.case.contacts, result.contacts), start=1):
        row = text.split(f'data-contact="{number}">')[1].split("</tr>")[0]
        assert f'<td class="floors">{contact.levels[0]}/{contact.levels[1]}</td>' in row
        assert f'<td class="gap">{shown.length(contact.gap)}</td>' in row
        assert f'<td class="force-expected">{shown.force(one.force_expected)}</td>' in row
        assert f'<td class="pounding-probability">{100 * one.pounding_probability:.3g} %</td>' in row
        assert f'<td class="mc-mean">{shown.force(check["contacts"][number - 1]["force_max_mean"])}</td>' in row
    assert "Pounding force at each contact during one record" in text and "Traceback" not in text
    assert "contact 2: gap" in text  # the inputs list each contact


def test_the_single_contact_report_is_unchanged_in_its_parts(tmp_path):
    from pounding import load_case
    from pounding.report import compute_snapshot, report_html

    text = report_html(compute_snapshot(load_case("section5-T2-0.4")))
    assert 'class="contacts"' not in text and "<th colspan=\"3\">Contact</th>" in text and "contact 1:" not in text


def test_a_report_with_its_check_drops_the_warnings_advice_to_run_it(tmp_path):
    """The check the warnings advise ("Check it with `pounding estimate --check`") stands above them in a report that
    ran it: the advice is dropped, the warning kept; the estimate's own warnings still carry it."""
    import html
    import re

    from pounding.cli.commands import main
    from pounding.closed_form.regimes import CHECK_ADVICE, without_check_advice

    from .test_rows import ROW, row

    case_file = tmp_path / "row.toml"
    case_file.write_text(ROW)
    path = tmp_path / "r.html"
    assert main(["report", str(case_file), "-o", str(path), "--records", "8"]) == 0
    page = path.read_text()
    warnings = estimate(row()).warnings
    assert any(CHECK_ADVICE in w for w in warnings)  # the test has teeth
    for warning in warnings:
        assert html.escape(without_check_advice(warning)) in page
    shown = re.findall(r'<p class="warning">(.*?)</p>', page, flags=re.DOTALL)
    assert len(shown) == len(warnings) and not any(html.escape(CHECK_ADVICE) in w for w in shown)


def test_a_one_contact_report_with_its_check_drops_the_advice_too(tmp_path):
    import html
    import re

    from pounding.cli.commands import main
    from pounding.closed_form.regimes import CHECK_ADVICE, without_check_advice

    preset = "section5-T2-0.4-G0x4pi2"
    warnings = estimate(preset).warnings
    assert any(CHECK_ADVICE in w for w in warnings)  # the test has teeth
    path = tmp_path / "r.html"
    assert main(["report", preset, "-o", str(path), "--records", "8"]) == 0
    shown = re.findall(r'<p class="warning">(.*?)</p>', path.read_text(), flags=re.DOTALL)
    assert [html.unescape(w).replace("\u26a0 ", "") for w in shown] == [without_check_advice(w) for w in warnings]
