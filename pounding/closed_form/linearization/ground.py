"""The ground filter: the Kanai-Tajimi (Eq. 7) or Clough-Penzien spectrum as
a linear filter of white noise."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pounding.hazard.excitation import CloughPenzien, KanaiTajimi
from pounding.hazard.filter_bank import FilterBank

# --- the ground filter --------------------------------------------------------


@dataclass(frozen=True, eq=False)
class GroundFilter:
    """Linear filter turning white noise into ground acceleration.

    x_f' = matrix x_f + noise_input w,  a_g = output . x_f, with w a vector
    of independent white noises of two-sided intensity ``G0`` [m^2/s^3]; the
    squared norm of output . (i omega - matrix)^-1 noise_input times G0 is the
    spectrum's PSD. ``noise_input`` has one column per noise.
    """

    matrix: np.ndarray
    noise_input: np.ndarray
    output: np.ndarray
    G0: float

    @property
    def size(self) -> int:
        return self.matrix.shape[0]


def ground_filter(spectrum: KanaiTajimi | FilterBank) -> GroundFilter:
    """State-space filter of a Kanai-Tajimi (Eq. 7), Clough-Penzien or filter-bank (G27) spectrum.

    Kanai-Tajimi: x'' + 2 xi_g omega_g x' + omega_g^2 x = w and
    a_g = omega_g^2 x + 2 xi_g omega_g x'. Clough-Penzien adds
    y'' + 2 xi_f omega_f y' + omega_f^2 y = a_KT and a_g = a_KT - omega_f^2 y - 2 xi_f omega_f y'.
    """
    if isinstance(spectrum, FilterBank):
        return _bank_filter(spectrum)
    wg, xg = spectrum.omega_g, spectrum.xi_g
    kt_output = np.array([wg * wg, 2.0 * xg * wg])
    kt_matrix = np.array([[0.0, 1.0], [-wg * wg, -2.0 * xg * wg]])
    if not isinstance(spectrum, CloughPenzien):
        return GroundFilter(kt_matrix, np.array([[0.0], [1.0]]), kt_output, float(spectrum.G0))
    wf, xf = spectrum.omega_f, spectrum.xi_f
    matrix = np.zeros((4, 4))
    matrix[:2, :2] = kt_matrix
    matrix[2, 3] = 1.0
    matrix[3, :2] = kt_output
    matrix[3, 2:] = [-wf * wf, -2.0 * xf * wf]
    output = np.concatenate([kt_output, [-wf * wf, -2.0 * xf * wf]])
    return GroundFilter(matrix, np.array([[0.0], [1.0], [0.0], [0.0]]), output, float(spectrum.G0))


def _bank_filter(bank: FilterBank) -> GroundFilter:
    """Block-diagonal filter of a bank (G27): component k's states (x_k, x_k'),
    driven by its own noise scaled by sqrt(w_k), output 2 xi_k omega_k x_k'."""
    count = len(bank.frequencies)
    matrix = np.zeros((2 * count, 2 * count))
    noise_input = np.zeros((2 * count, count))
    output = np.zeros(2 * count)
    for k, (w, x, weight) in enumerate(zip(bank.frequencies, bank.damping, bank.weights)):
        matrix[2 * k, 2 * k + 1] = 1.0
        matrix[2 * k + 1, 2 * k : 2 * k + 2] = [-w * w, -2.0 * x * w]
        noise_input[2 * k + 1, k] = np.sqrt(weight)
        output[2 * k + 1] = 2.0 * x * w
    return GroundFilter(matrix, noise_input, output, float(bank.G0))
