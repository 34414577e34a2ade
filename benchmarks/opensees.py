"""pounding against OpenSees on the same records, printed as figures.

For each case: `pounding export opensees` writes the model, OpenSees runs it
(`python model.py`, a subprocess, as a user runs it) and `simulate` integrates
the same records on one thread. Printed: each record's F_max both ways and
their difference, the impacts both ways, the CPU seconds a record each way;
for a case of several contacts, each contact's largest and mean difference;
with --halve, OpenSees again at half the exported step and how far each F_max
moved (the step is converged when under 0.1 %). Needs openseespy.

Run: python3 benchmarks/opensees.py [--records 10] [--seed 1] [--halve] [CASE ...]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from pounding import Settings, load_case, simulate  # noqa: E402
from pounding.export.opensees import export_opensees  # noqa: E402

CASES = ("section5-T2-0.4", "section6-T2-0.4-nonstationary")


def run_model(script: Path, *options: str) -> dict:
    """The model's last-line JSON."""
    out = subprocess.run([sys.executable, str(script), *options], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def pounding_cpu_per_record(case, records: int, seed: int):
    """simulate's result and its CPU seconds a record on one thread (after a warm-up)."""
    settings = Settings(workers=1)
    simulate(case, records=1, seed=seed, settings=settings)
    start = time.process_time()
    result = simulate(case, records=records, seed=seed, settings=settings)
    return result, (time.process_time() - start) / records


def print_contacts(result, opensees: dict) -> None:
    """Each contact's per-record |diff| of F_max, largest and mean over the records where it pounds, and its impacts."""
    for peaks, theirs in zip(result.contacts, opensees["contacts"]):
        pounded = peaks.force_max > 0
        difference = 100 * np.abs(np.array(theirs["force_max"], dtype=float)[pounded] / peaks.force_max[pounded] - 1)
        (left, right), (level_left, level_right) = peaks.contact.between, peaks.contact.levels
        summary = f"max {np.max(difference):.3f} %, mean {np.mean(difference):.3f} %" if pounded.any() else "no pounding"
        print(f"  contact buildings {left}-{right}, floors {level_left}/{level_right}: {summary} over {pounded.sum()} records; "
              f"impacts {peaks.impacts.sum()} / {sum(theirs['impacts'])}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=list(CASES), help=f"presets or case files (default: {', '.join(CASES)})")
    parser.add_argument("--records", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--halve", action="store_true", help="also run OpenSees at half the exported step")
    args = parser.parse_args()
    for name in args.cases:
        case = load_case(name)
        with tempfile.TemporaryDirectory() as folder:
            written = export_opensees(case, folder, records=args.records, seed=args.seed)
            opensees = run_model(written.script)
            halved = run_model(written.script, "--step", repr(written.time_step / 2)) if args.halve else None
        result, cpu = pounding_cpu_per_record(case, args.records, args.seed)
        force, impacts = result.force_max, result.impacts
        theirs = np.array(opensees["force_max"], dtype=float)
        difference = 100 * (theirs / force - 1)
        print(f"\n{case.name}: {args.records} records, seed {args.seed}; OpenSees step {1e6 * written.time_step:.4g} us "
              f"({written.time_step_reason})")
        header = f"{'record':>6} {'F_max pounding':>15} {'F_max OpenSees':>15} {'diff':>8} {'impacts':>9}"
        print(header + (f" {'half step moves':>16}" if halved else ""))
        for i in range(args.records):
            line = (f"{i:>6} {force[i] / 1e3:>12.2f} kN {theirs[i] / 1e3:>12.2f} kN {difference[i]:>+7.3f}% "
                    f"{impacts[i]:>4}/{opensees['impacts'][i]:<4}")
            if halved:
                line += f" {100 * (halved['force_max'][i] / theirs[i] - 1):>+15.3f}%"
            print(line)
        pounded = force > 0
        print(f"per-record |diff| over {pounded.sum()} pounding records: max {np.max(np.abs(difference[pounded])):.3f} %, "
              f"mean {np.mean(np.abs(difference[pounded])):.3f} %; impacts {impacts.sum()} / {sum(opensees['impacts'])}")
        if len(case.contacts) > 1:
            print_contacts(result, opensees)
        print(f"CPU per record: pounding {1e3 * cpu:.2f} ms, OpenSees {np.mean(opensees['cpu_seconds']):.2f} s "
              f"({np.mean(opensees['cpu_seconds']) / cpu:.0f} times); fallbacks: {opensees['fallbacks'] or 'none'}")


if __name__ == "__main__":
    main()
