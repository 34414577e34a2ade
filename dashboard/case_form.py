"""The dashboard's inputs as a case file, and a case file as the dashboard's
inputs: pure functions between the inputs (:class:`~dashboard.inputs.CaseInputs`
and the row's :class:`~dashboard.inputs.BuildingInputs`, in the unit system shown) and
the case file's schema (README.md), so the library converts, derives and
validates, and a bad input is named as a case file would name it."""

from __future__ import annotations

import math

from dashboard.inputs import (
    DESIGN_CODE_KEYS,
    RECORD_SET_FORM,
    RECORDED_FORMS,
    SPECTRUM_FITS,
    BuildingInputs,
    CaseInputs,
)
from dashboard.row_inputs import contacts_of_inputs, floors_of_case
from pounding.case.case import Case
from pounding.display_units import Display, display
from pounding.errors import CaseError
from pounding.hazard.excitation import CloughPenzien
from pounding.units import STANDARD_GRAVITY

__all__ = ["case_file_of_inputs", "chain_stiffness", "inputs_of_case"]

_SAMPLING = ("time_step", "cutoff_frequency", "synthesis_factor")


def chain_stiffness(mass: float, period: float, storeys: int) -> float:
    """The storey stiffness of ``storeys`` equal storeys of floor mass ``mass`` with fundamental period ``period``:
    the fixed-free chain's lowest eigenvalue is (k / m) 4 sin^2(pi / (4 N + 2))."""
    return mass * (2.0 * math.pi / period) ** 2 / (4.0 * math.sin(math.pi / (4 * storeys + 2)) ** 2)


def _in_file_units(inputs, shown: Display) -> dict:
    """The values of the inputs of ``inputs`` (one building, or the case's) with the dimensional ones in the
    case file's units."""
    dims = inputs.dimensions()
    return {name: shown.to_file(getattr(inputs, name), **dims[name]) if name in dims else getattr(inputs, name)
            for name in inputs.param}


def _hysteresis(b: dict) -> dict:
    """A storey's hysteresis table, ``b`` its building's input values in the file's units."""
    form = b["hysteresis"]
    if form == "elastic":
        return {"bouc_wen": {"alpha": 1.0}}
    if form == "Bouc-Wen":
        return {"bouc_wen": {key: b[key] for key in ("alpha", "A", "beta", "gamma", "n")}}
    given = {"yield drift": "yield_drift", "yield force": "yield_force"}[form]
    return {"hysteresis": {given: b[given], "post_yield_ratio": b["post_yield_ratio"], "n": b["n"], "beta_share": b["beta_share"]}}


def _building_table(building: BuildingInputs, shown: Display) -> dict:
    """The case file's table of one building: every storey alike."""
    b = _in_file_units(building, shown)
    storey = {"mass": b["mass"], **_hysteresis(b)}
    if b["storeys"] == 1:
        storeys = [{**storey, "period": b["period"]}]
    else:
        stiffness = chain_stiffness(b["mass"], b["period"], b["storeys"])
        storeys = [{**storey, "stiffness": stiffness} for _ in range(b["storeys"])]
    return {"damping_ratio": b["damping_ratio"], "storeys": storeys}


def _code_table(v: dict) -> dict:
    """``code`` and its parameters, as ``spectrum = "design"`` and ``[excitation.scale_to]`` take them."""
    code = DESIGN_CODE_KEYS[v["code"]]
    parameters = ({"ag": v["ag"], "ground_type": v["ground_type"], "spectrum_type": v["spectrum_type"]} if code == "ec8"
                  else {"SDS": v["SDS"], "SD1": v["SD1"], "TL": v["TL"]})
    return {"code": code, **parameters}


def _recorded(v: dict, records: list[str]) -> dict:
    if v["ground_motion"] == RECORD_SET_FORM:
        table = {"records": f"fema-p695:{v['record_set']}", "component": v["component"]}
    else:
        table = {"records": list(records)}
    if v["scaling"] == "scale factor":
        table["scale"] = v["scale"]
    elif v["scaling"] == "PGA":
        table["pga"] = v["records_pga"]
    elif v["scaling"] == "to the design spectrum":
        table["scale_to"] = {**_code_table(v), "fit": SPECTRUM_FITS[v["fit"]]}
    return table


def _excitation(v: dict, records: list[str], extra: dict) -> dict:
    form = v["ground_motion"]
    if form in RECORDED_FORMS:
        return _recorded(v, records)
    common = {"duration": v["duration"], "envelope": v["envelope"], **{k: extra[k] for k in _SAMPLING if k in extra}}
    if v["envelope"] == "shinozuka-sato":
        common |= {"B1": v["B1"], "B2": v["B2"]}
    if form == "design spectrum":
        return {"spectrum": "design", **_code_table(v), **common}
    spectrum = {"spectrum": extra.get("spectrum", "kanai-tajimi"), "omega_g": v["omega_g"], "xi_g": v["xi_g"]}
    if spectrum["spectrum"] == "clough-penzien":
        spectrum |= {"omega_f": extra["omega_f"], "xi_f": extra["xi_f"]}
    spectrum |= {"pga": v["pga"]} if v["intensity"] == "PGA" else {"G0": v["G0"]}
    return {**spectrum, **common}


def case_file_of_inputs(inputs: CaseInputs, buildings: tuple[BuildingInputs, ...], units: str, records: list[str] = (),
                        extra: dict | None = None, name: str = "case", description: str = "", changed=()) -> dict:
    """The case file of ``inputs`` and ``buildings`` (the row's, left to right, typed in ``units``); ``records`` the
    uploaded files' paths, ``extra`` what a loaded case had that the dashboard does not show (the records' sampling, a
    Clough-Penzien filter, an uploaded file's own contacts); ``changed`` the inputs of the contact law changed since
    (:func:`~dashboard.row_inputs.contacts_of_inputs`)."""
    extra = extra or {}
    shown = display(units)
    v = _in_file_units(inputs, shown)
    contacts = contacts_of_inputs(v, [b.contact_floor for b in buildings], [b.storeys for b in buildings], shown.system,
                                  extra.get("contacts"), changed)
    return {
        "units": shown.system.name, "name": name, "description": description,
        "excitation": _excitation(v, list(records), extra),
        "buildings": [_building_table(building, shown) for building in buildings],
        **contacts,
    }


def _building_values(case: Case, units: str, data: dict) -> list[dict]:
    """The input values of each building showing ``case``'s (each storey alike) in ``units``; its contact floor the
    last one of its contacts names."""
    u = display(units)
    floors = {}
    for contact in case.contacts:
        floors.update(zip(contact.between, contact.levels))
    out = []
    for b, building in enumerate(case.buildings, start=1):
        storeys = building.storeys
        first = storeys[0]
        if any(s != first for s in storeys[1:]):
            raise CaseError(f"buildings.{b}.storeys", "the dashboard takes buildings whose storeys are all alike; use the command line")
        bw = first.bouc_wen
        given = data["buildings"][b - 1]["storeys"][0]
        if bw.alpha == 1.0:
            form = "elastic"
        elif bw.A != 1.0:
            form = "Bouc-Wen"
        else:
            form = "yield force" if "yield_force" in given.get("hysteresis", {}) else "yield drift"
        total = bw.beta + bw.gamma
        values = {
            "storeys": building.n_storeys,
            "period": float(building.periods[0]),
            "mass": u.from_si(first.mass, mass=1),
            "stiffness": u.from_si(first.stiffness, force=1, length=-1),
            "damping_ratio": building.damping_ratio,
            "hysteresis": form,
            "alpha": bw.alpha, "A": bw.A, "n": bw.n,
            "beta": u.from_si(bw.beta, length=-bw.n), "gamma": u.from_si(bw.gamma, length=-bw.n),
            "contact_floor": floors.get(b, 1),
        }
        if form != "elastic" and total > 0:
            values |= {"post_yield_ratio": bw.alpha, "beta_share": max(0.5, bw.beta / total),
                       "yield_drift": u.from_si(first.yield_drift, length=1), "yield_force": u.from_si(first.yield_force, force=1)}
        out.append(values)
    return out


def _code_values(table: dict, where: str) -> dict:
    code = table.get("code")
    if code not in DESIGN_CODE_KEYS.values():
        raise CaseError(f"{where}.code", f"the dashboard takes EN 1998-1 and ASCE 7-16 spectra, not {code!r}; use the command line")
    keys = ("ag", "ground_type", "spectrum_type") if code == "ec8" else ("SDS", "SD1", "TL")
    return {"code": {c: n for n, c in DESIGN_CODE_KEYS.items()}[code]} | {key: table[key] for key in keys if key in table}


def _recorded_values(table: dict) -> dict:
    """The inputs of recorded motions (files or a FEMA P695 set) and their scaling."""
    scaling = ("scale factor" if "scale" in table else "PGA" if "pga" in table
               else "to the design spectrum" if "scale_to" in table else "as recorded")
    values = {"ground_motion": "recorded motions", "scaling": scaling}
    entries = table["records"] if isinstance(table["records"], list) else [table["records"]]
    if len(entries) == 1 and str(entries[0]).startswith("fema-p695:"):
        values |= {"ground_motion": RECORD_SET_FORM, "record_set": entries[0].split(":", 1)[1],
                   "component": table.get("component", "both")}
    if "scale" in table:
        values["scale"] = table["scale"]
    elif "pga" in table:
        values["records_pga"] = table["pga"]
    elif "scale_to" in table:
        values |= _code_values(table["scale_to"], "excitation.scale_to")
        values["fit"] = {key: name for name, key in SPECTRUM_FITS.items()}[table["scale_to"].get("fit", "not-below")]
    return values


def _excitation_values(case: Case, data: dict, units: str) -> tuple[dict, dict]:
    """The ground motion's input values, and the extras to keep (sampling, a Clough-Penzien filter)."""
    table = data["excitation"]
    u = display(units)
    excitation = case.excitation
    extra = {key: getattr(excitation, key) for key in _SAMPLING} if "records" not in table else {}
    if "records" in table:  # the duration and the envelope are the records' own (S3-S5)
        return {"duration": excitation.duration} | _recorded_values(table), extra
    values = {"duration": excitation.duration, "envelope": "none" if excitation.stationary else "shinozuka-sato"}
    if excitation.envelope is not None:
        values |= {"B1": excitation.envelope.B1, "B2": excitation.envelope.B2}
    if table.get("spectrum") == "design":
        return values | {"ground_motion": "design spectrum"} | _code_values(table, "excitation"), extra
    spectrum = excitation.spectrum
    if isinstance(spectrum, CloughPenzien):
        extra |= {"spectrum": "clough-penzien", "omega_f": spectrum.omega_f, "xi_f": spectrum.xi_f}
    from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration

    values |= {"ground_motion": "Kanai-Tajimi", "intensity": "PGA" if "pga" in table else "G0",
               "G0": u.from_si(spectrum.G0, length=2), "omega_g": spectrum.omega_g, "xi_g": spectrum.xi_g,
               "pga": expected_peak_ground_acceleration(excitation) / STANDARD_GRAVITY}
    return values, extra


def inputs_of_case(case: Case, data: dict, units: str) -> tuple[dict, list[dict], dict]:
    """The input values showing ``case`` (loaded from the case file ``data``) in ``units``: the case's (ground
    motion, which floors meet, the gap and contact law: its first contact's), each building's, and the extras to keep
    (an uploaded file's own contacts, where no choice of floors describes them).

    Raises :class:`CaseError` for what the dashboard cannot show (storeys that differ, a tabulated spectrum, more
    than three buildings)."""
    u = display(units)
    contact = case.contacts[0]
    floors, own = floors_of_case(case, data)
    buildings = _building_values(case, units, data)
    values, extra = _excitation_values(case, data, units)
    values |= {
        "buildings_in_row": len(case.buildings), "floors_meet": floors,
        "gap": u.from_si(contact.gap, length=1),
        "contact_stiffness": u.from_si(contact.stiffness, force=1, length=-contact.stiffness_exponent),
        "restitution": contact.restitution, "contact_model": contact.model,
    }
    if own is not None:
        extra["contacts"] = own
    return values, buildings, extra
