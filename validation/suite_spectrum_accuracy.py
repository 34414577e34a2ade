"""The closed form of a recorded suite against the Monte Carlo over the same records: the development suites
of docs/hazard.md S1-S8 (docs/accuracy.md, "Recorded motions").

Six suites, each drawn here with its own seed (none from validation's out-of-sample generators): stationary
Kanai-Tajimi records of the paper's soil; the same records low-passed at 10 Hz (4th-order Butterworth); the
same decimated to 0.02 s and to 0.1 s (scipy.signal.decimate, which low-passes first); a bimodal suite (two
Kanai-Tajimi soils, 6 and 35 rad/s); and a drifting-frequency suite (30 rad/s sliding to 8 rad/s under the
Shinozuka-Sato envelope). Every suite is scaled to the Kanai-Tajimi suite's mean PGA. For each suite and pair:
the fit quality (S8), and E[F_max] by the closed form on the suite's bank with its envelope (S1-S5, the
default), on the bank stationary over the mean significant duration, and on the Kanai-Tajimi / Clough-Penzien
fit of R1-R6 (before), each over the Monte Carlo mean of the same records.

With ``--gap``: the closed form's gap for 95 % no pounding over the Monte Carlo design gap of the same records
(the 95th percentile of the free relative motion's peak, ``simulate --design-gap``), for the yielding pairs;
the range over them is ``extreme_inputs.recorded_suite_gap`` of pounding/data/accuracy.json.

    python3 -m validation.suite_spectrum_accuracy                 # 200 records a suite, about 1 min on 2 cores
    python3 -m validation.suite_spectrum_accuracy --gap           # the gap for 95 %, about 1 min more
"""

from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np

from pounding import design_gap, load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.hazard.accelerograms import Accelerogram
from pounding.hazard.excitation import Excitation, KanaiTajimi, ShinozukaSato, ground_accelerations
from pounding.hazard.sources import RecordedMotions
from pounding.hazard.suite_spectrum import fit_suite_spectrum

SUITES = ("kanai-tajimi", "low-passed 10 Hz", "sampled 0.02 s", "sampled 0.1 s", "bimodal", "drifting")
PAIRS = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.6")
RECORDS, SEED, DURATION, STEP = 200, 31, 20.0, 0.005


def _draw(spectrum, records: int, seed: int, envelope=None) -> np.ndarray:
    return ground_accelerations(Excitation(spectrum, DURATION, envelope, time_step=STEP), seed, range(records))


def suite_records(name: str, records: int = RECORDS, seed: int = SEED) -> list[Accelerogram]:
    """The suite ``name`` of :data:`SUITES`, unscaled."""
    from scipy import signal

    reference = load_case(PAIRS[0]).excitation.spectrum  # the paper's soil, SI
    base = _draw(reference, records, seed)
    step = STEP
    if name == "low-passed 10 Hz":
        base = signal.sosfilt(signal.butter(4, 10.0, fs=1.0 / STEP, output="sos"), base, axis=1)
    elif name == "sampled 0.02 s":
        base, step = signal.decimate(base, 4, axis=1), 0.02
    elif name == "sampled 0.1 s":
        base, step = signal.decimate(signal.decimate(base, 4, axis=1), 5, axis=1), 0.1
    elif name == "bimodal":
        base = (_draw(KanaiTajimi(reference.G0, 6.0, 0.1), records, seed + 1)
                + _draw(KanaiTajimi(reference.G0, 35.0, 0.25), records, seed + 2))
    elif name == "drifting":
        envelope = ShinozukaSato()
        high = _draw(KanaiTajimi(reference.G0, 30.0, 0.3), records, seed + 3, envelope)
        low = _draw(KanaiTajimi(reference.G0, 8.0, 0.3), records, seed + 4, envelope)
        share = np.linspace(0.0, 1.0, base.shape[1])
        base = np.sqrt(1.0 - share) * high + np.sqrt(share) * low
    return [Accelerogram(f"{name}/{k}", step, row) for k, row in enumerate(base)]


def _scaled(records, pga: float) -> list[Accelerogram]:
    factor = pga / np.mean([record.peak for record in records])
    return [record.scaled(factor) for record in records]


def _case(pair: str, motions: RecordedMotions, excitation=None):
    return dataclasses.replace(load_case(pair), excitation=excitation or motions.excitation(), hazard=motions)


def main(records: int = RECORDS, suites=SUITES, pairs=PAIRS, seed: int = SEED) -> list[dict]:
    reference = None
    rows = []
    print("| suite | pair | Sa ratio at T1, T2 | worst Sa ratio 0.5T-2T | PGA ratio | MC E[F_max] [kN] | "
          "bank + envelope | bank, stationary | Kanai-Tajimi fit |\n|---|---|---|---|---|---|---|---|---|")
    for name in suites:
        raw = suite_records(name, records, seed)
        if reference is None:
            reference = np.mean([record.peak for record in suite_records(SUITES[0], records, seed)])
        suite = _scaled(raw, reference)
        step = max(record.time_step for record in suite)
        motions = RecordedMotions.fit(suite, min(2 * math.pi * 25.0, 0.8 * math.pi / step))
        stationary = fit_suite_spectrum(suite, motions.suite.requested_cutoff, modulated=False).excitation()
        old = Excitation(motions.fitted.spectrum, motions.fitted.duration, None, time_step=step,
                         cutoff_frequency=motions.suite.requested_cutoff)
        for pair in pairs:
            case = _case(pair, motions)
            periods = tuple(float(b.periods[0]) for b in case.buildings)
            quality = motions.fit_quality(periods)
            exact = simulate(case).force_max_mean
            forces = [estimate(_case(pair, motions, excitation)).force_expected
                      for excitation in (None, stationary, old)]
            worst = max(quality.ratios, key=lambda r: abs(math.log(r)))
            row = {"suite": name, "pair": pair, "building_ratios": quality.building_ratios, "worst": worst,
                   "pga_ratio": quality.pga_ratio, "monte_carlo": exact, "closed_form": [f / exact for f in forces]}
            rows.append(row)
            print(f"| {name} | {pair} | {', '.join(f'{r:.3f}' for r in quality.building_ratios)} | {worst:.3f} | "
                  f"{quality.pga_ratio:.3f} | {exact / 1e3:.4g} | " + " | ".join(f"{f / exact:.3f}" for f in forces) + " |")
    return rows


def gaps(records: int = RECORDS, suites=SUITES, pairs=PAIRS, seed: int = SEED) -> list[float]:
    """The closed form's gap for 95 % over the Monte Carlo design gap of the same records, minus 1, per suite and
    pair (printed as a table)."""
    reference = np.mean([record.peak for record in suite_records(SUITES[0], records, seed)])
    errors = []
    print("| suite | pair | Monte Carlo design gap [m] | closed form [m] | error |\n|---|---|---|---|---|")
    for name in suites:
        suite = _scaled(suite_records(name, records, seed), reference)
        step = max(record.time_step for record in suite)
        motions = RecordedMotions.fit(suite, min(2 * math.pi * 25.0, 0.8 * math.pi / step))
        for pair in pairs:
            case = _case(pair, motions)
            exact = design_gap(case, 0.95).gap
            closed = estimate(case, target_probability=0.95).required_gap
            errors.append(closed / exact - 1.0)
            print(f"| {name} | {pair} | {exact:.4g} | {closed:.4g} | {errors[-1]:+.1%} |")
    print(f"\nrange {min(errors):+.1%} to {max(errors):+.1%} over {len(errors)} suite-pair cases")
    return errors


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--gap", action="store_true", help="the gap for 95 %% against the Monte Carlo design gap")
    arguments = parser.parse_args()
    if arguments.gap:
        gaps(arguments.records, seed=arguments.seed)
    else:
        main(arguments.records, seed=arguments.seed)
