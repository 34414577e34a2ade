"""The closed form on recorded suites from generators nobody tuned on (issue 31).

Each suite of ``validation/suite_generators.py`` (Boore's 2003 stochastic
method at two magnitudes and distances, Rezaeian & Der Kiureghian's 2008
drifting filter at two drifts, one suite low-passed at 10 Hz and one resampled
to 0.02 s) is written as .AT2 files to a temporary folder and read back by a
case whose ``[excitation]`` says ``records = ["<suite>/*.AT2"]``, scaled so the
suite's mean PGA is 0.3 g (``scale``), or each record to 0.3 g (``pga``,
``--pga-each``). Under it stand building pairs of the accuracy grid
(``pounding.studies.paper_tables.accuracy_cases``): yielding and elastic, stiff
and flexible. The closed form (E[F_max], pounding probability), which sees the
suite only through the spectrum fitted to it, is set against Monte Carlo over
the same records, each once (mean F_max, the fraction of records that pound).
Also printed: the fitted process's expected PGA (G29) against the records' mean.

Issue 31's target for a fitted spectrum: the pounding probability within 0.10
of the records' fraction, and E[F_max] within 10 % on most suites.

    python3 -m validation.suite_accuracy                    # 100 records a suite, about 2 min on 2 cores
    python3 -m validation.suite_accuracy --quick            # 20 records a suite
    python3 -m validation.suite_accuracy --json out.json    # the rows as JSON too
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import subprocess
import tempfile
import tomllib
from pathlib import Path

import numpy as np

from pounding import estimate, simulate
from pounding.case.case import case_from_dict
from pounding.errors import InputError
from pounding.hazard.accelerograms import G, write_at2
from pounding.presets import preset_text
from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration
from pounding.studies.paper_tables import accuracy_cases

from .suite_generators import BruneSource, DriftingFilter, brune_suite, drifting_filter_suite, low_passed, resampled

RECORDS, QUICK_RECORDS = 100, 20
PGA = 0.3  # [g]: the suite's mean PGA (or each record's with --pga-each)
STRONG_DRIFT = DriftingFilter(frequency_start=6.0, frequency_end=1.0, damping_start=0.2, damping_end=0.4)
WEAK_DRIFT = DriftingFilter(frequency_start=3.0, frequency_end=2.4, damping_start=0.3, damping_end=0.2)
BASE_SUITES = {
    "Brune M7.0 R30 km": (lambda n: brune_suite(BruneSource(magnitude=7.0, distance=30.0e3), n, 3101, "brune-M7.0-R30"),
                          "Boore (2003): M 7.0, R 30 km, 70 bar, Q = 180 f^0.45, kappa 0.04 s, 40 s at 0.005 s", 3101),
    "Brune M5.5 R10 km": (lambda n: brune_suite(BruneSource(magnitude=5.5, distance=10.0e3), n, 3102, "brune-M5.5-R10"),
                          "Boore (2003): M 5.5, R 10 km, 70 bar, Q = 180 f^0.45, kappa 0.04 s, 40 s at 0.005 s", 3102),
    "RDK strong drift": (lambda n: drifting_filter_suite(STRONG_DRIFT, n, 3103, "rdk-strong"),
                         ("Rezaeian & Der Kiureghian (2008): f 6 -> 1 Hz, zeta 0.2 -> 0.4 over 30 s, gamma q (2.5, 0.25/s), "
                          "high-pass 0.1 Hz, 0.005 s"), 3103),
    "RDK weak drift": (lambda n: drifting_filter_suite(WEAK_DRIFT, n, 3104, "rdk-weak"),
                       ("Rezaeian & Der Kiureghian (2008): f 3 -> 2.4 Hz, zeta 0.3 -> 0.2 over 30 s, gamma q (2.5, 0.25/s), "
                        "high-pass 0.1 Hz, 0.005 s"), 3104),
}
DERIVED_SUITES = {
    "Brune M5.5 R10 km, low-passed 10 Hz": ("Brune M5.5 R10 km", lambda records: low_passed(records, 10.0, name="brune-M5.5-R10-lp10"),
                                            "the Brune M5.5 records through a 4th-order Butterworth at 10 Hz, zero phase"),
    "RDK strong drift, resampled 0.02 s": ("RDK strong drift", lambda records: resampled(records, 0.02, name="rdk-strong-dt0.02"),
                                           "the strong-drift records resampled to 0.02 s (polyphase, anti-aliased)"),
}
SUITES = (*BASE_SUITES, *DERIVED_SUITES)
PAIRS = ("section5-T2-0.4", "T1 1.2 T2 2.0", "T1 0.3 T2 0.2 G0x4", "section6-T2-0.4", "elastic 1.2/0.4 gap6cm",
         "elastic 0.5/0.3 gap3cm")
"""Grid pairs: yielding 1.2/0.4 s (gap 1 cm), flexible 1.2/2.0 s, stiff 0.3/0.2 s, the two-storey frames,
elastic 1.2/0.4 s (gap 6 cm) and stiff elastic 0.5/0.3 s (gap 3 cm)."""


def suites(names, records: int) -> dict:
    """{name: (records, description, seed)} for the suites ``names``, derived suites from their base's records."""
    base, out = {}, {}
    for name in names:
        source = DERIVED_SUITES[name][0] if name in DERIVED_SUITES else name
        if source not in base:
            make, description, seed = BASE_SUITES[source]
            base[source] = (make(records), description, seed)
        if name in DERIVED_SUITES:
            _, derive, description = DERIVED_SUITES[name]
            out[name] = (derive(base[source][0]), description, base[source][2])
        else:
            out[name] = base[name]
    return out


def recorded_case(records, folder: Path, label: str, pga_each: bool = False):
    """The case read from a TOML-shaped table whose ``[excitation]`` names ``records`` written as .AT2 files
    in ``folder``/``label``/, the Section 5 pair as its buildings."""
    directory = folder / label
    directory.mkdir(parents=True, exist_ok=True)
    for record in records:
        write_at2(directory / f"{record.name}.AT2", record, title=label)
    mean_peak = float(np.mean([record.peak for record in records])) / G
    excitation = {"records": [f"{label}/*.AT2"]}
    excitation.update({"pga": PGA} if pga_each else {"scale": PGA / mean_peak})
    data = tomllib.loads(preset_text("section5-T2-0.4"))
    data["excitation"] = excitation
    return case_from_dict(data, name=label, base_directory=folder)


def _grid_pairs(names) -> dict:
    cases = {case.name: case for case in accuracy_cases()}
    return {name: cases[name] for name in names}


def rows(records: int = RECORDS, suite_names=None, pair_names=None, pga_each: bool = False, seed: int = 11,
         fitted_process: bool = True):
    """(suite rows, case rows): for each suite its generator, the fitted spectrum and the PGAs; for each suite
    and pair the closed form against Monte Carlo over the suite's records (and, with ``fitted_process``, over
    as many records of the process the closed form takes)."""
    grid = _grid_pairs(pair_names or PAIRS)
    suite_rows, case_rows = [], []
    with tempfile.TemporaryDirectory(prefix="suite-accuracy-") as folder:
        for index, (name, (motions, description, generator_seed)) in enumerate(suites(suite_names or SUITES, records).items()):
            base = recorded_case(motions, Path(folder), f"suite{index}", pga_each)
            fitted = base.hazard.fitted
            peaks = np.array([record.peak for record in base.hazard.records]) / G
            suite_rows.append({
                "suite": name, "generator": description, "seed": generator_seed, "records": len(motions),
                "time_step": motions[0].time_step, "fitted": fitted.to_dict(),
                "records_mean_pga": float(peaks.mean()),
                "fitted_expected_pga": expected_peak_ground_acceleration(base.excitation) / G,
            })
            for pair_name, pair in grid.items():
                case = dataclasses.replace(base, buildings=pair.buildings, contacts=pair.contacts, name=f"{name}, {pair_name}")
                case_rows.append({"suite": name, "pair": pair_name, **compare(case, len(motions), seed, fitted_process)})
    return suite_rows, case_rows


def compare(case, records: int, seed: int = 11, fitted_process: bool = True) -> dict:
    """The closed form against Monte Carlo over the ``records`` records of the recorded ``case``, each once: the
    Monte Carlo mean F_max [N], its standard error and the fraction that pound; with ``fitted_process``, Monte
    Carlo over as many records synthesized from the process the closed form takes; the closed form's regime,
    gap / sigma_X, E[F_max] [N], its error and its pounding probability, or (``closed_form_error``) why it
    refused the case (InputError), the Monte Carlo kept."""
    study = simulate(case, records=records, seed=seed)
    mc = study.force_max_mean
    row = {"monte_carlo": mc, "std_error": study.force_max_std_error, "pounding_fraction": study.pounding_fraction,
           "yielding": any(storey.bouc_wen.alpha < 1.0 for building in case.buildings for storey in building.storeys)}
    if fitted_process:
        process = simulate(dataclasses.replace(case, hazard=None), records=records, seed=seed)
        row.update(fitted_process_monte_carlo=process.force_max_mean, fitted_process_fraction=process.pounding_fraction)
    row.update(regime=None, gap_over_sigma=None, closed_form=None, force_error=None, pounding_probability=None,
               closed_form_error=None)
    try:
        closed = estimate(case)
    except InputError as error:  # the closed form refuses the case: say why, keep the Monte Carlo
        row["closed_form_error"] = str(error)
    else:
        row.update(regime=closed.accuracy_regime, gap_over_sigma=case.contact.gap / closed.sigma_relative_displacement,
                   closed_form=closed.force_expected, pounding_probability=closed.pounding_probability,
                   force_error=closed.force_expected / mc - 1.0 if mc > 0 else None)
    return row


def summary_cells(case_rows) -> str:
    """The cells "E[F_max] within 10 % | median |error| | range | probability within 0.10 | largest |difference|"
    over ``case_rows`` (rows of :func:`compare`), those the closed form refused left out."""
    mine = [r for r in case_rows if r["closed_form"] is not None]
    errors = np.array([r["force_error"] for r in mine if r["force_error"] is not None])
    differences = np.abs([r["pounding_probability"] - r["pounding_fraction"] for r in mine])
    force = (f"{int(np.sum(np.abs(errors) <= 0.10))} of {errors.size} | {np.median(np.abs(errors)):.1%} | "
             f"{errors.min():+.0%} to {errors.max():+.0%}") if errors.size else "- | - | -"
    probability = f"{int(np.sum(differences <= 0.10))} of {differences.size} | {differences.max():.2f}" if differences.size else "- | -"
    return f"{force} | {probability}"


def commit() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              cwd=Path(__file__).parent, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def describe_spectrum(fitted: dict) -> str:
    text = f"{fitted['spectrum']}: omega_g {fitted['omega_g']:.1f} rad/s, xi_g {fitted['xi_g']:.2f}"
    if "omega_f" in fitted:
        text += f", omega_f {fitted['omega_f']:.2f} rad/s, xi_f {fitted['xi_f']:.2f}"
    return text + f", D {fitted['duration']:.1f} s"


def ratio_text(value: float, reference: float) -> str:
    return "n/a" if reference == 0 else f"{value / reference - 1.0:+.1%}"


def print_tables(suite_rows, case_rows, records: int, pga_each: bool) -> None:
    scaling = f"each record to a PGA of {PGA} g" if pga_each else f"each suite to a mean PGA of {PGA} g"
    print(f"Suites of {records} records, scaled {scaling}; Monte Carlo over the same records, each once.\n")
    print("| suite | generator | seed | dt (s) | fitted spectrum | records' mean PGA (g) | fitted E[PGA] (g) | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for s in suite_rows:
        print(f"| {s['suite']} | {s['generator']} | {s['seed']} | {s['time_step']:g} | {describe_spectrum(s['fitted'])} | "
              f"{s['records_mean_pga']:.3f} | {s['fitted_expected_pga']:.3f} | {s['fitted_expected_pga'] / s['records_mean_pga']:.2f} |")
    print("\nMonte Carlo over the records; the closed form (kN, its error, its pounding probability and that minus "
          "the records' fraction); Monte Carlo over as many records synthesized from the fitted process (its error "
          "and fraction), which splits the closed form's error into the fit's and the estimator's.\n")
    print("| suite | pair | regime | gap / sigma_X | records: E[F_max] (kN) | s.e. | pounding fraction | closed form (kN) | "
          "error | probability | difference | fitted process: error | fraction |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    refused = []
    for r in case_rows:
        relative = "n/a" if r["monte_carlo"] == 0 else f"{r['std_error'] / r['monte_carlo']:.1%}"
        if r["closed_form"] is None:
            refused.append(r)
            print(f"| {r['suite']} | {r['pair']} | refused ({len(refused)}) | - | {r['monte_carlo'] / 1e3:.1f} | {relative} | "
                  f"{r['pounding_fraction']:.2f} | - | - | - | - | {ratio_text(r['fitted_process_monte_carlo'], r['monte_carlo'])} | "
                  f"{r['fitted_process_fraction']:.2f} |")
            continue
        error = "n/a" if r["force_error"] is None else f"{r['force_error']:+.1%}"
        print(f"| {r['suite']} | {r['pair']} | {r['regime']} | {r['gap_over_sigma']:.2f} | {r['monte_carlo'] / 1e3:.1f} | "
              f"{relative} | {r['pounding_fraction']:.2f} | {r['closed_form'] / 1e3:.1f} | {error} | "
              f"{r['pounding_probability']:.2f} | {r['pounding_probability'] - r['pounding_fraction']:+.2f} | "
              f"{ratio_text(r['fitted_process_monte_carlo'], r['monte_carlo'])} | {r['fitted_process_fraction']:.2f} |")
    for number, r in enumerate(refused, 1):
        print(f"\n({number}) the closed form refused {r['suite']}, {r['pair']}: {r['closed_form_error']}")
    print("\n| suite | E[F_max] within 10 % | median \\|error\\| | range | probability within 0.10 | largest \\|difference\\| |")
    print("|---|---|---|---|---|---|")
    for name in dict.fromkeys(r["suite"] for r in case_rows):
        print(f"| {name} | {summary_cells([r for r in case_rows if r['suite'] == name])} |")


def main(records: int = RECORDS, suites=None, pairs=None, pga_each: bool = False, json_path=None) -> None:
    """The tables for ``records`` records a suite, the ``suites`` and ``pairs`` named (all for None); with
    ``json_path`` the rows are written there as JSON too."""
    suite_rows, case_rows = rows(records, suites, pairs, pga_each)
    print_tables(suite_rows, case_rows, records, pga_each)
    if json_path is not None:
        document = {"written_by": f"validation.suite_accuracy at {commit()}", "records": records,
                    "scaling": "pga each" if pga_each else "suite mean pga", "pga_g": PGA,
                    "suites": suite_rows, "cases": case_rows}
        Path(json_path).write_text(json.dumps(document, indent=1) + "\n")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=None, help=f"records a suite (default {RECORDS}, {QUICK_RECORDS} with --quick)")
    parser.add_argument("--quick", action="store_true", help=f"{QUICK_RECORDS} records a suite")
    parser.add_argument("--pga-each", action="store_true", help=f"scale each record to {PGA} g instead of the suite's mean")
    parser.add_argument("--json", metavar="PATH", help="write the rows as JSON to PATH")
    arguments = parser.parse_args()
    count = arguments.records or (QUICK_RECORDS if arguments.quick else RECORDS)
    main(count, pga_each=arguments.pga_each, json_path=arguments.json)
