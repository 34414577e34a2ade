"""Speed of the PSD compatible with a design spectrum (pounding.hazard.compatible_psd.compatible_spectrum).

- one compatible FilterBank for EN 1998-1 type 1, ground C, ag = 0.3 g, 20 s stationary; for ASCE 7-16
  (SDS = 1.0 g, SD1 = 0.6 g, TL = 8 s), 20 s under the Shinozuka-Sato envelope; and for EN 1998-1 type 2
  over 10 s: median of repeated calls after warm-up, against the target of 50 ms;
- beside them, timed in the same process, a baseline: one ``np.fft.rfft`` of 100 records of 4096
  samples (a 100 x 4096 array along its rows), and the ratio.

Run: python3 benchmarks/design_spectrum.py
"""

from __future__ import annotations

import numpy as np
from timing import median_seconds  # noqa: E402 (this folder is on the path)

from pounding.hazard.compatible_psd import compatible_spectrum
from pounding.hazard.design_spectra import ASCE7Spectrum, Eurocode8Spectrum
from pounding.hazard.excitation import ShinozukaSato

TARGET = 0.050  # [s] one compatible bank
G = 9.80665


def main() -> None:
    records = np.random.default_rng(1).standard_normal((100, 4096))
    fft = median_seconds(lambda: np.fft.rfft(records, axis=-1), repeats=200)
    print(f"baseline: one np.fft.rfft of 100 x 4096 samples  {1e3 * fft:7.3f} ms")
    cases = [
        ("EN 1998-1 type 1, C, 0.3 g, 20 s", Eurocode8Spectrum(0.3 * G, "C", 1), 20.0, None),
        ("ASCE 7-16, 1.0 g / 0.6 g, 20 s, envelope", ASCE7Spectrum(1.0 * G, 0.6 * G, 8.0), 20.0, ShinozukaSato()),
        ("EN 1998-1 type 2, B, 0.25 g, 10 s", Eurocode8Spectrum(0.25 * G, "B", 2), 10.0, None),
    ]
    for label, target, duration, envelope in cases:
        seconds = median_seconds(lambda: compatible_spectrum(target, duration, envelope))
        result = compatible_spectrum(target, duration, envelope)
        verdict = "within" if seconds <= TARGET else "OVER"
        print(f"{label:42s} {1e3 * seconds:7.2f} ms ({verdict} {1e3 * TARGET:g} ms; {seconds / fft:.0f} x the baseline); "
              f"{len(result.bank.frequencies)} components, {result.iterations} iterations, "
              f"misfit {100 * result.misfit:.1f} % from {result.periods[0]:g} to {result.periods[-1]:g} s")


if __name__ == "__main__":
    main()
