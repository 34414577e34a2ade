"""The dashboard's model: the case's inputs as parameters, in an engineer's
terms, and what they give.

The inputs are assembled into a case file (``case_form.case_data``), in the
unit system shown, and handed to ``pounding.case.case.case_from_dict``: the library
converts units, derives and validates, and its ``CaseError`` names the field as
a case file would. Each change is computed off the event loop, the newest only
(``runner.Latest``): first the estimate (the headline), then everything the
plots show (``pounding.report.compute_snapshot``, reusing the estimate).

No Panel here: the view (``view.py``) builds widgets from these parameters.
"""

from __future__ import annotations

import contextlib
import math
import shutil
import tempfile
import tomllib
from collections.abc import Callable
from pathlib import Path

import param

from pounding import defaults
from pounding.case.case import case_from_dict, load_case
from pounding.errors import CaseError, ConvergenceError, SimulationError
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.presets import preset_names, preset_text
from pounding.report import compute_snapshot
from pounding.units import UNIT_SYSTEMS

from dashboard.case_form import case_data, chain_stiffness, values_from_case
from dashboard.display_system import display_system
from dashboard.inputs import building_params, design_params, dimensions, excitation_params
from dashboard.messages import message
from dashboard.runner import Latest
from dashboard.studies import Studies
from dashboard.visibility import applies

__all__ = ["PoundingModel"]

_FAILURES = (CaseError, ConvergenceError, SimulationError, OverflowError, ValueError)
"""What an input can make the library raise: shown as a message naming the input, never a traceback."""


class PoundingModel(Studies):
    """Inputs of a case (dimensional ones in the unit system shown) and the results for it."""

    preset = param.Selector(default=defaults.CASE, objects=preset_names(), label="case (preset)",
                            doc="A built-in case (the paper's Sections 5 and 6); every input below starts from it.")
    units = param.Selector(default="SI", objects=list(UNIT_SYSTEMS), label="units",
                           doc="Unit system of the inputs and results: SI (kN, mm) or the paper's kgf, cm, s.")
    advanced = param.Boolean(False, label="advanced inputs", doc="Show the raw Bouc-Wen form, the contact law and its stiffness.")

    locals().update(design_params())
    locals().update(building_params(1, 1.2))
    locals().update(building_params(2, 0.4))
    locals().update(excitation_params())

    # --- outputs (not inputs) ---
    result = param.Parameter(None, precedence=-1, doc="pounding.closed_form.estimator.Estimate of the current inputs, or None.")
    snapshot = param.Parameter(None, precedence=-1, doc="pounding.report.Snapshot of the current inputs (the plots), or None.")
    error = param.String("", precedence=-1, doc="Why there is no result (names the input).")
    note = param.String("", precedence=-1, doc="A change that moved another input, said once.")
    uploaded = param.List([], precedence=-1, doc="Names of the uploaded records.")

    def __init__(self, schedule: Callable | None = None, batch=None, submit: Callable | None = None, **params):
        """``schedule(fn)`` runs ``fn`` on the session's event loop (default: at once); ``batch()`` is a context
        manager around each update of the outputs; ``submit(fn)`` runs a computation (default: at once, here)."""
        super().__init__(**params)
        self._schedule = schedule or (lambda fn: fn())
        self._batch = batch or contextlib.nullcontext
        self._compute_off_loop = submit or (lambda fn: fn())
        self._latest = Latest(self._compute_off_loop, self._schedule)
        self._syncing = False
        self._extra: dict = {}
        self._description = ""
        self._preset_values: dict = {}
        self._records_folder: Path | None = None
        self._shown_units = self.units
        self._load_preset()

    # --- inputs <-> case ---------------------------------------------------------

    def input_values(self) -> dict:
        """Every input's value (dimensional ones in ``units``)."""
        return {name: getattr(self, name) for name in self.param if self.param[name].precedence is None or self.param[name].precedence >= 0}

    def case_data(self) -> dict:
        """The inputs as a case file's contents (README.md schema), in ``units``."""
        records = [path.name for path in sorted(self._records_folder.iterdir())] if self._records_folder else []
        return case_data(self.input_values(), records, self._extra, name=self.case_name(), description=self._description)

    def case_name(self) -> str:
        """The preset's name, marked when the inputs differ from it."""
        return self.preset if not self.changes() else f"{self.preset} (modified)"

    def changes(self) -> list[tuple[str, object, object, str]]:
        """The inputs that differ from the preset's: (label, preset's value, current value, unit), in ``units``."""
        shown = display_system(self.units)
        dims = dimensions(self)
        out = []
        for name, before in self._preset_values.items():
            now = getattr(self, name)
            if name.startswith("stiffness_") or not _differs(before, now) or not applies(self, name):
                continue  # the storey stiffness is derived from the period, and shown only
            unit = shown.label(**dims[name]) if name in dims else ""
            out.append((self.param[name].label, before, now, unit))
        return out

    def build_case(self, data: dict | None = None):
        """The case of the current inputs (raises CaseError naming the input)."""
        data = self.case_data() if data is None else data
        return case_from_dict(data, name=data["name"], base_directory=self._records_folder)

    def _show(self, case, data: dict) -> None:
        """Set the inputs to show ``case`` (loaded from ``data``), and compute."""
        values, extra = values_from_case(case, data, self.units)
        self._extra, self._description = extra, case.description
        self._set_quietly(values)
        self._preset_values = {name: getattr(self, name) for name in self.input_values() if name not in ("preset", "units", "advanced",
                                                                                                         "records", "seed")}
        self.recompute()

    def _load_preset(self) -> None:
        data = tomllib.loads(preset_text(self.preset))
        case = load_case(self.preset)
        self._clear_records()
        capacity = _round_up(display_system(self.units).from_si(_capacity_guess(case), force=1))
        self._set_quietly({"capacity": capacity})
        self._show(case, data)

    def load_toml(self, text: bytes | str, filename: str = "case.toml") -> None:
        """Show a case file uploaded as TOML; a bad file leaves the inputs and sets ``error`` naming it."""
        try:
            data = tomllib.loads(text.decode() if isinstance(text, bytes) else text)
            if "records" in data.get("excitation", {}):
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
        self._show(case, data)
        self.note = f"Loaded {filename}."

    def toml(self) -> str:
        """The current inputs as a TOML case file."""
        import tomli_w

        data = self.case_data()
        if self._records_folder is not None:
            data["excitation"]["records"] = [Path(p).name for p in data["excitation"]["records"]]
        return tomli_w.dumps(data)

    def upload_records(self, files: dict[str, bytes]) -> None:
        """Take uploaded records (file name -> content): they replace any uploaded before, and the ground motion
        becomes 'recorded motions'."""
        self._clear_records()
        folder = Path(tempfile.mkdtemp(prefix="pounding-records-"))
        for name, content in files.items():
            (folder / Path(name).name).write_bytes(content)
        self._records_folder = folder
        self._set_quietly({"uploaded": sorted(Path(name).name for name in files)})
        if self.ground_motion == "recorded motions":
            self.recompute()
        else:
            self.ground_motion = "recorded motions"

    def _clear_records(self) -> None:
        if self._records_folder is not None:
            shutil.rmtree(self._records_folder, ignore_errors=True)
        self._records_folder = None
        self._set_quietly({"uploaded": []})

    def _set_quietly(self, values: dict) -> None:
        """Set inputs without recomputing (a preset, a unit switch, derived values)."""
        self._syncing = True
        try:
            self.param.update(**values)
        finally:
            self._syncing = False

    @param.depends("preset", watch=True)
    def _on_preset(self):
        self._load_preset()

    @param.depends("units", watch=True)
    def _on_units(self):
        """Convert the dimensional inputs to the new unit system (the case is unchanged)."""
        old, new = display_system(self._shown_units), display_system(self.units)
        self._shown_units = self.units
        dims = dimensions(self)
        convert = lambda name, value: new.from_si(old.to_si(value, **dims[name]), **dims[name])  # noqa: E731
        self._preset_values = {name: convert(name, value) if name in dims else value for name, value in self._preset_values.items()}
        self._set_quietly({name: convert(name, getattr(self, name)) for name in dims})
        self.recompute()

    @param.depends("storeys_1", "storeys_2", watch=True)
    def _on_storeys(self):
        """More or fewer storeys keep the fundamental period: the storey stiffness follows, and the page says so
        (and where a contact floor no longer exists, that it moved)."""
        if self._syncing:
            return
        notes = [f"The storey stiffness follows the number of storeys: T1 = {self.period_1:.3g} s and T2 = {self.period_2:.3g} s are kept."]
        moved = False
        for b in (1, 2):
            count = getattr(self, f"storeys_{b}")
            if getattr(self, f"level_{b}") > count:
                self._set_quietly({f"level_{b}": count})
                notes.append(f"Building {b}'s contact floor moved to {count}: it has {count} storey(s).")
                moved = True
        self.note = " ".join(notes)
        if moved:  # the change's own computation may have run with the floor that no longer exists
            self.recompute()

    @param.depends("contact_model", watch=True)
    def _on_contact_model(self):
        """Another law reads the contact stiffness in other units (force/length^1.5 or force/length): say so."""
        if not self._syncing:
            unit = display_system(self.units).label(**dimensions(self)["contact_stiffness"])
            self.note = f"The contact stiffness is now read in {unit} ({self.contact_model} law): check its value."

    # --- outputs -------------------------------------------------------------------

    def recompute(self) -> None:
        """Compute every output for the current inputs, the newest request only: the estimate, then the plots."""
        data = self.case_data()
        self._derive_stiffness()
        self._latest.request(lambda current, deliver: self._compute(data, current, deliver))

    def _derive_stiffness(self) -> None:
        """Show each building's storey stiffness, derived from its period, mass and storeys."""
        derived = {}
        u = display_system(self.units)
        for b in (1, 2):
            try:
                stiffness = chain_stiffness(u.to_si(getattr(self, f"mass_{b}"), mass=1), getattr(self, f"period_{b}"), getattr(self, f"storeys_{b}"))
            except (ZeroDivisionError, OverflowError):
                continue
            if math.isfinite(stiffness):
                derived[f"stiffness_{b}"] = u.from_si(stiffness, force=1, length=-1)
        self._set_quietly(derived)

    def _compute(self, data: dict, current, deliver) -> None:
        """The estimate, delivered; then, once the headline is out, what the plots show (from the same pair)."""
        try:
            case = self.build_case(data)
            pair = LinearizedPair.of(case)
            result = estimate(pair, target_probability=self.target_probability)
        except _FAILURES as error:
            text = message(error)
            deliver(lambda: self._failed(text))
            return

        def plots() -> None:
            if not current():
                return
            try:
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
            self.param.update(result=result, error="")

    def _snapshot_ready(self, snapshot) -> None:
        with self._batch():
            self.snapshot = snapshot

    @param.depends(*[name for name in (set(design_params()) | set(building_params(1, 1.0)) | set(building_params(2, 1.0))
                                        | set(excitation_params())) if not name.startswith("stiffness_")],
                   "seed", watch=True)
    def _on_input(self):
        if not self._syncing:
            self.recompute()


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
