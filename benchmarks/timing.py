"""The timing the benchmarks share (each run as ``python3 benchmarks/NAME.py``, this folder on the path)."""

from __future__ import annotations

import contextlib
import io
import time

import numpy as np


def median_seconds(function, repeats: int = 30, setup=None) -> float:
    """Median wall time of ``function()`` after one warm-up call (JIT cache
    load, tables); with ``setup``, ``function(setup())``, the setup untimed."""
    function(setup()) if setup else function()
    times = []
    for _ in range(repeats):
        argument = setup() if setup else None
        start = time.perf_counter()
        function(argument) if setup else function()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def command_output(argv: list[str]) -> str:
    """``pounding.cli.commands.main(argv)`` in this process, its stdout captured: the printed text."""
    from pounding.cli.commands import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        status = main(argv)
    if status != 0:
        raise RuntimeError(f"pounding {' '.join(argv)} exited {status}")
    return out.getvalue()
