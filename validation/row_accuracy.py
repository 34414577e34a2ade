"""The closed form of cases with several contacts against Monte Carlo (docs/accuracy.md, "Several contacts").

On the grid of :mod:`pounding.studies.row_grid` (48 cases: two buildings meeting at every shared floor, a
taller beside a shorter one, three in a row; elastic and yielding; Kanai-Tajimi and Clough-Penzien; two gaps),
each case's closed form (:class:`~pounding.closed_form.row.RowEstimate`) against :data:`RECORDS` records of the
whole case (seed :data:`SEED`):

- the largest force over all contacts, E[F_max] closed form / Monte Carlo - 1, by kind of case;
- each contact's E[F_max] against the same records;
- how contacts interact: each contact's Monte Carlo mean in the whole case over that of its two buildings
  alone with that contact only (``case.pair(i)``, the same records), which the closed form takes it to be.

    python3 -m validation.row_accuracy                 # the grid, about 5 min on 2 cores
    python3 -m validation.row_accuracy --update        # and write force["several contacts"] into accuracy.json
    python3 -m validation.row_accuracy --cases 2 --records 8
"""

from __future__ import annotations

import argparse
import datetime
import json
from pathlib import Path

import numpy as np

from pounding import estimate, simulate
from pounding.closed_form.regimes import ROW_KINDS, row_kind
from pounding.closed_form.row import contact_pairs, largest_force_distribution
from pounding.studies.row_grid import row_cases

from .entries import DEFAULT_OUTPUT, force_entry, git_commit
from .sizes import first

RECORDS, SEED = 200, 11
SEVERAL_CONTACTS_ABOUT = ("force['several contacts']: a case of several contacts, the largest force over all contacts, closed form "
         "(each contact's pair, contacts independent) against Monte Carlo of the whole case, by kind; force['several "
         "contacts, each contact']: each contact's force alike; interaction: each contact's Monte Carlo mean in the "
         "whole case over its pair's alone: validation/row_accuracy.py on pounding.studies.row_grid's 48 cases")


def measure(case, records: int) -> dict:
    """One case: its kind, the errors of the largest force and of each contact, and each contact's interaction ratio."""
    # the closed form as RowEstimate makes it, without the accuracy this script measures for it
    estimates = [estimate(pair) for pair in contact_pairs(case)]
    largest = largest_force_distribution([e.force_max_distribution for e in estimates]).mean()
    whole = simulate(case, records=records, seed=SEED)
    error = lambda cf, mc: cf / mc - 1.0 if mc > 0 else None  # noqa: E731
    contacts, interaction = [], []
    for index, (contact_estimate, peaks) in enumerate(zip(estimates, whole.contacts)):
        mean = float(peaks.force_max.mean())
        contacts.append(error(contact_estimate.force_expected, mean))
        alone = simulate(case.pair(index), records=records, seed=SEED).force_max_mean
        interaction.append(mean / alone if alone > 0 else None)
    return {"name": case.name, "kind": row_kind(case), "force": error(largest, whole.force_max_mean),
            "force_mc": whole.force_max_mean, "force_cf": largest, "contacts": contacts,
            "interaction": interaction}


def _valid(values) -> list[float]:
    return [v for v in values if v is not None]


def tables(rows: list[dict]) -> dict:
    """By kind: the largest force's errors (accuracy.json's entry), each contact's, and the interaction ratios."""
    out = {}
    for kind in ROW_KINDS:
        mine = [r for r in rows if r["kind"] == kind]
        ratios = np.array(_valid([x for r in mine for x in r["interaction"]]))
        out[kind] = {
            "largest": force_entry(_valid([r["force"] for r in mine])),
            "each contact": force_entry(_valid([x for r in mine for x in r["contacts"]])),
            "interaction": {"contacts": int(ratios.size),
                            "median": round(float(np.median(ratios)), 3) if ratios.size else None,
                            "low": round(float(ratios.min()), 2) if ratios.size else None,
                            "high": round(float(ratios.max()), 2) if ratios.size else None},
        }
    return out


def print_tables(rows: list[dict], measured: dict) -> None:
    print("| case | MC E[F_max] (kN) | closed form (kN) | error | each contact's errors | in the case / alone |")
    print("|---|---|---|---|---|---|")
    percent = lambda v: "n/a" if v is None else f"{100 * v:+.0f} %"  # noqa: E731
    for r in rows:
        ratios = ", ".join("n/a" if v is None else f"{v:.2f}" for v in r["interaction"])
        print(f"| {r['name']} | {r['force_mc'] / 1e3:.1f} | {r['force_cf'] / 1e3:.1f} | {percent(r['force'])} | "
              f"{', '.join(percent(v) for v in r['contacts'])} | {ratios} |")
    print()
    print("| kind | of | cases | within 10 % | median | range | interaction median (range) |")
    print("|---|---|---|---|---|---|---|")
    for kind, entry in measured.items():
        for of in ("largest", "each contact"):
            e = entry[of]
            span = "n/a" if e["low"] is None else f"{100 * e['low']:+.0f} % to {100 * e['high']:+.0f} %"
            median = "n/a" if e["median_abs_error"] is None else f"{100 * e['median_abs_error']:.0f} %"
            i = entry["interaction"]
            inter = "n/a" if i["median"] is None else f"{i['median']:.2f} ({i['low']:.2f} to {i['high']:.2f})"
            print(f"| {kind} | {of} | {e['cases']} | {e['within_10_percent']} | {median} | {span} | "
                  f"{inter if of == 'largest' else ''} |")


def several_contacts(cases: int | None = None, records: int = RECORDS, rows: list[dict] | None = None) -> dict:
    """accuracy.json's part for several contacts: ``force`` (the two tables by kind) and ``section`` (the
    interaction), measured on the first ``cases`` of each kind (all for None), or from ``rows`` already measured."""
    if rows is None:
        grid = row_cases()
        chosen = [case for kind in ROW_KINDS for case in first([c for c in grid if row_kind(c) == kind], cases)]
        rows = [measure(case, records) for case in chosen]
    measured = tables(rows)
    return {"force": {"several contacts": {kind: entry["largest"] for kind, entry in measured.items()},
                      "several contacts, each contact": {kind: entry["each contact"] for kind, entry in measured.items()}},
            "section": {"interaction": {kind: entry["interaction"] for kind, entry in measured.items()}},
            "rows": rows, "measured": measured}


def main(cases: int | None = None, records: int = RECORDS, update: bool = False, output=DEFAULT_OUTPUT) -> dict:
    result = several_contacts(cases, records)
    print_tables(result["rows"], result["measured"])
    if update:
        if cases is not None or records != RECORDS:
            raise SystemExit("--update writes the full grid's numbers only: run it without --cases and --records")
        document = json.loads(Path(output).read_text())
        document["force"].update(result["force"])
        document["several_contacts"] = {"about": f"{SEVERAL_CONTACTS_ABOUT}; at commit {git_commit()} on "
                                                 f"{datetime.date.today().isoformat()}", **result["section"]}
        Path(output).write_text(json.dumps(document, indent=2, ensure_ascii=False) + "\n")
    return result["measured"]


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, help="the first N cases of each kind")
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--update", action="store_true", help="write force['several contacts'] into accuracy.json")
    arguments = parser.parse_args()
    main(arguments.cases, arguments.records, arguments.update)
