"""Where the recommended estimate's error sits: the peak force of an impact
of a given speed, or the largest approach speed of the record.

For each case of the accuracy grid (300 records, seed 11), with F(v) the
estimator's peak force of an impact at speed v against the buildings'
braking force at the gap (``Estimate.opposing_force``):

- impact force: the simulated E[F_max] against the mean over records of
  F(V_max), V_max each record's largest simulated approach speed. It tests the
  impact model alone, on the simulated speeds;
- largest speed: the estimate against that same mean. It tests the model of
  the largest approach speed (crossings of the gap, mirror returns, clumps);
- the two multiply to the estimate's error against Monte Carlo;
- the impact-force column without the braking force, for free masses, shows
  what the braking force corrects.

    python3 docs/error_decomposition.py       # about 1 min on 2 cores
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from pounding import simulate  # noqa: E402
from pounding.contact import impact_peak_force  # noqa: E402
from pounding.estimator import estimate  # noqa: E402
from pounding.validation import accuracy_cases  # noqa: E402


def main() -> None:
    print("| case | gap / sigma_X | bandwidth q | impact force, free masses | impact force | largest speed | estimate |")
    print("|---|---|---|---|---|---|---|")
    for case in accuracy_cases():
        result = estimate(case)
        simulated = simulate(case, records=300, seed=11)
        speeds = simulated.impact_velocity_max
        braked = impact_peak_force(case.contact, speeds, case.reduced_mass, result.opposing_force).mean()
        free = impact_peak_force(case.contact, speeds, case.reduced_mass).mean()
        mean = simulated.force_max_mean
        print(
            f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {result.crossings.bandwidth:.2f} "
            f"| {free / mean - 1:+.1%} | {braked / mean - 1:+.1%} | {result.force_expected / braked - 1:+.1%} "
            f"| {result.force_expected / mean - 1:+.1%} |"
        )
    print("\nimpact force: F(V_max) of the simulated speeds / simulated E[F_max] - 1; largest speed: estimate / that - 1.")


if __name__ == "__main__":
    main()
