"""Speed of the distribution of F_max, fragility curves and force spectra (issue 23), printed as figures,
each beside a baseline timed in the same process:

- the quantiles and the probability of exceeding a capacity on top of an estimate (G31 is built by the
  estimate; reading it): target 1 ms;
- a closed-form fragility curve of 20 PGAs on the Section 5 case, against one estimate: target 100 ms;
- a closed-form force spectrum of 30 periods of building 1, against one estimate: target 300 ms;
- the Monte Carlo side of a fragility point (100 records, serial, on the sweep engine's chunks: one thread)
  against simulate of the same 100 records on one thread: the engine's overhead (files, exact sums).

Run: python3 benchmarks/fragility.py
"""

from __future__ import annotations

import tempfile

import numpy as np
from timing import median_seconds  # noqa: E402 (this folder is on the path)

from pounding import Settings, estimate, load_case, simulate
from pounding.case.scaling import PeakGroundAcceleration
from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.force_spectrum import force_spectrum
from pounding.studies.fragility import fragility_curve
from pounding.units import STANDARD_GRAVITY

CASE = "section5-T2-0.4"


def main() -> None:
    case = load_case(CASE)
    one = median_seconds(lambda: estimate(case))
    print(f"one estimate (baseline)                 {1e3 * one:7.2f} ms")

    def read_distribution(result):
        distribution = result.force_max_distribution
        return [distribution.quantile(p) for p in (0.5, 0.84, 0.95)], result.probability_exceeding(3e5)

    quantiles = median_seconds(read_distribution, setup=lambda: estimate(case), repeats=200)
    print(f"quantiles and P(F_max > C), added       {1e3 * quantiles:7.3f} ms   (target 1 ms; {quantiles / one:.3f} of an estimate)")

    pga = np.linspace(0.05, 0.6, 20) * STANDARD_GRAVITY
    curve = median_seconds(lambda: fragility_curve(case, 3e5, pga), repeats=10)
    print(f"fragility curve, 20 PGAs, closed form   {1e3 * curve:7.1f} ms   (target 100 ms; {curve / one:.1f} estimates)")

    periods = np.linspace(0.2, 2.0, 30)
    spectrum = median_seconds(lambda: force_spectrum(case, periods, period2=0.4), repeats=5)
    print(f"force spectrum, 30 periods, closed form {1e3 * spectrum:7.1f} ms   (target 300 ms; {spectrum / one:.1f} estimates)")

    scaled = PeakGroundAcceleration(case).case_at(0.3 * STANDARD_GRAVITY)
    direct = median_seconds(lambda: simulate(scaled, records=100, seed=1, settings=Settings(workers=1)), repeats=3)

    def engine():
        with tempfile.TemporaryDirectory() as folder:
            fragility_curve(CASE, 3e5, np.array([0.3, 0.31]) * STANDARD_GRAVITY, MonteCarloPlan(100, 1, folder, "serial"))

    on_engine = median_seconds(engine, repeats=3) / 2
    print(f"Monte Carlo, 100 records a PGA          {on_engine:7.2f} s    (simulate of the same records, one thread, {direct:.2f} s; ratio {on_engine / direct:.2f})")


if __name__ == "__main__":
    main()
