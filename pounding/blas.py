"""BLAS on one thread, for a stretch of closed-form work: its matrices have a few dozen rows, and OpenBLAS's
threads cost more than they give there (a 20-PGA fragility curve took 58 ms on one thread against 145 ms on two,
benchmarks/fragility.py). A context, so the caller's own setting is back afterwards."""

from __future__ import annotations

__all__ = ["single_blas_thread"]


def single_blas_thread():
    """A context in which BLAS runs on one thread (threadpoolctl)."""
    from threadpoolctl import threadpool_limits

    return threadpool_limits(1, user_api="blas")
