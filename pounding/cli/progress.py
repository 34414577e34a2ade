"""The command line's one progress bar: tqdm on stderr while stderr is a terminal, nothing otherwise (a pipe or a
log file gets no bar), closed however the work ends."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager

__all__ = ["progress_bar"]


@contextmanager
def progress_bar(total: int | None = None, unit: str = "record",
                 enabled: bool = True) -> Iterator[Callable[[int, int], None] | None]:
    """Yield ``progress(done, total)`` drawing a bar of ``total`` units (None: the total the work reports), or
    None where no bar is drawn (``enabled`` False, or stderr not a terminal)."""
    if not (enabled and sys.stderr.isatty()):
        yield None
        return
    from tqdm import tqdm

    bar = tqdm(total=total, unit=unit, file=sys.stderr, dynamic_ncols=True)

    def progress(done: int, reported_total: int) -> None:
        if bar.total is None or total is None:
            bar.total = reported_total
        bar.update(done - bar.n)

    try:
        yield progress
    finally:
        bar.close()
