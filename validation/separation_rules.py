"""The separation rules' expected floor peaks against Monte Carlo: the numbers.

Reproduces the table of ``validation/HISTORY.md`` ("The separation rules"). SRSS,
ABS and DDC combine the expected peak |displacement| u1, u2 of the two contact
floors; how good a rule can be rests on those two numbers. For each case the
buildings are set far apart (no pounding), 300 records (seed 5) give each
floor's mean peak, and two closed forms are set against it:

- Davenport's factor on the stationary sigma (Michaelov's equivalent process
  under an envelope), with twice the upcrossing rate for |x|: the estimate's
  rule until this was measured;
- :func:`pounding.random_vibration.peaks.expected_absolute_peak`: the floor's sigmas from rest
  (or under the envelope) with Vanmarcke's clumps, the estimate's rule now.

Cases: the grid's buildings and excitations (each once, the gap variants
dropped) and every fourth case of a random draw (seed 2030, a draw not used
elsewhere).

    python3 -m validation.separation_rules            # about 1 min on 2 cores
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pounding import simulate
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.random_vibration.peaks import davenport_peak_factor, envelope_variance, equivalent_stationary
from pounding.studies.paper_tables import accuracy_cases, random_cases

from .sizes import first

RECORDS, SEED, APART = 300, 5, 5.0  # records, seed, gap [m] no record reaches


def davenport_peaks(case, response) -> np.ndarray:
    """The former rule: Davenport on the stationary sigma, rate 2 nu (Michaelov under an envelope)."""
    excitation = case.excitation
    sigma_x, sigma_v = np.array(response.sigma_displacement), np.array(response.sigma_velocity)
    rate = sigma_v / (math.pi * sigma_x)
    if excitation.stationary:
        return sigma_x * davenport_peak_factor(rate, excitation.duration)
    times = np.arange(0.0, excitation.duration + 1e-9, 0.1)
    peaks = []
    for sigma, nu in zip(sigma_x, rate):
        variance, duration = equivalent_stationary(envelope_variance(excitation.envelope, times, sigma**2), times)
        peaks.append(math.sqrt(variance) * davenport_peak_factor(nu, duration))
    return np.array(peaks)


def kind(case, pair: LinearizedPair) -> str:
    if not pair.yielding:
        return "elastic"
    if "frames" in case.name or case.name.startswith(("section6", "s6")):
        return "frames (alpha 0.02)"
    return "yielding"


def apart_cases() -> list:
    """The grid's buildings and excitations, each once, and every fourth case of the draw 2030, set far apart."""
    seen, chosen = set(), []
    for case in accuracy_cases() + random_cases(2030)[::4]:
        key = (case.buildings, case.excitation, case.contact.levels)
        if key not in seen:
            seen.add(key)
            chosen.append(case.with_contact(gap=APART))
    return chosen


def main(cases: int | None = None, records: int = RECORDS) -> None:
    """The tables over the first ``cases`` of :func:`apart_cases` (all for None), ``records`` records each."""
    rows = []
    print("| case | kind | floor peaks, Monte Carlo (cm) | Davenport, stationary | from rest, Vanmarcke's clumps |")
    print("|---|---|---|---|---|")
    for case in first(apart_cases(), cases):
        pair = LinearizedPair.of(case)
        result = simulate(case, records=records, seed=SEED)
        if result.impacts.sum():
            continue
        simulated = result.displacement_max.mean(axis=0)
        estimated = estimate(pair)
        before = davenport_peaks(case, estimated.response) / simulated - 1
        now = np.array(estimated.separation_rules["peak_displacement"]) / simulated - 1
        rows.append((kind(case, pair), before, now))
        print(f"| {case.name} | {rows[-1][0]} | {100 * simulated[0]:.2f} / {100 * simulated[1]:.2f} | "
              f"{100 * before[0]:+.1f}% / {100 * before[1]:+.1f}% | {100 * now[0]:+.1f}% / {100 * now[1]:+.1f}% |", flush=True)
    print("\n| pairs | floors | Davenport, stationary: median, range | from rest, Vanmarcke's clumps: median, range |")
    print("|---|---|---|---|")
    for name in ("elastic", "yielding", "frames (alpha 0.02)"):
        chosen = [(b, n) for k, b, n in rows if k == name]
        if chosen:
            before, now = (np.concatenate(column) for column in zip(*chosen))
            print(f"| {name} | {before.size} | {100 * np.median(before):+.1f}%, {100 * before.min():+.1f}% to {100 * before.max():+.1f}% | "
                  f"{100 * np.median(now):+.1f}%, {100 * now.min():+.1f}% to {100 * now.max():+.1f}% |")


if __name__ == "__main__":
    main()
