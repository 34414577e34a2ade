"""Parametric studies: every combination of some case keys, estimated in
closed form and simulated by Monte Carlo, the records spread over Dask.

A sweep varies keys of the case *file* by their dotted path (``contact.gap``,
``buildings.2.storeys.1.period``, ``excitation.G0``; buildings and storeys
counted from 1), in the case's own units. Each combination (a *point*) is
the case file with those keys set, loaded and validated as any case file.

For each point, the records ``0 .. records - 1`` of the study seeded ``seed``
are split into chunks of ``chunk_records``; a chunk runs on a Dask worker,
which returns sums (of F_max, F_max^2, impacts, ...) and each record's F_max
(8 bytes a record, for quantiles and exceedance counts), never time
histories: memory stays small however many records. The sums
are exact (rational), so the table does not depend on how the records were
chunked or on which worker ran what: record *i* is seeded by
``SeedSequence(seed, spawn_key=(i,))`` (see :func:`pounding.simulate`).

Resumable: the client writes each finished chunk (and each point's closed-form
estimate) to ``output_dir`` as a small JSON file, atomically, named by a hash
of the point's physics, the seed, the tolerance and the chunk's record range.
A rerun computes only the files that are missing, so an interrupted sweep
(Ctrl-C, a killed client) loses the chunks in flight only, and its final table
equals an uninterrupted run's. A worker lost mid-chunk costs that chunk only:
Dask reruns it elsewhere. Files land where the *client* runs; a remote cluster
needs no shared file system, only ``pounding`` installed on its workers.

Layout of ``output_dir``::

    sweep.json                           what was asked (case, vary, records, seed, ...)
    sweep.csv (or sweep.parquet)         the table, one row per point
    sweep.html                           the design chart (static, Bokeh)
    points/<key>/point.json              the point's case data and varied values
    points/<key>/estimate.json           closed-form figures
    points/<key>/chunk-<first>-<count>.json   sums over records first .. first + count - 1, and each one's F_max

This package imports nothing heavy at load (the command line builds its parser from
:func:`pounding.cli.sweep.add_arguments`): Dask, pandas and Bokeh are imported when used.

Modules: :mod:`.spec` (the specs of ``vary``), :mod:`.points` (the case file
with the varied keys set), :mod:`.work` (what runs on Dask workers),
:mod:`.store` (the files), :mod:`.engine` (the sweep itself, and :func:`monte_carlo_forces`, every
record's F_max at adjusted cases for fragility curves and force spectra), :mod:`.table` (the table),
:mod:`.chart` (the design chart); the command ``pounding sweep`` is :mod:`pounding.cli.sweep`.
"""

from pounding.studies.sweeps.chart import write_chart
from pounding.studies.sweeps.engine import (
    SERIAL,
    TABLE_FORMATS,
    SweepInterrupted,
    monte_carlo_forces,
    sweep,
)
from pounding.studies.sweeps.spec import parse_values, parse_vary
from pounding.studies.sweeps.table import monte_carlo_summary
from pounding.studies.sweeps.work import chunk_sums, point_estimate

__all__ = [
    "SERIAL",
    "TABLE_FORMATS",
    "SweepInterrupted",
    "chunk_sums",
    "monte_carlo_forces",
    "monte_carlo_summary",
    "parse_values",
    "parse_vary",
    "point_estimate",
    "sweep",
    "write_chart",
]
