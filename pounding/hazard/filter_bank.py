"""A bank of band-pass filters of independent white noises: the rational
spectrum that stands for a tabulated one (a design spectrum's compatible PSD).

Component k is x_k'' + 2 xi_k omega_k x_k' + omega_k^2 x_k = w_k, output
2 xi_k omega_k x_k', so ``|H_k(omega)|^2`` = (2 xi_k omega_k omega)^2 /
((omega_k^2 - omega^2)^2 + (2 xi_k omega_k omega)^2): 1 at omega_k, zero at
omega = 0, falling as 1/omega^2 above. The ground acceleration is the sum of
the outputs, the w_k independent of two-sided intensities G0 w_k, so

    S_g(omega) = G0 sum_k w_k ``|H_k(omega)|^2``          (docs/theory.md, G27)

and the linear pipeline (Lyapunov, covariance from rest) takes the bank as
one filter with as many noise inputs as components.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.errors import CaseError, finite_number, finite_numbers, quote

__all__ = ["FilterBank"]

COMPONENTS_MAX = 64
"""Most components of a bank (each adds two states to the closed form's linear system)."""


@dataclass(frozen=True)
class FilterBank:
    """Two-sided PSD of ground acceleration as a bank of band-pass filtered white noises (G27).

    Parameters
    ----------
    G0 : float
        Intensity [m^2/s^3]: the PSD is G0 times the weighted sum of the
        components' ``|H_k|^2`` (the weights are dimensionless).
    frequencies : tuple of float
        Centre frequencies omega_k [rad/s], > 0.
    damping : tuple of float
        Damping ratios xi_k [-], > 0 (the half-power band is about 2 xi_k omega_k wide).
    weights : tuple of float
        w_k >= 0 [-], not all zero.
    """

    G0: float
    frequencies: tuple[float, ...]
    damping: tuple[float, ...]
    weights: tuple[float, ...]

    def __post_init__(self):
        object.__setattr__(self, "G0", finite_number("G0", self.G0))
        if not self.G0 >= 0:
            raise CaseError("G0", f"must be >= 0, got {quote(self.G0)}")
        for field in ("frequencies", "damping", "weights"):
            object.__setattr__(self, field, finite_numbers(field, getattr(self, field)))
        count = len(self.frequencies)
        if not 1 <= count <= COMPONENTS_MAX or len(self.damping) != count or len(self.weights) != count:
            raise CaseError("frequencies", f"frequencies, damping and weights must have the same length, 1 to {COMPONENTS_MAX}")
        if not all(0 < w <= 1e6 for w in self.frequencies):
            raise CaseError("frequencies", "must lie in (0, 1e6] rad/s")
        if not all(0 < x <= 100 for x in self.damping):
            raise CaseError("damping", "must lie in (0, 100]")
        if not (all(w >= 0 for w in self.weights) and any(w > 0 for w in self.weights)):
            raise CaseError("weights", "must be >= 0 and not all zero")

    def component_responses(self, omega) -> np.ndarray:
        """``|H_k(omega)|^2``, one row per component [-]."""
        w = np.asarray(omega, dtype=float)[None, ...]
        centre = np.asarray(self.frequencies).reshape((-1,) + (1,) * (w.ndim - 1))
        xi = np.asarray(self.damping).reshape(centre.shape)
        band = np.square(2.0 * xi * centre * w)
        return band / (np.square(centre**2 - np.square(w)) + band)

    def psd(self, omega):
        """Two-sided PSD S_g(omega) [m^2/s^3], G27."""
        weights = np.asarray(self.weights).reshape((-1,) + (1,) * np.ndim(omega))
        return self.G0 * np.sum(weights * self.component_responses(omega), axis=0)

    def variance(self) -> float:
        """Variance of ground acceleration [m^2/s^4]: G0 sum_k w_k 2 pi xi_k omega_k (each
        band-pass output of unit-intensity noise has variance 2 pi xi_k omega_k)."""
        return self.G0 * sum(2.0 * math.pi * x * w * c for x, w, c in zip(self.damping, self.frequencies, self.weights))
