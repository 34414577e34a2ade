"""The peak and RMS ground acceleration of an excitation's records, and G0
for a target peak (docs/hazard.md, G29-G30).

The records carry nothing above the cutoff, so the spectral moments are
those of the PSD cut there (a Kanai-Tajimi acceleration has no finite second
moment otherwise), on the records' own synthesis grid:

    lambda_k = sum_j w_j^k G(w_j) dw,  G = 2 S_g, 0 < w_j <= cutoff;
    nu_0 = sqrt(lambda_2 / lambda_0) / (2 pi),  delta = sqrt(1 - lambda_1^2 / (lambda_0 lambda_2)).

The expected peak of |a| over the duration is Vanmarcke's (1975) for a
double barrier, the standard deviation sigma(t) = A(t) sigma following the
envelope A:

    P(max |a| <= u) = exp(-int_0^T 2 nu_0 (1 - exp(-sqrt(pi/2) delta^1.2 r)) / (exp(r^2 / 2) - 1) dt),  r = u / sigma(t)
    E[PGA] = int_0^inf (1 - P(max |a| <= u)) du                                                        (G29)

E[PGA] scales with sqrt(G0): G0 for a target peak is one division (G30).
"""

from __future__ import annotations

import math

import numpy as np

from .errors import CaseError
from .excitation import Excitation

__all__ = ["expected_peak_ground_acceleration", "intensity_for_peak_ground_acceleration", "rms_acceleration"]

_LEVELS = np.linspace(0.0, 12.0, 601)[1:]  # u / sigma_max of the quadrature of G29
_TIMES = 200  # points of the envelope's time integral


def _moments(excitation: Excitation) -> tuple[float, float, float]:
    omega = excitation.synthesis_frequencies()
    weights = 2.0 * excitation.spectrum.psd(omega) * omega[1]
    weights[(omega <= 0.0) | (omega > excitation.cutoff_frequency)] = 0.0
    return tuple(float(np.sum(omega**k * weights)) for k in range(3))


def rms_acceleration(excitation: Excitation) -> float:
    """RMS ground acceleration of the stationary records below the cutoff [m/s^2] (at the envelope's peak)."""
    return math.sqrt(_moments(excitation)[0])


def expected_peak_ground_acceleration(excitation: Excitation) -> float:
    """E[max |a_g|] of the records over their duration [m/s^2], G29."""
    l0, l1, l2 = _moments(excitation)
    if not (l0 > 0.0 and l2 > 0.0):
        return 0.0
    sigma = math.sqrt(l0)
    nu0 = math.sqrt(l2 / l0) / (2.0 * math.pi)
    delta = math.sqrt(max(1.0 - l1 * l1 / (l0 * l2), 0.0))
    times = np.linspace(0.0, excitation.duration, _TIMES)
    scale = excitation.envelope(times) if excitation.envelope is not None else np.ones(_TIMES)
    dt = np.full(_TIMES, excitation.duration / (_TIMES - 1))
    dt[[0, -1]] *= 0.5
    levels = _LEVELS * float(np.max(scale))
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        r = levels[:, None] / np.maximum(scale[None, :], 1e-300)
        rate = 2.0 * nu0 * -np.expm1(-math.sqrt(math.pi / 2.0) * delta**1.2 * r) / np.expm1(0.5 * r * r)
    rate = np.nan_to_num(rate, nan=0.0, posinf=0.0)
    below = np.exp(-(rate @ dt))
    step = levels[1] - levels[0]
    return float(sigma * (step * np.sum(1.0 - below) + levels[0] * 1.0))


def intensity_for_peak_ground_acceleration(excitation: Excitation, pga: float) -> float:
    """G0 [m^2/s^3] that gives ``excitation``'s records an expected PGA of ``pga`` [m/s^2] (G30)."""
    unit = expected_peak_ground_acceleration(excitation)
    if not (unit > 0.0 and math.isfinite(unit)):
        raise CaseError("pga", "the spectrum carries nothing below the records' cutoff: no G0 gives a peak")
    G0 = excitation.spectrum.G0 * (pga / unit) ** 2
    if not (math.isfinite(G0) and G0 > 0.0):
        raise CaseError("pga", f"{pga:g} m/s^2 needs a G0 beyond the range of numbers")
    return G0
