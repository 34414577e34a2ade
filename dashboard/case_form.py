"""The dashboard's inputs as a case file, and a case file as the dashboard's
inputs: pure functions between a dict of input values (in the unit system
shown) and the case file's schema (README.md), so the library converts, derives
and validates, and a bad input is named as a case file would name it."""

from __future__ import annotations

import math

from pounding.case.case import Case
from pounding.errors import CaseError
from pounding.hazard.excitation import CloughPenzien
from pounding.units import STANDARD_GRAVITY

from dashboard.display_system import display_system
from dashboard.inputs import dimensions

__all__ = ["case_data", "chain_stiffness", "values_from_case"]

_CODES = {"EN 1998-1": "ec8", "ASCE 7-16": "asce7-16"}
_SAMPLING = ("time_step", "cutoff_frequency", "synthesis_factor")


def chain_stiffness(mass: float, period: float, storeys: int) -> float:
    """The storey stiffness of ``storeys`` equal storeys of floor mass ``mass`` with fundamental period ``period``:
    the fixed-free chain's lowest eigenvalue is (k / m) 4 sin^2(pi / (4 N + 2))."""
    return mass * (2.0 * math.pi / period) ** 2 / (4.0 * math.sin(math.pi / (4 * storeys + 2)) ** 2)


def _hysteresis(v: dict, b: int) -> dict:
    form = v[f"hysteresis_{b}"]
    if form == "elastic":
        return {"bouc_wen": {"alpha": 1.0}}
    if form == "Bouc-Wen":
        return {"bouc_wen": {key: v[f"{key}_{b}"] for key in ("alpha", "A", "beta", "gamma", "n")}}
    given = {"yield drift": "yield_drift", "yield force": "yield_force"}[form]
    return {"hysteresis": {given: v[f"{given}_{b}"], "post_yield_ratio": v[f"post_yield_ratio_{b}"], "n": v[f"n_{b}"],
                           "beta_share": v[f"beta_share_{b}"]}}


def _excitation(v: dict, records: list[str], extra: dict) -> dict:
    form = v["ground_motion"]
    if form == "recorded motions":
        table = {"records": list(records)}
        if v["scaling"] == "scale factor":
            table["scale"] = v["scale"]
        elif v["scaling"] == "PGA":
            table["pga"] = v["records_pga"]
        return table
    common = {"duration": v["duration"], "envelope": v["envelope"], **{k: extra[k] for k in _SAMPLING if k in extra}}
    if v["envelope"] == "shinozuka-sato":
        common |= {"B1": v["B1"], "B2": v["B2"]}
    if form == "design spectrum":
        code = _CODES[v["code"]]
        parameters = ({"ag": v["ag"], "ground_type": v["ground_type"], "spectrum_type": v["spectrum_type"]} if code == "ec8"
                      else {"SDS": v["SDS"], "SD1": v["SD1"], "TL": v["TL"]})
        return {"spectrum": "design", "code": code, **parameters, **common}
    spectrum = {"spectrum": extra.get("spectrum", "kanai-tajimi"), "omega_g": v["omega_g"], "xi_g": v["xi_g"]}
    if spectrum["spectrum"] == "clough-penzien":
        spectrum |= {"omega_f": extra["omega_f"], "xi_f": extra["xi_f"]}
    spectrum |= {"pga": v["pga"]} if v["intensity"] == "PGA" else {"G0": v["G0"]}
    return {**spectrum, **common}


def case_data(v: dict, records: list[str] = (), extra: dict | None = None, name: str = "case", description: str = "") -> dict:
    """The case file of the input values ``v`` (units as ``v["units"]``); ``records`` the uploaded files' paths,
    ``extra`` what a loaded case had that the dashboard does not show (the records' sampling, a Clough-Penzien filter)."""
    extra = extra or {}
    shown = display_system(v["units"])
    v = {**v, **{name: shown.to_file(v[name], **dims) for name, dims in dimensions(v).items()}}  # in the file's units
    buildings = []
    for b in (1, 2):
        count = v[f"storeys_{b}"]
        storey = {"mass": v[f"mass_{b}"], **_hysteresis(v, b)}
        if count == 1:
            storeys = [{**storey, "period": v[f"period_{b}"]}]
        else:
            stiffness = chain_stiffness(v[f"mass_{b}"], v[f"period_{b}"], count)
            storeys = [{**storey, "stiffness": stiffness} for _ in range(count)]
        buildings.append({"damping_ratio": v[f"damping_ratio_{b}"], "storeys": storeys})
    return {
        "units": shown.file_units, "name": name, "description": description,
        "excitation": _excitation(v, list(records), extra),
        "buildings": buildings,
        "contact": {"model": v["contact_model"], "gap": v["gap"], "stiffness": v["contact_stiffness"],
                    "restitution": v["restitution"], "levels": [v["level_1"], v["level_2"]]},
    }


def _building_values(case: Case, units: str, data: dict) -> dict:
    u = display_system(units)
    out = {}
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
        out |= {
            f"storeys_{b}": building.n_storeys,
            f"period_{b}": float(building.periods[0]),
            f"mass_{b}": u.from_si(first.mass, mass=1),
            f"stiffness_{b}": u.from_si(first.stiffness, force=1, length=-1),
            f"damping_ratio_{b}": building.damping_ratio,
            f"hysteresis_{b}": form,
            f"alpha_{b}": bw.alpha, f"A_{b}": bw.A, f"n_{b}": bw.n,
            f"beta_{b}": u.from_si(bw.beta, length=-bw.n), f"gamma_{b}": u.from_si(bw.gamma, length=-bw.n),
        }
        if form != "elastic" and total > 0:
            out |= {f"post_yield_ratio_{b}": bw.alpha, f"beta_share_{b}": max(0.5, bw.beta / total),
                    f"yield_drift_{b}": u.from_si(first.yield_drift, length=1), f"yield_force_{b}": u.from_si(first.yield_force, force=1)}
    return out


def _excitation_values(case: Case, data: dict, units: str) -> tuple[dict, dict]:
    """The ground motion's input values, and the extras to keep (sampling, a Clough-Penzien filter)."""
    table = data["excitation"]
    u = display_system(units)
    excitation = case.excitation
    extra = {key: getattr(excitation, key) for key in _SAMPLING} if "records" not in table else {}
    values = {"duration": excitation.duration, "envelope": "none" if excitation.stationary else "shinozuka-sato"}
    if excitation.envelope is not None:
        values |= {"B1": excitation.envelope.B1, "B2": excitation.envelope.B2}
    if "records" in table:
        scaling = "scale factor" if "scale" in table else "PGA" if "pga" in table else "as recorded"
        values |= {"ground_motion": "recorded motions", "scaling": scaling}
        values |= {"scale": table["scale"]} if "scale" in table else {"records_pga": table["pga"]} if "pga" in table else {}
        return values, extra
    if table.get("spectrum") == "design":
        code = table.get("code")
        if code not in _CODES.values():
            raise CaseError("excitation.code", f"the dashboard takes EN 1998-1 and ASCE 7-16 spectra, not {code!r}; use the command line")
        values |= {"ground_motion": "design spectrum", "code": {c: n for n, c in _CODES.items()}[code]}
        keys = ("ag", "ground_type", "spectrum_type") if code == "ec8" else ("SDS", "SD1", "TL")
        values |= {key: table[key] for key in keys if key in table}
        return values, extra
    spectrum = excitation.spectrum
    if isinstance(spectrum, CloughPenzien):
        extra |= {"spectrum": "clough-penzien", "omega_f": spectrum.omega_f, "xi_f": spectrum.xi_f}
    from pounding.random_vibration.peak_factors import expected_peak_ground_acceleration

    values |= {"ground_motion": "Kanai-Tajimi", "intensity": "PGA" if "pga" in table else "G0",
               "G0": u.from_si(spectrum.G0, length=2), "omega_g": spectrum.omega_g, "xi_g": spectrum.xi_g,
               "pga": expected_peak_ground_acceleration(excitation) / STANDARD_GRAVITY}
    return values, extra


def values_from_case(case: Case, data: dict, units: str) -> tuple[dict, dict]:
    """The input values showing ``case`` (loaded from the case file ``data``) in ``units``, and the extras to keep.

    Raises :class:`CaseError` for what the dashboard cannot show (storeys that differ, a tabulated spectrum)."""
    u = display_system(units)
    contact = case.contact
    values = _building_values(case, units, data)
    excitation, extra = _excitation_values(case, data, units)
    values |= excitation
    values |= {
        "level_1": contact.levels[0], "level_2": contact.levels[1],
        "gap": u.from_si(contact.gap, length=1),
        "contact_stiffness": u.from_si(contact.stiffness, force=1, length=-contact.stiffness_exponent),
        "restitution": contact.restitution, "contact_model": contact.model,
    }
    return values, extra
