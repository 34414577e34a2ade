"""The report's inputs as a table of parameter, value and unit: every storey
of both buildings, the contact, and the excitation in the form the case gave
it (a random process by G0 or PGA, a design spectrum with its code's
parameters, recorded motions). Lengths and forces in the report's display
units, other quantities in its unit system."""

from __future__ import annotations

import html

from pounding.case.case import Case
from pounding.case.engineering import engineering_terms
from pounding.display_units import display
from pounding.hazard.design_spectra import ASCE7Spectrum, Eurocode8Spectrum
from pounding.hazard.filter_bank import FilterBank
from pounding.hazard.sources import DesignSpectrum
from pounding.units import STANDARD_GRAVITY

__all__ = ["SPECTRUM_NAMES", "code_parameters", "input_rows", "inputs_html"]

_G = STANDARD_GRAVITY
SPECTRUM_NAMES = {"KanaiTajimi": "Kanai-Tajimi", "CloughPenzien": "Clough-Penzien"}
"""Names of the random processes, by class name."""


def _number(value: float) -> str:
    """4 significant digits; 39,240 rather than 3.924e+04 between 10^4 and 10^8."""
    if 1e4 <= abs(value) < 1e8:
        return f"{value:,.0f}"
    return f"{value:.4g}"


def input_rows(case: Case, units: str = "SI", terms: dict | None = None) -> list[tuple[str, str, str] | str]:
    """The inputs as rows (parameter, value, unit); a plain string starts a group ("Building 1")."""
    d = display(units)
    u = d.system
    terms = terms or engineering_terms(case)
    storeys = {(s["building"], s["storey"]): s for s in terms["storeys"]}
    rows: list = []
    for number, building in enumerate(case.buildings, start=1):
        rows.append(f"Building {number}")
        rows += [("storeys", str(building.n_storeys), "-"),
                 (f"fundamental period T{number}", _number(building.periods[0]), "s"),
                 ("damping ratio", f"{building.damping_ratio:g}", "-")]
        for level, storey in enumerate(building.storeys, start=1):
            law, derived = storey.bouc_wen, storeys[(number, level)]
            where = f"storey {level}: "
            rows += [
                (where + "mass", _number(u.from_si(storey.mass, mass=1)), u.mass_label),
                (where + "stiffness", _number(u.from_si(storey.stiffness, force=1, length=-1)), u.label(force=1, length=-1)),
                (where + "yield drift", _yield(derived["yield_drift"], d.length_scale), d.length_unit),
                (where + "yield force", _yield(derived["yield_force"], d.force_scale), d.force_unit),
                (where + "post-yield ratio (Bouc-Wen alpha)", f"{law.alpha:g}", "-"),
                (where + "Bouc-Wen A, n", f"{law.A:g}, {law.n:g}", "-"),
                (where + "Bouc-Wen beta, gamma", f"{_number(u.from_si(law.beta, length=-law.n))}, "
                 f"{_number(u.from_si(law.gamma, length=-law.n))}", u.label(length=-law.n)),
            ]
            if storey.damping is not None:
                rows.append((where + "damping coefficient", _number(u.from_si(storey.damping, force=1, length=-1)),
                             u.label(force=1, length=-1, time=1)))
    several = len(case.contacts) > 1
    for number, c in enumerate(case.contacts, start=1):
        exponent = c.stiffness_exponent
        (left, right), where = c.between, f"contact {number}: " if several else ""
        rows += [
            f"Contact {number}: buildings {left}-{right}, floors {c.levels[0]}/{c.levels[1]}" if several else "Contact",
            (where + "contact law", c.model, ""),
            (where + "gap", _number(c.gap / d.length_scale), d.length_unit),
            (where + "contact stiffness", _number(u.from_si(c.stiffness, force=1, length=-exponent)), u.label(force=1, length=-exponent)),
            (where + "coefficient of restitution e", f"{c.restitution:g}", "-"),
            (where + f"contact floors (building {left}, building {right})", f"{c.levels[0]}, {c.levels[1]}", "-"),
        ]
    rows.append("Excitation")
    rows += _excitation_rows(case, units, terms)
    return rows


def _yield(value: float | None, scale: float) -> str:
    return "elastic" if value is None else _number(value / scale)


def _excitation_rows(case: Case, units: str, terms: dict) -> list[tuple[str, str, str]]:
    u = display(units).system
    excitation, spectrum, hazard = case.excitation, case.excitation.spectrum, case.hazard
    motion = terms["ground_motion"]
    rows = []
    if case.recorded:
        fitted = hazard.fitted
        rows += [("form", "recorded motions", ""),
                 ("records", f"{len(hazard.records)}: {', '.join(hazard.names[:6])}{', ...' if len(hazard.records) > 6 else ''}", ""),
                 ("scaling", hazard.scaling, ""),
                 ("records' mean PGA", _number(motion["records_pga_mean"] / _G), "g"),
                 ("spectrum describing the records", SPECTRUM_NAMES.get(type(fitted.spectrum).__name__, ""), ""),
                 (f"significant duration ({fitted.duration_definition})", f"{fitted.duration:.4g}", "s")]
        if hazard.suite is not None:
            rows.append(("the closed form's process", hazard.suite.describe(), ""))
    elif isinstance(hazard, DesignSpectrum):
        rows += [("form", "design spectrum", "")] + code_parameters(hazard)
        rows.append(("compatible filter bank (both methods)", f"{len(spectrum.frequencies)} band-pass filtered white noises", ""))
    if not isinstance(spectrum, FilterBank):
        name = SPECTRUM_NAMES.get(type(spectrum).__name__, type(spectrum).__name__)
        if not case.recorded:
            rows.append(("form", f"{name} random process", ""))
        rows += [("G0 (intensity)", _number(u.from_si(spectrum.G0, length=2)), u.label(length=2, time=-3)),
                 ("omega_g, xi_g", f"{_number(spectrum.omega_g)}, {_number(spectrum.xi_g)}", "rad/s, -")]
        if hasattr(spectrum, "omega_f"):
            rows.append(("omega_f, xi_f (Clough-Penzien filter)", f"{_number(spectrum.omega_f)}, {_number(spectrum.xi_f)}", "rad/s, -"))
    if not case.recorded:
        rows.append(("duration", f"{excitation.duration:g}", "s"))
        envelope = excitation.envelope
        rows.append(("envelope", "none (stationary)" if envelope is None else
                     f"Shinozuka-Sato, B1 = {envelope.B1:g}, B2 = {envelope.B2:g}", "" if envelope is None else "1/s"))
    rows += [("expected PGA of the records", _number(motion["pga_expected"] / _G), "g"),
             ("RMS ground acceleration", _number(motion["rms_acceleration"] / _G), "g"),
             ("time step, cutoff frequency", f"{excitation.time_step:g}, {_number(excitation.cutoff_frequency)}", "s, rad/s")]
    return rows


def code_parameters(hazard: DesignSpectrum) -> list[tuple[str, str, str]]:
    """The design spectrum's code and parameters as (parameter, value, unit) rows; accelerations in g."""
    target = hazard.target
    if isinstance(target, Eurocode8Spectrum):
        s, tb, tc, td = target.parameters
        return [("code", "EN 1998-1", ""), ("a_g", _number(target.ag / _G), "g"),
                ("ground type, spectrum type", f"{target.ground_type}, {target.spectrum_type}", "-"),
                ("S, T_B, T_C, T_D", f"{s:g}, {tb:g}, {tc:g}, {td:g}", "-, s, s, s")]
    if isinstance(target, ASCE7Spectrum):
        return [("code", "ASCE 7-16", ""), ("S_DS, S_D1", f"{_number(target.SDS / _G)}, {_number(target.SD1 / _G)}", "g"),
                ("T_L (T_0, T_S)", f"{target.TL:g} ({target.T0:.3g}, {target.TS:.3g})", "s")]
    return [("code", "tabulated spectrum", ""),
            ("periods", ", ".join(f"{p:g}" for p in target.periods), "s"),
            ("Sa (5 % damping)", ", ".join(_number(a / _G) for a in target.accelerations), "g")]


def inputs_html(case: Case, units: str = "SI", terms: dict | None = None) -> str:
    """The inputs table: parameter, value, unit; one group of rows per building, the contact, the excitation."""
    body = []
    for row in input_rows(case, units, terms):
        if isinstance(row, str):
            body.append(f'<tr class="group"><th colspan="3">{html.escape(row)}</th></tr>')
        else:
            parameter, value, unit = row
            body.append(f'<tr><td>{html.escape(parameter)}</td><td class="value">{html.escape(value)}</td>'
                        f"<td>{html.escape(unit)}</td></tr>")
    return ('<table class="inputs"><thead><tr><th>parameter</th><th>value</th><th>unit</th></tr></thead><tbody>'
            + "".join(body) + "</tbody></table>")
