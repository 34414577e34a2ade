"""The compiled kernels of the linearization: a small dense solve, the
Lyapunov equation in the entries of a symmetric covariance, the yielding
storeys' second moments, and the Anderson-mixing step of the fixed-point
iteration.

Numba's on-disk cache of a compiled function does not notice an edit to a
compiled function it calls in another file, so these call trees live here,
in one file.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["dense_solve", "iteration_moments", "lyapunov_upper", "mixing_step", "second_moments"]


@njit(cache=True, nogil=True)
def dense_solve(matrix, rhs):
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


@njit(cache=True, nogil=True)
def lyapunov_upper(matrix, rhs, rows, cols):
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
    return dense_solve(operator, rhs)


@njit(cache=True, nogil=True)
def second_moments(matrix, rhs, rows, cols, left, right):
    """left_i^T P right_i for the stationary covariance P of ``matrix`` under
    the noise whose negated upper triangle is ``rhs``."""
    upper = lyapunov_upper(matrix, rhs, rows, cols)
    n = matrix.shape[0]
    covariance = np.empty((n, n))
    for e in range(rows.size):
        covariance[rows[e], cols[e]] = upper[e]
        covariance[cols[e], rows[e]] = upper[e]
    out = np.zeros(left.shape[0])
    for i in range(left.shape[0]):
        for j in range(n):
            if left[i, j] != 0.0:
                for k in range(n):
                    out[i] += left[i, j] * covariance[j, k] * right[i, k]
    return out


@njit(cache=True, nogil=True)
def iteration_moments(matrix, z_states, velocity_start, drift_rows, c_e, k_e, rhs, rows, cols, left, right):
    """Put (c_e, k_e) of the yielding storeys into the state matrix (in place)
    and return their second moments, see :class:`_StoreyMoments`."""
    for s in range(z_states.size):
        row = z_states[s]
        for j in range(drift_rows.shape[1]):
            matrix[row, velocity_start + j] = c_e[s] * drift_rows[s, j]
        matrix[row, row] = k_e[s]
    return second_moments(matrix, rhs, rows, cols, left, right)


@njit(cache=True, nogil=True)
def mixing_step(x, residual, history_x, history_f, filled, relaxation, count):
    """Under-relaxed fixed-point step with Anderson mixing (Walker & Ni 2011).

    ``history_x`` and ``history_f`` hold the last ``filled`` iterates and
    residuals (updated in place). The step is shortened until c_e > 0 and
    k_e < 0 (the first ``count`` entries of x are c_e, the next k_e).
    Returns the step (all zeros if no admissible step exists) and the new
    ``filled``. Plain loops: numba compiles array expressions and BLAS calls
    slowly (seconds), and the sizes here are tiny.
    """
    depth, size = history_x.shape
    if filled == depth:
        for i in range(depth - 1):
            for j in range(size):
                history_x[i, j] = history_x[i + 1, j]
                history_f[i, j] = history_f[i + 1, j]
        filled -= 1
    for j in range(size):
        history_x[filled, j] = x[j]
        history_f[filled, j] = residual[j]
    filled += 1
    step = np.empty(size)
    for j in range(size):
        step[j] = relaxation * residual[j]
    columns = filled - 1
    if columns > 0:
        # The combination of the last differences that best cancels the
        # residual (least squares by the normal equations, lightly
        # regularized against repeated residuals), applied to the iterates
        # and residuals.
        gram = np.zeros((columns, columns))
        projection = np.zeros(columns)
        for a in range(columns):
            for j in range(size):
                d_fa = history_f[a + 1, j] - history_f[a, j]
                projection[a] += d_fa * residual[j]
                for b in range(columns):
                    gram[a, b] += d_fa * (history_f[b + 1, j] - history_f[b, j])
        trace = 0.0
        for a in range(columns):
            trace += gram[a, a]
        for a in range(columns):
            gram[a, a] += 1e-12 * trace + 1e-300
        weights = dense_solve(gram, projection)
        finite = True
        for a in range(columns):
            finite = finite and math.isfinite(weights[a])
        if finite:
            for a in range(columns):
                for j in range(size):
                    d_x = history_x[a + 1, j] - history_x[a, j]
                    d_f = history_f[a + 1, j] - history_f[a, j]
                    step[j] -= (d_x + relaxation * d_f) * weights[a]
    for _ in range(60):
        admissible = True
        for i in range(count):
            if not (x[i] + step[i] > 0.0 and x[count + i] + step[count + i] < 0.0):
                admissible = False
        if admissible:
            return step, filled
        for j in range(size):
            step[j] *= 0.5
    return np.zeros(size), filled
