"""The stationary covariance of a linear system under white noise: the
Lyapunov equation A P + P A^T + Q = 0, small systems by a compiled dense
solve in the entries of the symmetric P, larger ones by scipy."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.linalg import solve_continuous_lyapunov

from pounding.closed_form.linearization.kernels import lyapunov_upper

DENSE_LYAPUNOV_LIMIT = 10
"""Largest state dimension solved as a dense linear system in the entries of
the symmetric covariance; beyond, scipy's Bartels-Stewart solver is faster."""

@lru_cache(maxsize=32)
def lyapunov_maps(n: int):
    """Rows and columns of the upper triangle of an n x n matrix: the
    coordinates (m = n (n + 1) / 2 unknowns) of a symmetric covariance."""
    return np.triu_indices(n)


def lyapunov_covariance(matrix: np.ndarray, noise_covariance: np.ndarray) -> np.ndarray:
    """Solve A P + P A^T + Q = 0 for the stationary covariance P.

    Small systems (the usual case here: a few storeys and a filter) are solved
    as a dense linear system in the n (n + 1) / 2 unknowns of the symmetric P,
    several times faster than scipy's Schur-based ``solve_continuous_lyapunov``
    at this size; larger ones by scipy.

    Parameters
    ----------
    matrix : ndarray, (n, n)
        A, asymptotically stable.
    noise_covariance : ndarray, (n, n)
        Q, symmetric.

    Returns
    -------
    ndarray, (n, n)
        P, symmetric.
    """
    n = matrix.shape[0]
    if n > DENSE_LYAPUNOV_LIMIT:
        solution = solve_continuous_lyapunov(matrix, -noise_covariance)
        return 0.5 * (solution + solution.T)
    rows, cols = lyapunov_maps(n)
    # Equation (i, j) of A P + P A^T = -Q is sum_k A_ik P_kj + A_jk P_ik = -Q_ij.
    upper = lyapunov_upper(np.ascontiguousarray(matrix, dtype=float), -noise_covariance[rows, cols], rows, cols)
    if not np.all(np.isfinite(upper)):
        raise np.linalg.LinAlgError("the Lyapunov equation is singular (the system has a mode at or symmetric about zero)")
    solution = np.empty((n, n))
    solution[rows, cols] = upper
    solution[cols, rows] = upper
    return solution
