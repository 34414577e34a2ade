"""The closed-form distribution of F_max (G31) against Monte Carlo (issue 23):
the median, 84th and 95th percentiles as errors, and the Kolmogorov-Smirnov
distance between the closed-form CDF and the records' empirical one, by regime.

Prints a markdown table per case and a summary by regime; docs/accuracy.md quotes it.

    python3 -m validation.force_distribution_accuracy                 # the 33-case grid, 500 records: about 2 min
    python3 -m validation.force_distribution_accuracy --draw 2029     # also a draw of 100 random cases
"""

from __future__ import annotations

import argparse
import json
from collections import defaultdict

import numpy as np

from pounding import estimate, simulate
from pounding.studies.paper_tables import accuracy_cases, random_cases

RECORDS, SEED = 500, 11
PROBABILITIES = (0.5, 0.84, 0.95)


def kolmogorov_smirnov(distribution, forces) -> float:
    """sup_f |P(F_max <= f) - the records' empirical CDF|, checked on both sides of every record's F_max
    (the closed form has an atom at 0, no impact, and is continuous above)."""
    ordered = np.sort(np.asarray(forces, dtype=float))
    n = ordered.size
    closed_after = distribution.probability_below(ordered)
    closed_before = np.where(ordered > 0.0, closed_after, 0.0)  # just below f: the atom at 0 is not yet reached
    empirical_after = np.searchsorted(ordered, ordered, side="right") / n  # ties (the records without impact) counted once
    empirical_before = np.searchsorted(ordered, ordered, side="left") / n
    return float(max(np.max(np.abs(closed_after - empirical_after)), np.max(np.abs(closed_before - empirical_before))))


def row(case, records: int, seed: int) -> dict:
    closed = estimate(case)
    forces = simulate(case, records=records, seed=seed).force_max
    distribution = closed.force_max_distribution
    errors = {}
    for probability in PROBABILITIES:
        empirical = float(np.quantile(forces, probability))
        errors[f"{probability:g}"] = None if empirical == 0.0 else distribution.quantile(probability) / empirical - 1.0
    return {"case": case.name, "regime": closed.accuracy_regime, "pounding_fraction": float(np.mean(forces > 0)),
            "quantile_errors": errors, "kolmogorov_smirnov": kolmogorov_smirnov(distribution, forces)}


def rows(cases, records: int = RECORDS, seed: int = SEED) -> list[dict]:
    return [row(case, records, seed) for case in cases]


def summary(table: list[dict]) -> list[dict]:
    """By regime: cases, the median and largest KS distance, and per fractile the cases within 10 % and the median |error|."""
    groups = defaultdict(list)
    for item in table:
        groups[item["regime"]].append(item)
    out = []
    for regime, items in groups.items():
        distances = np.array([item["kolmogorov_smirnov"] for item in items])
        entry = {"regime": regime, "cases": len(items), "ks_median": float(np.median(distances)), "ks_max": float(distances.max())}
        for key in (f"{p:g}" for p in PROBABILITIES):
            errors = np.array([item["quantile_errors"][key] for item in items if item["quantile_errors"][key] is not None])
            entry[key] = {"cases": int(errors.size), "within_10": int(np.sum(np.abs(errors) <= 0.10)),
                          "median_abs": float(np.median(np.abs(errors))) if errors.size else None,
                          "range": [float(errors.min()), float(errors.max())] if errors.size else None}
        out.append(entry)
    return out


def main(records: int = RECORDS, seed: int = SEED, draw: int | None = None, cases: int | None = None, json_output: bool = False) -> None:
    """``cases``: only the first ones of the grid (and of the draw)."""
    cases = accuracy_cases()[:cases] + (random_cases(draw)[:cases] if draw is not None else [])
    table = rows(cases, records, seed)
    if json_output:
        print(json.dumps({"rows": table, "summary": summary(table)}))
        return
    percent = lambda e: "n/a" if e is None else f"{100 * e:+.1f} %"  # noqa: E731
    print(f"Monte Carlo: {records} records a case, seed {seed}; errors are closed form / Monte Carlo - 1.\n")
    print("| case | regime | pounding | median | 84 % | 95 % | KS distance |")
    print("|---|---|---|---|---|---|---|")
    for item in table:
        errors = item["quantile_errors"]
        print(f"| {item['case']} | {item['regime']} | {item['pounding_fraction']:.2f} | {percent(errors['0.5'])} | "
              f"{percent(errors['0.84'])} | {percent(errors['0.95'])} | {item['kolmogorov_smirnov']:.3f} |")
    print("\n| regime | cases | KS median | KS largest | median within 10 % | 84 % within 10 % | 95 % within 10 % | 84 %: median \\|error\\|, range |")
    print("|---|---|---|---|---|---|---|---|")
    for entry in summary(table):
        cells = [f"{entry[k]['within_10']} of {entry[k]['cases']}" for k in ("0.5", "0.84", "0.95")]
        e84 = entry["0.84"]
        spread = "n/a" if e84["range"] is None else (f"{100 * e84['median_abs']:.1f} %, {100 * e84['range'][0]:+.0f} % to "
                                                       f"{100 * e84['range'][1]:+.0f} %")
        print(f"| {entry['regime']} | {entry['cases']} | {entry['ks_median']:.3f} | {entry['ks_max']:.3f} | {' | '.join(cells)} | {spread} |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--draw", type=int, default=None, help="also the 100 cases of this random draw")
    parser.add_argument("--json", action="store_true")
    arguments = parser.parse_args()
    main(arguments.records, arguments.seed, arguments.draw, json_output=arguments.json)
