"""``pounding validate``: the paper's Tables 1, 2, 5 and 6 beside this project's Monte Carlo and both estimators,
or (``--grid``) both estimators against Monte Carlo on the accuracy grid (docs/accuracy.md)."""

from __future__ import annotations

import json

from pounding.cli.progress import progress_bar

__all__ = ["validate_command"]


def _grid(args) -> int:
    from pounding.studies.paper_tables import accuracy, accuracy_cases
    from pounding.studies.storey_grid import engineer_storey_cases

    cases = accuracy_cases() + engineer_storey_cases()
    with progress_bar(len(cases), unit="case") as progress:
        rows = accuracy(cases, records=args.records, seed=args.seed, progress=progress)
    if args.json:
        print(json.dumps({"records": args.records, "seed": args.seed, "units": {"force": "N"},
                          "rows": [dict(row.__dict__, recommended_error=row.recommended_error, paper_error=row.paper_error) for row in rows]}))
        return 0

    def percent(error):
        return "n/a" if error is None else f"{100 * error:+.1f} %"

    print(f"Monte Carlo: {args.records} records per case, seed {args.seed}; errors are estimate / Monte Carlo - 1.\n")
    print("| case | regime | gap / sigma_X | Monte Carlo E[F_max] (kN) | s.e. | recommended | paper | P(pounding) MC | P estimate |")
    print("|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        relative = "n/a" if row.monte_carlo == 0.0 else f"{100 * row.monte_carlo_std_error / row.monte_carlo:.1f} %"
        if row.refused:
            print(f"| {row.case} | refused | - | {row.monte_carlo / 1e3:.1f} | {relative} | - | - | {row.pounding_fraction:.3f} | - |")
            continue
        print(f"| {row.case} | {row.accuracy_regime} | {row.gap_over_sigma:.2f} | {row.monte_carlo / 1e3:.1f} | {relative} | "
              f"{percent(row.recommended_error)} | {percent(row.paper_error)} | {row.pounding_fraction:.3f} | {row.pounding_probability:.3f} |")
    unpounded = sum(row.monte_carlo == 0.0 for row in rows)
    if unpounded:
        print(f"\nno record pounded in {unpounded} case(s): no relative error there (n/a); more records would tell")
    refused = [row for row in rows if row.refused]
    if refused:
        print(f"\nthe closed form refused {len(refused)} case(s), saying why (not counted): {refused[0].refused}")
    for label, errors in (("recommended", [r.recommended_error for r in rows]), ("paper", [r.paper_error for r in rows])):
        magnitudes = sorted(abs(e) for e in errors if e is not None)
        if not magnitudes:
            continue
        within = sum(m <= 0.10 for m in magnitudes)
        print(f"\n{label}: median |error| {100 * magnitudes[len(magnitudes) // 2]:.1f} %, largest {100 * magnitudes[-1]:.1f} %, "
              f"within 10 %: {within} of {len(magnitudes)}", end="")
    print()
    return 0


def validate_command(args) -> int:
    from pounding.studies.paper_tables import ASSUMPTIONS, READINGS_MEASURED, validate

    if args.grid:
        return _grid(args)

    with progress_bar(24, unit="case") as progress:
        rows = validate(records=args.records, seed=args.seed, progress=progress)
    if args.json:
        print(json.dumps({"records": args.records, "seed": args.seed, "rows": [row.to_dict() for row in rows],
                          "assumptions": list(ASSUMPTIONS), "readings_measured": READINGS_MEASURED, "units": {"force": "N"}}))
        return 0

    def kn(value):  # the display unit of every force printed (the paper prints MN: 0.285 MN is 285.0 kN)
        return "     n/a" if value is None else f"{value / 1e3:8.1f}"

    print(f"Expected extreme pounding force [kN]; Monte Carlo: {args.records} records, seed {args.seed}.")
    current = None
    for row in rows:
        if (row.table, row.reading) != current:
            current = (row.table, row.reading)
            print(f"\n{row.table}, excitation {row.reading}")
            print("  T1, T2 (s)   paper exact  paper proposed | Monte Carlo (+- s.e.)  paper's method  recommended")
        print(f"  1.2, {row.period_2:.1f}    {kn(row.paper_exact)}     {kn(row.paper_proposed)}    |"
              f"  {kn(row.monte_carlo)} +- {row.monte_carlo_std_error / 1e3:.1f}    {kn(row.paper_estimator)}     {kn(row.recommended_estimator)}")
    print("\nAssumptions where the paper is silent or misprinted:")
    for line in ASSUMPTIONS:
        print(f"  - {line}")
    print(f"\nThe two readings of the excitation: {READINGS_MEASURED}")
    return 0
