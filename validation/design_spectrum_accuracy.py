"""The recommended closed form against Monte Carlo on design-spectrum cases
(issue 22): EC8 and ASCE 7-16 spectra, a few ground types, elastic and
yielding pairs, each the same compatible filter bank for both methods.

Prints a markdown table (case, regime, gap / sigma_X, Monte Carlo E[F_max]
with its standard error, the recommended and the paper's estimate as errors)
and a summary by regime; docs/accuracy.md quotes it.

    python3 -m validation.design_spectrum_accuracy            # about 2 min on 2 cores
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from pounding import estimate, simulate
from pounding.case.case import case_from_dict

RECORDS, SEED = 300, 2022

HAZARDS = {
    "EC8 1 B 0.25g": {"code": "ec8", "spectrum_type": 1, "ground_type": "B", "ag": 0.25},
    "EC8 1 C 0.30g": {"code": "ec8", "spectrum_type": 1, "ground_type": "C", "ag": 0.30},
    "EC8 1 D 0.20g": {"code": "ec8", "spectrum_type": 1, "ground_type": "D", "ag": 0.20},
    "EC8 2 C 0.30g": {"code": "ec8", "spectrum_type": 2, "ground_type": "C", "ag": 0.30},
    "ASCE 1.0/0.6": {"code": "asce7-16", "SDS": 1.0, "SD1": 0.6, "TL": 8.0},
    "ASCE 0.5/0.2": {"code": "asce7-16", "SDS": 0.5, "SD1": 0.2, "TL": 6.0},
}
# (label, periods [s], yield drifts [m] or None for elastic, gap [m])
PAIRS = {
    "elastic 1.0/0.5 s": ((1.0, 0.5), (None, None), 0.02),
    "yielding 1.0/0.5 s": ((1.0, 0.5), (0.02, 0.01), 0.02),
    "yielding 1.0/0.5 s, gap 8 cm": ((1.0, 0.5), (0.02, 0.01), 0.08),
}
MASS = 4.0e4  # [kg] per floor: the paper's scale (40 kgf s^2/cm)
CONTACT = {"model": "jankowski", "gap": 0.02, "stiffness": 1.96e9, "restitution": 0.65}  # SI: 2e5 kgf/cm^1.5


def case_data(hazard: dict, pair: tuple, duration: float = 20.0) -> dict:
    periods, drifts, gap = pair
    buildings = []
    for period, drift in zip(periods, drifts):
        storey = {"period": period, "mass": MASS}
        if drift is not None:
            storey["hysteresis"] = {"yield_drift": drift, "post_yield_ratio": 0.05}
        buildings.append({"damping_ratio": 0.05, "storeys": [storey]})
    return {"units": "SI", "excitation": {"spectrum": "design", "duration": duration, **hazard},
            "buildings": buildings, "contact": {**CONTACT, "gap": gap, "levels": [1, 1]}}


def rows(records: int = RECORDS, seed: int = SEED, hazards=None, pairs=None) -> list[dict]:
    out = []
    for hazard_name in hazards or HAZARDS:
        for pair_name in pairs or PAIRS:
            case = case_from_dict(case_data(HAZARDS[hazard_name], PAIRS[pair_name]), name=f"{hazard_name}, {pair_name}")
            closed = estimate(case)
            study = simulate(case, records=records, seed=seed)
            mc = study.force_max_mean
            paper = closed.paper.force_expected
            out.append({
                "case": case.name, "regime": closed.accuracy_regime,
                "gap_over_sigma": case.contact.gap / closed.sigma_relative_displacement,
                "monte_carlo": mc, "std_error": study.force_max_std_error,
                "recommended_error": closed.force_expected / mc - 1 if mc > 0 else None,
                "paper_error": paper / mc - 1 if mc > 0 and paper is not None else None,
                "pounding_fraction": study.pounding_fraction, "pounding_probability": closed.pounding_probability,
            })
    return out


def main(records: int = RECORDS, seed: int = SEED, hazards=None, pairs=None, json_output: bool = False) -> None:
    table = rows(records, seed, hazards, pairs)
    if json_output:
        print(json.dumps(table))
        return
    percent = lambda e: "n/a" if e is None else f"{100 * e:+.1f} %"  # noqa: E731
    print(f"Monte Carlo: {records} records a case, seed {seed}; errors are estimate / Monte Carlo - 1.\n")
    print("| case | regime | gap / sigma_X | Monte Carlo E[F_max] (kN) | s.e. | recommended | paper | P(pounding) MC | estimate |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in table:
        relative = "n/a" if r["monte_carlo"] == 0 else f"{100 * r['std_error'] / r['monte_carlo']:.1f} %"
        print(f"| {r['case']} | {r['regime']} | {r['gap_over_sigma']:.2f} | {r['monte_carlo'] / 1e3:.1f} | {relative} | "
              f"{percent(r['recommended_error'])} | {percent(r['paper_error'])} | {r['pounding_fraction']:.3f} | {r['pounding_probability']:.3f} |")
    print("\n| regime | cases | within 10 % | median error | range |\n|---|---|---|---|---|")
    for regime in sorted({r["regime"] for r in table}):
        errors = np.array([r["recommended_error"] for r in table if r["regime"] == regime and r["recommended_error"] is not None])
        if errors.size:
            print(f"| {regime} | {errors.size} | {int(np.sum(np.abs(errors) <= 0.1))} | {100 * np.median(np.abs(errors)):.1f} % | "
                  f"{100 * errors.min():+.0f} % to {100 * errors.max():+.0f} % |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--json", action="store_true")
    arguments = parser.parse_args()
    main(arguments.records, arguments.seed, json_output=arguments.json)
