"""A case as a standalone OpenSeesPy model (``pounding export opensees``).

:func:`export_opensees` writes ``model.py`` and the ground-acceleration
records it runs: exactly those :func:`~pounding.simulation.monte_carlo.simulate`
integrates for the same records and seed (synthetic, or the case's recorded
motions as scaled). Every building of the case is in the model, and every
contact is an impact element of its own, all in one analysis. ``python model.py``
runs each record through OpenSees and prints F_max and the impacts of each, over
all contacts and at each contact, as JSON on its last line. The model's code is
:mod:`pounding.export.opensees_script`; this module writes the case's numbers before
it and chooses the analysis step (:func:`analysis_time_step`).

How the project's equations map to OpenSees, the step's convergence and the
agreement measured: docs/opensees.md.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pounding import __version__, defaults
from pounding.case.case import Case, contact_label
from pounding.errors import ArgumentError, CaseError, quote
from pounding.export.opensees_script import CONTACT_MATERIALS
from pounding.mechanics.contact import Contact, hertz_peak_penetration
from pounding.output import check_folder, write_atomic
from pounding.simulation.ground_motion import check_suite_range, ground_motion_batches, record_names
from pounding.simulation.system import check_records

__all__ = [
    "HERTZ_DURATION_FACTOR",
    "PERIOD_STEPS",
    "STEPS_PER_IMPACT",
    "OpenSeesExport",
    "analysis_time_step",
    "check_exportable",
    "export_opensees",
    "impact_duration",
    "model_script",
]

STEPS_PER_IMPACT = 500
"""Analysis steps over the shortest impact of the records, at least: from there on halving the step moved F_max
by 0.07 % at most (docs/opensees.md); at 330, by up to 0.11 %."""
PERIOD_STEPS = 1000
"""Analysis steps over the buildings' shortest natural period, at least (Newmark's period error (omega h)^2 / 12
is then 3e-6): the bound when no record pounds."""
HERTZ_DURATION_FACTOR = 2.9432
"""An undamped Hertz impact lasts this many times its peak penetration over the approach velocity [-]."""
_IMPORTS_MARKER = "# --- model.py: imports"
_CODE_MARKER = "# --- model.py: the OpenSeesPy model"
_LACKING = {
    "linear": "ViscoelasticGap pulls as an impact ends, pounding's law never does (docs/opensees.md)",
}


def check_exportable(case: Case, keys: tuple[str, ...] | None = None) -> None:
    """:class:`CaseError` naming the first contact whose law OpenSees has no material for: ``KEY.model``, ``KEY``
    the contact's key in ``keys`` (one a contact, in the case's order, as the case file names them: see
    :func:`pounding.cli.export.contact_keys`), by default ``contact`` for a case of one contact and
    ``contacts.i`` (i from 1, the case's order) for several."""
    if keys is None:
        keys = ("contact",) if len(case.contacts) == 1 else tuple(f"contacts.{i}" for i in range(1, len(case.contacts) + 1))
    for key, contact in zip(keys, case.contacts):
        if contact.model not in CONTACT_MATERIALS:
            reason = _LACKING.get(contact.model, "OpenSees has no material for it")
            raise CaseError(f"{key}.model", f"{quote(contact.model)} has no OpenSees equivalent: {reason}; use {', '.join(CONTACT_MATERIALS)}")


def impact_duration(contact: Contact, reduced_mass: float, approach_velocity: float) -> float:
    """Duration of an undamped impact of two masses of ``reduced_mass`` [kg] meeting at ``approach_velocity``
    [m/s], > 0 [s]: Hertz, 2.9432 delta_H / v (delta_H of Eq. 13); linear, pi sqrt(m / k)."""
    if not contact.law.hertzian:
        return math.pi * math.sqrt(reduced_mass / contact.stiffness)
    return HERTZ_DURATION_FACTOR * hertz_peak_penetration(approach_velocity, contact.stiffness, reduced_mass) / approach_velocity


def analysis_time_step(case: Case, record_step: float, approach_velocities) -> tuple[float, str]:
    """The OpenSees analysis step [s] and why: ``record_step`` / 2^k, the largest at most the shortest impact over
    all contacts over :data:`STEPS_PER_IMPACT` and the shortest natural period over :data:`PERIOD_STEPS`.

    ``approach_velocities`` holds, for each contact in the case's order, its fastest approach over the records
    [m/s] (0 where it never pounds); each contact's impact is taken at its own fastest approach, with the reduced
    mass of its own two floors. A single number stands for a case of one contact."""
    velocities = np.atleast_1d(np.asarray(approach_velocities, dtype=float))
    if velocities.shape != (len(case.contacts),):
        raise ArgumentError("approach_velocities", f"must hold one velocity per contact ({len(case.contacts)}), got {velocities.size}")
    period = min(float(building.periods[-1]) for building in case.buildings)
    bound, reason = period / PERIOD_STEPS, f"the shortest natural period ({period:.4g} s) over {PERIOD_STEPS}"
    for contact, velocity in zip(case.contacts, velocities):
        if not velocity > 0.0:
            continue
        duration = impact_duration(contact, case.reduced_mass_of(contact), float(velocity))
        if duration / STEPS_PER_IMPACT < bound:
            bound = duration / STEPS_PER_IMPACT
            where = f" ({contact_label(contact)})" if len(case.contacts) > 1 else ""
            reason = (f"the shortest impact of these records{where} ({1e3 * duration:.3g} ms, undamped, at its fastest approach, "
                      f"{velocity:.3g} m/s) over {STEPS_PER_IMPACT}")
    halvings = max(0, math.ceil(math.log2(record_step / bound) - 1e-12))
    return record_step / 2**halvings, f"the record step {record_step:g} s / 2^{halvings}, at most {reason}"


@dataclass(frozen=True)
class OpenSeesExport:
    """What :func:`export_opensees` wrote.

    Attributes
    ----------
    script : Path
        ``model.py``.
    record_files : tuple of Path
        The records, one file each: the ground acceleration [m/s^2], one sample a line.
    time_step : float
        The model's analysis step [s] (``TIME_STEP`` in the script).
    time_step_reason : str
        How it was chosen.
    """

    script: Path
    record_files: tuple[Path, ...]
    time_step: float
    time_step_reason: str


def _writable_folder(directory, field: str) -> Path:
    """``directory`` made if missing and proven writable (a file made and removed): :class:`ArgumentError` naming
    ``field`` where it is no folder, :class:`OSError` naming it where the system refuses (as every command's
    output: exit 1, not 2)."""
    folder = check_folder(directory, field, create=True)
    try:
        descriptor, name = tempfile.mkstemp(prefix=".pounding-export.", dir=folder)
        os.close(descriptor)
        os.unlink(name)
    except OSError as error:
        raise OSError(error.errno, f"cannot write in it: {error.strerror or error}", os.fspath(directory)) from None
    return folder


def export_opensees(case: Case, directory, records: int, seed: int = defaults.SEED, field: str = "directory") -> OpenSeesExport:
    """Write ``directory``/model.py and ``directory``/records/ for records ``0 .. records - 1`` of the study
    seeded ``seed`` (a recorded-motion case: its first ``records`` motions, as scaled).

    Parameters
    ----------
    case : Case
    directory : str or PathLike
        Made if missing.
    records : int
        Number of records, >= 1.
    seed : int
    field : str
        Names ``directory`` in errors.

    Raises
    ------
    CaseError
        A contact law OpenSees has no material for (naming ``contact.model`` or ``contacts.i.model``).
    ArgumentError
        A bad record count, or a file where the folder should be (naming ``field``).
    OSError
        The system refused to make or write the folder, naming it.
    """
    from pounding.simulation.monte_carlo import simulate  # the impacts' speeds choose the step: a few ms a record

    check_exportable(case)
    records, seed, _ = check_records(records, seed, 0)
    check_suite_range(case, records, 0)
    folder = _writable_folder(directory, field)
    # model.py comes last: an older one goes first, so a run stopped early leaves records and no model that lists them
    (folder / "model.py").unlink(missing_ok=True)
    indices = np.arange(records)
    study = simulate(case, records=records, seed=seed)
    names = record_names(case, seed, indices)
    width = len(str(records - 1))
    entries, files = [], []
    for index, name in zip(indices, names):
        _, accelerations, record_step = next(ground_motion_batches(case, seed, [index]))
        relative = f"records/record-{index:0{width}d}.txt"
        text = "\n".join(map(repr, accelerations[0].tolist())) + "\n"
        files.append(write_atomic(folder / relative, text, field, make_parents=True))
        entries.append({"file": relative, "time_step": record_step, "samples": accelerations.shape[1], "name": name})
    record_step = min(entry["time_step"] for entry in entries)
    velocities = [float(np.max(peaks.impact_velocity_max)) for peaks in study.contacts]
    time_step, reason = analysis_time_step(case, record_step, velocities)
    script = model_script(case, entries, time_step, reason, records, seed)
    path = write_atomic(folder / "model.py", script, field)
    return OpenSeesExport(path, tuple(files), time_step, reason)


def _number(value: float) -> str:
    return repr(float(value))


def _storey_lines(case: Case) -> list[str]:
    lines = ["BUILDINGS = ["]
    for number, building in enumerate(case.buildings, start=1):
        lines.append(f"    [  # building {number}, from the ground up")
        for storey, damping in zip(building.storeys, building.storey_damping()):
            bw = storey.bouc_wen
            values = {"mass": storey.mass, "stiffness": storey.stiffness, "alpha": bw.alpha, "A": bw.A, "beta": bw.beta,
                      "gamma": bw.gamma, "n": bw.n, "damping": damping}
            lines.append("        {" + ", ".join(f'"{key}": {_number(value)}' for key, value in values.items()) + "},")
        lines.append("    ],")
    lines.append("]")
    return lines


_DAMPING = {"jankowski": "xi of Eq. 5 from the restitution", "hertzdamp": "3 (1 - e^2) / 4 from the restitution",
            "hertz": "none: elastic"}


def _contact_lines(case: Case) -> list[str]:
    lines = ["CONTACTS = ["]
    for number, contact in enumerate(case.contacts, start=1):
        lines += [
            f"    {{  # contact {number}: {contact_label(contact)}",
            f'        "between": {list(contact.between)!r},  # the two neighbouring buildings, left to right',
            f'        "levels": {list(contact.levels)!r},  # the floor of the left building and the floor of the right one that meet',
            f'        "law": "{contact.model}",  # {contact.law.reference}; OpenSees: {CONTACT_MATERIALS[contact.model]}',
            f'        "gap": {_number(contact.gap)},  # [m] at rest',
            f'        "stiffness": {_number(contact.stiffness)},  # beta [N/m^1.5]',
            f'        "restitution": {_number(contact.restitution)},  # e, Eq. 6 [-]',
            f'        "damping": {_number(contact.damping_ratio())},  # {_DAMPING[contact.model]} [-]',
            f'        "reduced_mass": {_number(case.reduced_mass_of(contact))},  # m1 m2 / (m1 + m2) of the floors that meet [kg]',
            "    },",
        ]
    lines.append("]")
    return lines


def model_script(case: Case, records: list[dict], time_step: float, reason: str, count: int, seed: int) -> str:
    """The text of ``model.py``: the case's numbers (SI), then :mod:`pounding.export.opensees_script`'s code.

    ``records`` holds one dict per record: ``file`` (relative to model.py), ``time_step`` [s],
    ``samples`` and ``name``."""
    study = f"records={count}" if case.recorded else f"records={count}, seed={seed}"
    header = [
        "#!/usr/bin/env python3",
        f'"""OpenSeesPy model of the pounding case {case.name!r}, {count} record(s); written by pounding {__version__}.',
        "",
        f"Made by pounding's OpenSees export ({study}): `pounding.simulate({case.name!r}, {study})`",
        "integrates the same records (records/: the ground acceleration [m/s^2], one sample a line, from t = 0).",
        "",
        "    python model.py                 each record: a line, then one JSON object on the last line:",
        "                                    force_max [N] and impacts, one per record, over all contacts and",
        "                                    at each contact (contacts), and the fallbacks used",
        "    python model.py --check-step    also the first record at half the step: how far F_max moves",
        "",
        "Needs openseespy (pip install openseespy). Units: SI (m, kg, s, N). The equation numbers are those of",
        "Rahimi & Soltani (2016), as in pounding's documentation.",
        '"""',
        "",
    ]
    docstring_end = len(header)
    header += [
        f"CASE_NAME = {json.dumps(case.name)}",
        "",
        "# Each building's storeys from the ground up: floor mass [kg], initial storey stiffness k [N/m], the Bouc-Wen",
        "# law (Eq. 2, 36): alpha, A [-], beta, gamma [1/m^n], n [-]; the storey's dashpot c [N s/m].",
        *_storey_lines(case),
        "",
        "# The contacts, in the case's order: an impact element each between the floors that meet (Eq. 3-6, 10);",
        "# delta = x_left - x_right - gap is the penetration.",
        *_contact_lines(case),
        "",
        f"# Analysis step [s]: {reason}.",
        "# Halving it moves F_max by under 0.1 % (pounding's docs/opensees.md; `python model.py --check-step` measures it here).",
        f"TIME_STEP = {_number(time_step)}",
        "",
        "# The records: file, sampling interval [s], samples, and how pounding names them.",
        "RECORDS = [",
        *(f"    {json.dumps(entry)}," for entry in records),
        "]",
        "",
    ]
    code = Path(__file__).with_name("opensees_script.py").read_text(encoding="utf-8")
    imports = code[code.index(_IMPORTS_MARKER):code.index(_CODE_MARKER)]
    body = code[code.index(_CODE_MARKER):]
    return "\n".join(header[:docstring_end]) + "\n" + imports + "\n".join(header[docstring_end:]) + "\n" + body + (
        '\n\nif __name__ == "__main__":\n    sys.exit(main())\n')
