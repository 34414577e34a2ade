"""Every warning the library can give, in plain words: no equation label (Eq. 19, (G31)) and no internal symbol
(sigma_X, q = 0.55, memory 0.06, beta_share) in what the command line, the dashboard and the report show; they
belong in docs/theory.md. Where the closed form may be off, the advice is its Monte Carlo check (``pounding
estimate --check``), which the dashboard's headline says in its own terms; every warning at most 200 characters.

The warnings are collected by running the estimator where each kind is given: every preset at its own gap, at
0.75 and 1.5 times its RMS relative displacement; a yielding pair under a Clough-Penzien spectrum; records cut
below the motion; a soft and an absurdly stiff contact; a suite of recorded motions whose fitted spectrum sits
off the records and on a bound of its range."""

from __future__ import annotations

import dataclasses
import html
import re

import numpy as np
import pytest

from pounding import load_case, preset_names
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import CloughPenzien, KanaiTajimi, ground_accelerations
from pounding.presets import preset_description, preset_text

FORBIDDEN = {
    "an equation label": re.compile(r"\bEqs?\.|\((?:[GDCRSKFP]\d+|E\d+)\)|\b[GCRSKF]\d+-\d+\b|\bG(?:[1-9]|[1-3]\d)\b"),
    "a standard deviation's symbol": re.compile(r"sigma|\bnu\b|\brho\b"),
    "a bandwidth or correlation symbol": re.compile(r"\b[qr] = "),
    "the impacts' memory": re.compile(r"\bmemory\b"),
    "a case file's internal key": re.compile(r"\bbeta_share\b|\bomega_[gf]\b|\bxi_[gf]\b"),
    "the linearization's residual": re.compile(r"\bresidual\b"),
}
ADVICE = ("Check it with `pounding estimate --check`.", "Use `pounding simulate --design-gap")
PRESET = "section5-T2-0.4"


def _with(case, **contact):
    return case.with_contact(**contact)


def _closed_form_texts():
    """(where, text) of every warning and accuracy statement of the estimates described in the module docstring."""
    results = []
    for name in preset_names():
        pair = LinearizedPair.of(load_case(name))
        first = estimate(pair)
        results.append((name, first))
        sigma = first.sigma_relative_displacement
        results += [(f"{name} at {u} RMS", estimate(LinearizedPair(_with(pair.case, gap=u * sigma), pair.buildings)))
                    for u in (0.75, 1.5)]
    case = load_case("section5-T2-0.8")
    s = case.excitation.spectrum
    spectrum = CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6)
    results.append(("Clough-Penzien, yielding", estimate(dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=spectrum)))))
    case = load_case(PRESET)
    results.append(("records cut at 10 rad/s", estimate(dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, cutoff_frequency=10.0)))))
    results.append(("soft contact", estimate(_with(case, stiffness=case.contact.stiffness * 1e-9))))
    results.append(("stiff contact", estimate(_with(case, stiffness=case.contact.stiffness * 1e12))))
    for where, result in results:
        yield where, result.measured_accuracy
        yield where, result.accuracy.statement(with_verdict=True)
        for warning in result.warnings:
            yield where, warning


@pytest.fixture(scope="module")
def texts(tmp_path_factory):
    """Every text collected, the recorded suite's included: six records of the preset scaled by 3 (its fitted
    spectrum misses their mean) and the closed form on them."""
    folder = tmp_path_factory.mktemp("suite")
    (folder / "motions").mkdir()
    excitation = load_case(PRESET).excitation
    for index, record in enumerate(ground_accelerations(excitation, 5, range(6))):
        write_at2(folder / "motions" / f"m{index}.AT2", Accelerogram(f"m{index}", excitation.time_step, record))
    text = preset_text(PRESET)
    start, end = text.index("[excitation]"), text.index("[[buildings]]")
    (folder / "case.toml").write_text(text[:start] + '[excitation]\nrecords = ["motions/*.AT2"]\n\n' + text[end:])
    recorded = load_case(folder / "case.toml")
    found = list(_closed_form_texts())
    found += [("recorded suite", w) for w in estimate(recorded).warnings]
    from pounding.hazard.fit_quality import FitQuality
    from pounding.hazard.motion_fit import XI_RANGE, FittedExcitation

    off = FitQuality((0.5, 1.0), (1.6, 1.0), (0.2,), (1.0,), 1.0, 1.0, 1.0)
    found.append(("fit quality", off.warning()))
    found.append(("fit on a bound", FittedExcitation(KanaiTajimi(0.05, 10.0, XI_RANGE[0]), 10.0, "d", np.ones(3), np.ones(3)).bound_warning()))
    return [(where, text) for where, text in found if text]


def test_warnings_speak_plain_words(texts):
    bad = [(where, what, text) for where, text in texts for what, pattern in FORBIDDEN.items() if pattern.search(text)]
    assert bad == []


def test_every_warning_is_one_or_two_short_sentences(texts):
    for where, text in texts:
        assert len(text) <= 200 and "\n" not in text, (where, text)
        assert text.count(". ") <= 2, (where, text)  # at most three sentences, the advice being one


def test_every_kind_of_warning_was_met(texts):
    """The scan saw each kind of warning the library gives (a scan that met none would pass on anything)."""
    starts = ("A building yields and the spectrum", "Storeys near elastic-perfectly plastic", "The buildings sway at nearly",
              "The gap is 0.5 to 1 times", "Only the largest swings close this gap", "The gap for 95 %", "The records stop at",
              "The contact is soft", "The force is", "The closed-form gap for recorded motions", "The closed form's spectrum is",
              "The Kanai-Tajimi fit to the records")
    seen = {start for start in starts for _, text in texts if text.startswith(start)}
    assert seen == set(starts)


def test_where_the_closed_form_may_be_off_the_advice_is_its_check_and_the_dashboard_knows_it(texts):
    """A warning that says the force may be off ends on the Monte Carlo check of the same case (it said `pounding
    simulate`, which reprints the closed form); each advice given is one the dashboard's headline turns into its
    own terms, so a command line never shows on the page."""
    from dashboard.headline import _ADVICE, _in_page_terms

    for where, text in texts:
        if "may be off" in text or "measured" in text and "off" in text and text.startswith("The"):
            assert text.endswith(ADVICE[0]) or ADVICE[1] in text, (where, text)
        if "`pounding" in text:
            assert any(command in text for command, _, _ in _ADVICE), (where, text)
            assert "`pounding" not in _in_page_terms(text, set()), (where, text)
    assert {command for command, _, _ in _ADVICE} >= {ADVICE[0], ADVICE[1]}


def test_a_rare_pounding_warning_never_sits_under_a_high_probability_of_pounding():
    """The Section 5 pair at 1.5 RMS relative displacements pounds in most records (the estimate's probability is
    high), and its warning must not say pounding is rare there (it did: "69.9 % probability of pounding" above
    "Pounding is rare at this gap")."""
    pair = LinearizedPair.of(load_case(PRESET))
    sigma = estimate(pair).sigma_relative_displacement
    result = estimate(LinearizedPair(_with(pair.case, gap=1.5 * sigma), pair.buildings))
    assert result.pounding_probability > 0.5
    texts = (*result.warnings, result.measured_accuracy)
    assert any(text.startswith("Only the largest swings close this gap") for text in texts)
    assert not [text for text in texts if re.search(r"pounding is rare|rare pounding|seldom", text, re.IGNORECASE)]


def test_the_report_speaks_plain_words_outside_its_method_section():
    """What a report's reader sees (its scripts and styles aside) names no symbol anywhere and no equation label
    before its Method section, which cites the paper's equations by number (as does a built-in case's description of
    the paper's case); its figures' legends and titles, drawn
    by Bokeh from the scripts, carry no label either. A modulated case at 1.5 RMS relative displacements, whose
    estimate warns."""
    from pounding.report import compute_snapshot, report_html

    case = load_case("section5-T2-0.4-nonstationary")
    pair = LinearizedPair.of(case)
    sigma = estimate(pair).sigma_relative_displacement
    snapshot = compute_snapshot(_with(case, gap=1.5 * sigma))
    assert snapshot.estimate.warnings
    page = report_html(snapshot)
    shown = re.sub(r"<(script|style)\b[^>]*>.*?</\1>", "", page, flags=re.S)
    shown = shown.replace(html.escape(preset_description(case.name)), "")  # the paper's case, cited as the paper writes it
    before_method = shown[: shown.index("<h2>5. Method</h2>")]
    for what, pattern in FORBIDDEN.items():
        if what == "an equation label":
            assert not pattern.search(before_method), pattern.search(before_method)
        elif what != "a case file's internal key":  # the inputs table names the case file's keys, as typed
            assert not pattern.search(shown), (what, pattern.search(shown))
    scripts = "".join(re.findall(r"<script\b[^>]*>(.*?)</script>", page, flags=re.S))
    labels = re.findall(r'"(?:label|text)":\s*(?:\{"type":"value","value":)?"([^"]*)"', scripts)
    assert labels and not [label for label in labels if FORBIDDEN["an equation label"].search(label)], labels
