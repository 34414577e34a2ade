"""Throughput of ``pounding.sweep`` on Dask, printed as figures.

The Section 5 case T1 = 1.2 s, T2 = 0.4 s, 20 s stationary records, swept
over 4 gaps:
- records per second in this process without Dask (``scheduler="serial"``)
  and on a 2-worker local cluster (one thread per worker process), after the
  workers are warm; the cluster's start-up and warm-up are timed apart;
- the overhead per chunk: the same records in chunks of 1 against chunks of
  ``--chunk-records`` (a Dask round trip, the case rebuilt on the worker,
  the exact sums, the chunk file written atomically by the client);
- the data moved per chunk: the task's pickled arguments and result, and the
  file kept on disk.

How it scales to a cluster. A chunk is independent of every other: the
scheduler sends a worker the point's case file (about 1 kB pickled) with
(seed, first record, count), and gets back about 0.3 kB of exact sums; no
record, history or per-record array crosses the network, so the traffic per
chunk stays near 1.3 kB however many records it holds, and the client's
memory and disk grow with the number of chunks (one ~0.35 kB file each), not
with the number of records. A chunk costs chunk_records x (time per record,
about 4 ms for a 20 s record of the two SDOF buildings on one core) plus a
fixed overhead measured here, a few milliseconds (a third of it the engine's
own per-call set-up, the rest the scheduler round trip and the client's
fsync'd write of the chunk file). At the default 100 records per chunk
(~0.4 s of work) that overhead is a few per cent, so throughput grows with
the number of worker cores until the scheduler's rate limits it: Dask's
scheduler handles a few thousand tasks per second, i.e. some 10^5 records/s
at 100 records per chunk, hundreds of cores. On a real cluster raise
--chunk-records so a chunk lasts seconds (multi-storey buildings and long
records raise the time per record by themselves), while keeping several
chunks per worker thread for load balance; a lost worker then costs only its
chunk in flight. Every new worker process loads the cached numba kernels
once (~1-2 s; ~10 s of compilation with an empty cache: ship the cache or
warm the image). On a machine with few cores, the client, the scheduler and
the nannies share the cores with the workers: expect a 2-worker speed-up
below 2 on 2 cores, and noisy figures when other jobs run (the load average
is printed; the best of --repeat runs is kept).

Run: python3 benchmarks/sweep.py [--records 300] [--chunk-records 100] [--repeat 2]
"""

from __future__ import annotations

import argparse
import logging
import os
import pickle
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from pounding import defaults  # noqa: E402
from pounding.presets import preset_text  # noqa: E402
from pounding.studies.sweeps import chunk_sums, sweep  # noqa: E402

CASE = "section5-T2-0.4"
GAPS = [0.5, 1.0, 1.5, 2.0]  # cm


def timed_sweep(records: int, chunk_records: int, scheduler, folder: Path) -> tuple[float, object]:
    data = tomllib.loads(preset_text(CASE))
    start = time.perf_counter()
    table = sweep(data, {"contact.gap": GAPS}, records=records, seed=1, output_dir=folder, scheduler=scheduler,
                  chunk_records=chunk_records, chart=False)
    return time.perf_counter() - start, table


def best_of(repeat: int, records: int, chunk_records: int, scheduler, folder: Path) -> tuple[float, object]:
    """The fastest of ``repeat`` sweeps, each into a fresh folder (nothing to resume)."""
    runs = [timed_sweep(records, chunk_records, scheduler, folder / str(number)) for number in range(repeat)]
    return min(runs, key=lambda run: run[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=300, help="records per point (4 points)")
    parser.add_argument("--chunk-records", type=int, default=defaults.CHUNK_RECORDS)
    parser.add_argument("--repeat", type=int, default=2, help="time the best of this many runs (default 2)")
    args = parser.parse_args()
    from distributed import Client, LocalCluster

    total = args.records * len(GAPS)
    print(f"case {CASE}, 20 s records, gaps {GAPS} cm: {len(GAPS)} points x {args.records} records = {total}; "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} before the runs")
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        timed_sweep(2, 1, "serial", scratch / "warm")  # kernels and estimator loaded in this process
        serial, reference = best_of(args.repeat, args.records, args.chunk_records, "serial", scratch / "serial")
        print(f"serial (this process, 1 thread)          {serial:7.2f} s   {total / serial:7.1f} records/s")

        start = time.perf_counter()
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=logging.ERROR)
        client = Client(cluster)
        started = time.perf_counter() - start
        try:
            start = time.perf_counter()
            timed_sweep(2, 1, client, scratch / "warm-cluster")  # loads the kernels in each worker
            warmed = time.perf_counter() - start
            print(f"local cluster: start {started:.2f} s, first sweep (workers load numba kernels) {warmed:.2f} s")
            parallel, table = best_of(args.repeat, args.records, args.chunk_records, client, scratch / "cluster")
            same = table.drop(columns=[]).equals(reference)
            print(f"2-worker local cluster, chunks of {args.chunk_records:<4d}   {parallel:7.2f} s   {total / parallel:7.1f} records/s"
                  f"   (x{serial / parallel:.2f}; table identical to serial: {same})")
            small = max(2, args.records // 5)
            for label, scheduler in (("serial, no Dask", "serial"), ("2-worker cluster", client)):
                big, _ = timed_sweep(small, small, scheduler, scratch / f"big-{label}")
                single, _ = timed_sweep(small, 1, scheduler, scratch / f"single-{label}")
                extra = small * len(GAPS) - len(GAPS)
                print(f"per-chunk overhead, {label}: {small * len(GAPS)} records in chunks of 1 {single:.2f} s, "
                      f"in chunks of {small} {big:.2f} s -> {1e3 * (single - big) / extra:.1f} ms of wall clock per chunk")
        finally:
            client.close()
            cluster.close()

        data = tomllib.loads(preset_text(CASE))
        arguments = pickle.dumps((data, 1, 0, args.chunk_records, 1e-6))
        result = pickle.dumps(chunk_sums(data, 1, 0, args.chunk_records))
        files = sorted((scratch / "cluster").glob("*/points/*/chunk-*.json"))
        size = sum(path.stat().st_size for path in files) / len(files)
        print(f"data per chunk: to the worker {len(arguments)} B (case file + record range), back {len(result)} B (sums); "
              f"chunk file {size:.0f} B on disk")
    print()
    print("How it scales to a cluster. " + " ".join(__doc__.split("How it scales to a cluster.")[1].split("Run:")[0].split()))


if __name__ == "__main__":
    main()
