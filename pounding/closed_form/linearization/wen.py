"""Eq. 20-21: the equivalent linear coefficients c_e and k_e of a Bouc-Wen
storey from the Gaussian statistics of its drift velocity and hysteretic
displacement (Wen 1980, Atalik & Utku 1976), with the printing errors of
Eq. 21 corrected (docs/errata.md, E5 and E6).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import beta as beta_function
from scipy.special import betainc, gamma

# --- Eq. 20-21: the equivalent linear coefficients ---------------------------


def wen_constants(n):
    """Constants of Eq. 21 that depend on n only: E[r^n] of the Rayleigh
    radius split as in Wen (1980), and B(1/2, (n+1)/2) of I_s."""
    n = np.asarray(n, dtype=float)
    root = 2.0 ** (0.5 * n)
    a = root * gamma(0.5 * n + 1.0) / math.pi
    b = root * gamma(0.5 * (n + 1.0)) / math.sqrt(math.pi)
    return n, a, b, beta_function(0.5, 0.5 * (n + 1.0))


def _wen_integral(rho, n, beta_half):
    """I_s = 2 int_l^(pi/2) sin^n(theta) d theta with l = arccos(rho) [-] (Eq. 21).

    With s = cos(theta) it is 2 int_0^rho (1 - s^2)^((n-1)/2) ds, an odd function
    of rho: sign(rho) B(1/2, (n+1)/2) I_(rho^2)(1/2, (n+1)/2), with I the
    regularized incomplete beta function and ``beta_half`` = B(1/2, (n+1)/2).
    """
    return np.sign(rho) * beta_half * betainc(0.5, 0.5 * (n + 1.0), rho * rho)


def _wen_terms(sigma_velocity, sigma_z, rho, constants):
    """(F1, F2, F3, F4) of Eq. 21 with the constants of :func:`wen_constants`."""
    n, a, b, beta_half = constants
    i_s = _wen_integral(rho, n, beta_half)
    sigma_z_n1 = sigma_z ** (n - 1.0)
    sigma_z_n = sigma_z_n1 * sigma_z
    f1 = a * sigma_z_n * i_s
    f2 = b * sigma_z_n
    f3 = n * a * sigma_velocity * sigma_z_n1 * (2.0 * (1.0 - rho * rho) ** (0.5 * (n + 1.0)) / n + rho * i_s)
    f4 = n * b * rho * sigma_velocity * sigma_z_n1
    return f1, f2, f3, f4


def wen_expectations(sigma_velocity, sigma_z, rho, n):
    """Gaussian expectations F1..F4 of the Bouc-Wen law, Eq. 21 (corrected).

    For a zero-mean Gaussian pair (udot, z) with standard deviations
    ``sigma_velocity``, ``sigma_z`` and correlation ``rho``:

    - F1 = E[sgn(udot) ``|z|^(n-1)`` z]
    - F2 = E[``|z|^n``]
    - F3 = n E[``|udot|`` ``|z|^(n-1)``]
    - F4 = n E[udot ``|z|^(n-1)`` sgn(z)]

    so that E[d zdot/d udot] = A - beta F1 - gamma F2 and
    E[d zdot/d z] = -beta F3 - gamma F4 (Eq. 20). With polar coordinates of
    the standardized pair, E[r^n] = 2^(n/2) Gamma(n/2 + 1) and the angular
    averages give I_s / pi and the other factors of Eq. 21.

    Two printing errors of Eq. 21 are corrected here. F3 and F4 scale with the
    standard deviation of the drift *velocity*, not of the drift: as printed
    k_e would have the wrong dimensions (docs/errata.md, E5). The angle of I_s is
    l = arccos(rho); the printed atan(sqrt(1 - rho^2) / rho) takes the wrong
    branch for rho < 0 and flips the sign of I_s there (docs/errata.md, E6).

    Parameters
    ----------
    sigma_velocity : array_like
        Standard deviation of the storey drift velocity udot [m/s].
    sigma_z : array_like
        Standard deviation of the hysteretic displacement z [m].
    rho : array_like
        Correlation coefficient of udot and z [-], in [-1, 1].
    n : array_like
        Bouc-Wen exponent [-], >= 1.

    Returns
    -------
    F1, F2 : ndarray
        [m^n].
    F3, F4 : ndarray
        [m^n / s].
    """
    sigma_velocity, sigma_z, rho, n = np.broadcast_arrays(
        *(np.asarray(value, dtype=float) for value in (sigma_velocity, sigma_z, rho, n))
    )
    return _wen_terms(sigma_velocity, sigma_z, np.clip(rho, -1.0, 1.0), wen_constants(n))


def coefficients_from_statistics(A, beta, gamma_, statistics, constants):
    """c_e and k_e of Eq. 20 from (sigma_velocity, sigma_z, rho) and :func:`wen_constants` of n."""
    f1, f2, f3, f4 = _wen_terms(*statistics, constants)
    return A - beta * f1 - gamma_ * f2, -beta * f3 - gamma_ * f4


def equivalent_coefficients(A, beta, gamma_, n, sigma_velocity, sigma_z, rho):
    """Equivalent linear coefficients c_e [-] and k_e [1/s] of Eq. 19-20:
    c_e = A - beta F1 - gamma F2, k_e = -beta F3 - gamma F4.

    Parameters
    ----------
    A, beta, gamma_, n : array_like
        Bouc-Wen parameters (``beta``, ``gamma_`` in [1/m^n]).
    sigma_velocity, sigma_z, rho : array_like
        Statistics of the storey drift velocity and hysteretic displacement,
        see :func:`wen_expectations`.

    Returns
    -------
    c_e, k_e : ndarray
    """
    sigma_velocity, sigma_z, rho, n = np.broadcast_arrays(
        *(np.asarray(value, dtype=float) for value in (sigma_velocity, sigma_z, rho, n))
    )
    return coefficients_from_statistics(A, beta, gamma_, (sigma_velocity, sigma_z, np.clip(rho, -1.0, 1.0)), wen_constants(n))
