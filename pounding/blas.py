"""BLAS on one thread, for a stretch of closed-form work: its matrices have a few dozen rows, and OpenBLAS's
threads cost more than they give there (a 20-PGA fragility curve took 58 ms on one thread against 145 ms on two,
benchmarks/fragility.py; on a loaded machine an estimate of the Section 5 case took 49 ms on BLAS's threads against
15 ms on one). A context, so the caller's own setting is back afterwards."""

from __future__ import annotations

from functools import lru_cache

__all__ = ["single_blas_thread"]


@lru_cache(maxsize=1)
def _controller():
    """threadpoolctl's view of the loaded BLAS libraries, made once (it takes milliseconds; a limit then 15 us)."""
    import scipy.linalg  # noqa: F401 -- scipy's own BLAS loaded first, so the controller sees it
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def single_blas_thread():
    """A context in which BLAS runs on one thread (threadpoolctl)."""
    return _controller().limit(limits=1, user_api="blas")
