"""The stationary covariance of a linear system under white noise: the
Lyapunov equation A P + P A^T + Q = 0, small systems by a compiled dense
solve in the entries of the symmetric P, larger ones by scipy."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numba import njit
from scipy.linalg import solve_continuous_lyapunov

_DENSE_LYAPUNOV_LIMIT = 10
"""Largest state dimension solved as a dense linear system in the entries of
the symmetric covariance; beyond, scipy's Bartels-Stewart solver is faster."""

@lru_cache(maxsize=32)
def _lyapunov_maps(n: int):
    """Rows and columns of the upper triangle of an n x n matrix: the
    coordinates (m = n (n + 1) / 2 unknowns) of a symmetric covariance."""
    return np.triu_indices(n)


@njit(cache=True)
def _solve(matrix, rhs):
    """Solve matrix x = rhs by Gaussian elimination with partial pivoting
    (small dense systems; numba's LAPACK binding costs seconds to compile).
    Returns NaNs if the matrix is singular. Overwrites ``matrix``."""
    n = rhs.size
    x = rhs.copy()
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(matrix[i, k]) > abs(matrix[pivot, k]):
                pivot = i
        if matrix[pivot, k] == 0.0:
            return np.full(n, np.nan)
        if pivot != k:
            for j in range(n):
                matrix[k, j], matrix[pivot, j] = matrix[pivot, j], matrix[k, j]
            x[k], x[pivot] = x[pivot], x[k]
        for i in range(k + 1, n):
            factor = matrix[i, k] / matrix[k, k]
            if factor != 0.0:
                for j in range(k, n):
                    matrix[i, j] -= factor * matrix[k, j]
                x[i] -= factor * x[k]
    for k in range(n - 1, -1, -1):
        total = x[k]
        for j in range(k + 1, n):
            total -= matrix[k, j] * x[j]
        x[k] = total / matrix[k, k]
    return x


@njit(cache=True)
def _lyapunov_upper(matrix, rhs, rows, cols):
    """Upper triangle p of the symmetric P with A P + P A^T = -Q, from the
    dense m x m system (m = n (n + 1) / 2) on ``rhs`` = upper triangle of Q
    negated; NaNs if singular."""
    n = matrix.shape[0]
    m = rows.size
    unknown = np.empty((n, n), dtype=np.int64)
    for e in range(m):
        unknown[rows[e], cols[e]] = e
        unknown[cols[e], rows[e]] = e
    operator = np.zeros((m, m))
    for e in range(m):
        i, j = rows[e], cols[e]
        for k in range(n):
            operator[e, unknown[k, j]] += matrix[i, k]
            operator[e, unknown[i, k]] += matrix[j, k]
    return _solve(operator, rhs)


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
    if n > _DENSE_LYAPUNOV_LIMIT:
        solution = solve_continuous_lyapunov(matrix, -noise_covariance)
        return 0.5 * (solution + solution.T)
    rows, cols = _lyapunov_maps(n)
    # Equation (i, j) of A P + P A^T = -Q is sum_k A_ik P_kj + A_jk P_ik = -Q_ij.
    upper = _lyapunov_upper(np.ascontiguousarray(matrix, dtype=float), -noise_covariance[rows, cols], rows, cols)
    if not np.all(np.isfinite(upper)):
        raise np.linalg.LinAlgError("the Lyapunov equation is singular (the system has a mode at or symmetric about zero)")
    solution = np.empty((n, n))
    solution[rows, cols] = upper
    solution[cols, rows] = upper
    return solution
