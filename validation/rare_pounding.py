"""Rare pounding (gap beyond sigma_X) and the gap for a target probability: the numbers.

Reproduces the tables of ``validation/HISTORY.md`` ("Rare pounding and the gap
for a target probability"):

1. the recommended estimate against Monte Carlo (300 records, seed 11) at
   gaps of 1.5 and 2.5 sigma_X, for yielding and elastic pairs;
2. the gap ``estimate`` gives for 95 % probability of no pounding, checked
   by simulating 1,000 records (seed 9) at that gap: the fraction that pounds
   should be at most 5 %.

    python3 -m validation.rare_pounding            # about 1.5 min on 2 cores
"""

from __future__ import annotations

import dataclasses

from pounding import load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.studies.paper_tables import accuracy, varied_case

from .sizes import first

RECORDS, SEED = 300, 11
DESIGN_RECORDS, DESIGN_SEED = 1000, 9

YIELDING = [("section5-T2-0.4", 1.0), ("section5-T2-0.6", 1.0), ("section5-T2-0.8", 1.0), ("section6-T2-0.4", 1.0),
            ("section6-T2-0.8", 1.0), ("section5-T2-0.4", 4.0), ("section5-T2-0.8", 0.25)]
ELASTIC = [(1.2, 0.8), (0.6, 0.3), (2.0, 0.5)]
LEVELS = (1.5, 2.5)  # gap / sigma_X


def rare_cases() -> list:
    bases = [varied_case(load_case(name), g0=g0, name=f"{name} G0x{g0:g}") for name, g0 in YIELDING]
    bases += [varied_case(load_case("section5-T2-0.4"), elastic=True, periods=periods, name=f"elastic {periods[0]}/{periods[1]}")
              for periods in ELASTIC]
    cases = []
    for base in bases:
        sigma = estimate(base).sigma_relative_displacement
        cases += [varied_case(base, gap=level * sigma, name=f"{base.name} gap {level} sigma_X") for level in LEVELS]
    return cases


def design_cases() -> list:
    return [
        varied_case(load_case("section5-T2-0.4"), elastic=True, periods=(1.2, 0.8), name="elastic 1.2/0.8"),
        varied_case(load_case("section5-T2-0.4"), elastic=True, name="elastic 1.2/0.4"),
        varied_case(load_case("section5-T2-0.4"), elastic=True, periods=(2.0, 0.5), name="elastic 2.0/0.5"),
        load_case("section5-T2-0.4"), load_case("section5-T2-0.8"), load_case("section6-T2-0.8"),
        varied_case(load_case("section5-T2-0.8"), g0=0.25, name="section5-T2-0.8 G0x0.25"),
    ]


def main(cases: int | None = None, records: int = RECORDS, design_records: int = DESIGN_RECORDS) -> None:
    """Both tables over the first ``cases`` of each (all for None), ``records`` records for the force
    and ``design_records`` at the gap for 95 %."""
    print("| case | Monte Carlo E[F_max] (kN) | s.e. | recommended | P(pounding) MC | P estimate |")
    print("|---|---|---|---|---|---|")
    for row in accuracy(first(rare_cases(), cases), records=records, seed=SEED):
        if row.monte_carlo == 0.0:  # no record pounded: no relative error
            print(f"| {row.case} | 0.0 | - | - | {row.pounding_fraction:.3f} | {row.pounding_probability:.3f} |")
            continue
        print(f"| {row.case} | {row.monte_carlo / 1e3:.1f} | {row.monte_carlo_std_error / row.monte_carlo:.1%} | "
              f"{row.recommended_error:+.1%} | {row.pounding_fraction:.3f} | {row.pounding_probability:.3f} |")
    print()
    print(f"| case | sigma_X (cm) | gap for 95 % (cm) | fraction pounding there, Monte Carlo ({design_records:,} records) |")
    print("|---|---|---|---|")
    for case in first(design_cases(), cases):
        result = estimate(case, target_probability=0.95)
        at_gap = case.with_contact(gap=result.required_gap)
        fraction = simulate(at_gap, records=design_records, seed=DESIGN_SEED).pounding_fraction
        print(f"| {case.name} | {100 * result.sigma_relative_displacement:.2f} | {100 * result.required_gap:.2f} | {fraction:.3f} |")


if __name__ == "__main__":
    main()
