"""Speed of the spectrum fitted to a suite of records (pounding.hazard.motion_fit.fit_excitation).

- one fit to 20 stationary Kanai-Tajimi records of 20 s at 0.005 s (4001 samples
  each; the strong motion's periodograms, the bins, both least-squares fits):
  median of repeated calls after warm-up, against the target of 200 ms;
- beside it, timed in the same process, a baseline: one ``np.fft.rfft`` of all
  20 records (a 20 x 4001 array along its rows), and the ratio;
- the same fit to 20 records of different steps and lengths (0.01 s x 30 s and
  0.004 s x 15 s), and to 100 records.

Run: python3 benchmarks/motion_fit.py
"""

from __future__ import annotations

import math

import numpy as np
from timing import median_seconds  # noqa: E402 (this folder is on the path)

from pounding.hazard.accelerograms import Accelerogram
from pounding.hazard.excitation import Excitation, KanaiTajimi, ground_accelerations
from pounding.hazard.motion_fit import fit_excitation

TARGET = 0.200  # [s] one fit to 20 records of 20 s at 0.005 s
CUTOFF = 2.0 * math.pi * 25.0  # [rad/s]


def suite(records: int, duration: float = 20.0, time_step: float = 0.005, seed: int = 1) -> list[Accelerogram]:
    excitation = Excitation(KanaiTajimi(0.05, 15.6, 0.6), duration=duration, time_step=time_step, cutoff_frequency=CUTOFF)
    rows = ground_accelerations(excitation, seed, range(records))
    return [Accelerogram(f"r{seed}-{k}", time_step, row) for k, row in enumerate(rows)]


def main() -> None:
    records = suite(20)
    stacked = np.stack([record.acceleration for record in records])
    fit = median_seconds(lambda: fit_excitation(records, CUTOFF))
    fft = median_seconds(lambda: np.fft.rfft(stacked, axis=-1), repeats=200)
    mixed = suite(10, 30.0, 0.01, seed=2) + suite(10, 15.0, 0.004, seed=3)
    mixed_fit = median_seconds(lambda: fit_excitation(mixed, CUTOFF))
    many = suite(100, seed=4)
    many_fit = median_seconds(lambda: fit_excitation(many, CUTOFF), repeats=10)
    fitted = fit_excitation(records, CUTOFF)
    verdict = "within" if fit <= TARGET else "OVER"
    print("fit_excitation, 20 records of 20 s at 0.005 s (Kanai-Tajimi 0.05 m^2/s^3, 15.6 rad/s, 0.6):")
    print(f"  one fit (median of 30)               {1e3 * fit:7.2f} ms   ({verdict} the target of {1e3 * TARGET:g} ms)")
    print(f"  baseline: one np.fft.rfft of all 20  {1e3 * fft:7.3f} ms   (the fit is {fit / fft:.0f} times it)")
    print(f"  fitted: {fitted.to_dict()['spectrum']}, G0 = {fitted.spectrum.G0:.4g} m^2/s^3, "
          f"omega_g = {fitted.spectrum.omega_g:.3g} rad/s, xi_g = {fitted.spectrum.xi_g:.3g}, D = {fitted.duration:.2f} s")
    print(f"fit_excitation, 20 records of mixed steps and lengths {1e3 * mixed_fit:7.2f} ms")
    print(f"fit_excitation, 100 records of 20 s at 0.005 s       {1e3 * many_fit:7.2f} ms")


if __name__ == "__main__":
    main()
