"""The records' lowest frequencies, and the Clough-Penzien spectrum: the numbers.

Reproduces the tables of validation/HISTORY.md, "The records' lowest
frequencies":

1. Monte Carlo (2,000 records, seed 11) against the synthesis factor of the
   records (``Excitation.synthesis_factor``: 1 is the default, records
   periodic over about their duration; 16 keeps the Kanai-Tajimi spectrum
   down to 1/16 of that frequency), beside the recommended estimate;
2. the recommended estimate against Monte Carlo (600 records, seed 11) with
   the grid's cases driven by a Clough-Penzien spectrum (the same soil, a
   high-pass at omega_f = 2 rad/s, xi_f = 0.6): no ground motion at low
   frequency;
3. under that spectrum, the gap ``estimate`` gives for 95 % probability of no
   pounding, checked by simulating 1,000 records (seed 9) at that gap.

    python3 -m validation.record_synthesis                  # about 3.5 min on 2 cores
    python3 -m validation.record_synthesis --design-gaps    # the third table alone
"""

from __future__ import annotations

import argparse
import dataclasses

from pounding import load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.hazard.excitation import CloughPenzien
from pounding.studies.paper_tables import accuracy_cases, varied_case

from .sizes import first

FACTORS = (1, 2, 4, 8, 16)
FACTOR_CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.8", "elastic 1.2/0.4 gap12cm",
                "s5-T2-0.4 G0x0.25 gap5cm", "s5-T2-0.8 G0x0.25 gap3.4cm")
CLOUGH_PENZIEN_CASES = ("section5-T2-0.4", "section5-T2-0.6", "section5-T2-0.8", "section5-T2-0.4-nonstationary",
                        "section6-T2-0.4", "section6-T2-0.8", "s5-T2-0.4 G0x4", "s5-T2-0.4 G0x4pi2", "s5-T2-0.4 gap0",
                        "T1 1.2 T2 0.2", "T1 1.2 T2 2.0", "s6-T2-0.6 G0x10 e0.4", "mdof-3+2-floor2",
                        "elastic 1.2/0.4 gap6cm", "elastic 1.2/0.4 gap10cm", "elastic 0.5/0.3 gap3cm",
                        "s5-T2-0.4 G0x0.25 gap5cm", "s5-T2-0.8 G0x0.25 gap3.4cm")
FACTOR_RECORDS, CLOUGH_PENZIEN_RECORDS, SEED = 2000, 600, 11
DESIGN_RECORDS, DESIGN_SEED = 1000, 9


def with_excitation(case, **changes):
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, **changes))


def clough_penzien(case):
    s = case.excitation.spectrum
    return with_excitation(case, spectrum=CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6))


def clough_penzien_cases() -> list:
    """The grid's cases of :data:`CLOUGH_PENZIEN_CASES` driven by the Clough-Penzien spectrum, named as in the grid."""
    cases = {case.name: case for case in accuracy_cases()}
    return [clough_penzien(cases[name]) for name in CLOUGH_PENZIEN_CASES]


DESIGN_GAP_CASES = (("section5-T2-0.4", False), ("section5-T2-0.8", False), ("section6-T2-0.8", False), ("section5-T2-0.4", True))


def design_gap_cases() -> list[tuple[str, object]]:
    """(label, case) of :data:`DESIGN_GAP_CASES` under the Clough-Penzien spectrum (True: made elastic)."""
    return [("elastic 1.2/0.4" if elastic else name, clough_penzien(varied_case(load_case(name), elastic=True) if elastic else load_case(name)))
            for name, elastic in DESIGN_GAP_CASES]


def design_gap_fraction(case, records: int = DESIGN_RECORDS, target: float = 0.95):
    """The estimate of ``case`` for ``target`` and the fraction of ``records`` simulated records (seed 9)
    that pound at the gap it gives for ``target``."""
    result = estimate(case, target_probability=target)
    at_gap = case.with_contact(gap=result.required_gap)
    return result, simulate(at_gap, records=records, seed=DESIGN_SEED).pounding_fraction


def synthesis_tables(cases: int | None = None, factor_records: int = FACTOR_RECORDS,
                     clough_penzien_records: int = CLOUGH_PENZIEN_RECORDS) -> None:
    """The first two tables over the first ``cases`` of each (all for None)."""
    grid = {case.name: case for case in accuracy_cases()}
    print("| case | estimate (kN) | " + " | ".join(f"factor {f}: E[F_max] (kN), P" for f in FACTORS) + " |")
    print("|---|---|" + "---|" * len(FACTORS))
    for name in first(FACTOR_CASES, cases):
        case = grid[name]
        cells = []
        for factor in FACTORS:
            result = simulate(with_excitation(case, synthesis_factor=factor), records=factor_records, seed=SEED)
            cells.append(f"{result.force_max_mean / 1e3:.1f} ± {result.force_max_std_error / 1e3:.1f}, {result.pounding_fraction:.3f}")
        print(f"| {name} | {estimate(case).force_expected / 1e3:.1f} | " + " | ".join(cells) + " |")

    print("\n| case, Clough-Penzien | gap / sigma_X | Monte Carlo E[F_max] (kN) | s.e. | recommended | P(pounding) MC | P estimate |")
    print("|---|---|---|---|---|---|---|")
    for case in first(clough_penzien_cases(), cases):
        result = estimate(case)
        simulated = simulate(case, records=clough_penzien_records, seed=SEED)
        mean = simulated.force_max_mean
        if mean == 0.0:  # no record pounded: no relative error
            print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | 0.0 | - | - "
                  f"| {simulated.pounding_fraction:.3f} | {result.pounding_probability:.3f} |")
            continue
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {mean / 1e3:.1f} "
              f"| {simulated.force_max_std_error / mean:.1%} | {result.force_expected / mean - 1:+.1%} "
              f"| {simulated.pounding_fraction:.3f} | {result.pounding_probability:.3f} |")


def design_gaps(cases: int | None = None, records: int = DESIGN_RECORDS) -> None:
    """The gap ``estimate`` gives for 95 % no pounding under Clough-Penzien, checked on ``records`` records
    (the first ``cases`` of :data:`DESIGN_GAP_CASES`, all for None)."""
    print(f"\n| case, Clough-Penzien | sigma_X (cm) | gap for 95 % (cm) | fraction pounding there, Monte Carlo ({records:,} records) |")
    print("|---|---|---|---|")
    for label, case in first(design_gap_cases(), cases):
        result, fraction = design_gap_fraction(case, records)
        print(f"| {label} | {100 * result.sigma_relative_displacement:.2f} | {100 * result.required_gap:.2f} | {fraction:.3f} |", flush=True)


def main(design_gaps_only: bool = False, cases: int | None = None, factor_records: int = FACTOR_RECORDS,
         clough_penzien_records: int = CLOUGH_PENZIEN_RECORDS, design_records: int = DESIGN_RECORDS) -> None:
    """The three tables (or the third alone) over the first ``cases`` of each (all for None)."""
    if not design_gaps_only:
        synthesis_tables(cases, factor_records, clough_penzien_records)
    design_gaps(cases, design_records)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--design-gaps", action="store_true", help="the third table alone")
    main(parser.parse_args().design_gaps)
