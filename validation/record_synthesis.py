"""The records' lowest frequencies, and the Clough-Penzien spectrum: the numbers.

Reproduces the two tables of docs/estimator.md, "The records' lowest
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

    python3 docs/record_synthesis.py                  # about 3.5 min on 2 cores
    python3 docs/record_synthesis.py --design-gaps    # the third table alone
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from pounding import load_case, simulate  # noqa: E402
from pounding.estimator import estimate  # noqa: E402
from pounding.excitation import CloughPenzien  # noqa: E402
from pounding.validation import _vary, accuracy_cases  # noqa: E402

FACTORS = (1, 2, 4, 8, 16)
FACTOR_CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.8", "elastic 1.2/0.4 gap12cm",
                "s5-T2-0.4 G0x0.25 gap5cm", "s5-T2-0.8 G0x0.25 gap3.4cm")
CLOUGH_PENZIEN_CASES = ("section5-T2-0.4", "section5-T2-0.6", "section5-T2-0.8", "section5-T2-0.4-nonstationary",
                        "section6-T2-0.4", "section6-T2-0.8", "s5-T2-0.4 G0x4", "s5-T2-0.4 G0x4pi2", "s5-T2-0.4 gap0",
                        "T1 1.2 T2 0.2", "T1 1.2 T2 2.0", "s6-T2-0.6 G0x10 e0.4", "mdof-3+2-floor2",
                        "elastic 1.2/0.4 gap6cm", "elastic 1.2/0.4 gap10cm", "elastic 0.5/0.3 gap3cm",
                        "s5-T2-0.4 G0x0.25 gap5cm", "s5-T2-0.8 G0x0.25 gap3.4cm")


def with_excitation(case, **changes):
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, **changes))


def clough_penzien(case):
    s = case.excitation.spectrum
    return with_excitation(case, spectrum=CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6))


def main() -> None:
    cases = {case.name: case for case in accuracy_cases()}
    print("| case | estimate (kN) | " + " | ".join(f"factor {f}: E[F_max] (kN), P" for f in FACTORS) + " |")
    print("|---|---|" + "---|" * len(FACTORS))
    for name in FACTOR_CASES:
        case = cases[name]
        cells = []
        for factor in FACTORS:
            result = simulate(with_excitation(case, synthesis_factor=factor), records=2000, seed=11)
            cells.append(f"{result.force_max_mean / 1e3:.1f} ± {result.force_max_std_error / 1e3:.1f}, {result.pounding_fraction:.3f}")
        print(f"| {name} | {estimate(case).force_expected / 1e3:.1f} | " + " | ".join(cells) + " |")

    print("\n| case, Clough-Penzien | gap / sigma_X | Monte Carlo E[F_max] (kN) | s.e. | recommended | P(pounding) MC | P estimate |")
    print("|---|---|---|---|---|---|---|")
    for name in CLOUGH_PENZIEN_CASES:
        case = clough_penzien(cases[name])
        result = estimate(case)
        simulated = simulate(case, records=600, seed=11)
        mean = simulated.force_max_mean
        print(f"| {name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {mean / 1e3:.1f} "
              f"| {simulated.force_max_std_error / mean:.1%} | {result.force_expected / mean - 1:+.1%} "
              f"| {simulated.pounding_fraction:.3f} | {result.pounding_probability:.3f} |")


DESIGN_GAP_CASES = (("section5-T2-0.4", False), ("section5-T2-0.8", False), ("section6-T2-0.8", False), ("section5-T2-0.4", True))


def design_gaps() -> None:
    """The gap ``estimate`` gives for 95 % no pounding under Clough-Penzien, checked on 1,000 records."""
    print("\n| case, Clough-Penzien | sigma_X (cm) | gap for 95 % (cm) | fraction pounding there, Monte Carlo (1,000 records) |")
    print("|---|---|---|---|")
    for name, elastic in DESIGN_GAP_CASES:
        case = clough_penzien(_vary(load_case(name), elastic=True) if elastic else load_case(name))
        result = estimate(case, target_probability=0.95)
        at_gap = dataclasses.replace(case, contact=dataclasses.replace(case.contact, gap=result.required_gap))
        fraction = simulate(at_gap, records=1000, seed=9).pounding_fraction
        label = "elastic 1.2/0.4" if elastic else name
        print(f"| {label} | {100 * result.sigma_relative_displacement:.2f} | {100 * result.required_gap:.2f} | {fraction:.3f} |", flush=True)


if __name__ == "__main__":
    if "--design-gaps" in sys.argv:
        design_gaps()
    else:
        main()
        design_gaps()
