"""Which inputs apply as the others stand (a yield drift only where the storeys are given by it, the design
code's parameters only under a design spectrum, ...), and which are shown: those that apply, the advanced ones
only with the advanced switch on (a third building's only in a row of three). An input is named by its owner
(the model, or one of its :class:`~dashboard.inputs.BuildingInputs`) and its parameter's name."""

from __future__ import annotations

from dashboard.inputs import RECORD_SET_FORM, RECORDED_FORMS, BuildingInputs
from dashboard.row_inputs import CHOSEN_FLOORS

__all__ = ["ADVANCED", "applies", "visible"]

ADVANCED = {"contact_model", "contact_stiffness", "seed", "n", "beta_share"}
"""Inputs shown only with the advanced switch (they always apply): the contact law, the seed, and each building's
Bouc-Wen n and beta share."""

_YIELDING = ("yield drift", "yield force")


def _storey_input_applies(model, building: BuildingInputs, name: str) -> bool:
    form = building.hysteresis
    if name == "yield_drift":
        return form == "yield drift"
    if name == "yield_force":
        return form == "yield force"
    if name in ("post_yield_ratio", "beta_share"):
        return form in _YIELDING
    if name == "n":
        return form in _YIELDING or form == "Bouc-Wen"
    if name in ("alpha", "A", "beta", "gamma"):
        return form == "Bouc-Wen"
    if name == "contact_floor":  # one floor each: the floor of each building that meets its neighbours
        return model.floors_meet == CHOSEN_FLOORS and max(b.storeys for b in model.row()) > 1
    return True


def _excitation_input_applies(model, name: str) -> bool:
    form = model.ground_motion
    synthetic = form not in RECORDED_FORMS
    to_spectrum = not synthetic and model.scaling == "to the design spectrum"
    if name in ("duration", "envelope"):
        return synthetic
    if name in ("B1", "B2"):
        return synthetic and model.envelope == "shinozuka-sato"
    if name in ("intensity", "omega_g", "xi_g"):
        return form == "Kanai-Tajimi"
    if name == "pga":
        return form == "Kanai-Tajimi" and model.intensity == "PGA"
    if name == "G0":
        return form == "Kanai-Tajimi" and model.intensity == "G0"
    coded = form == "design spectrum" or to_spectrum
    if name == "code":
        return coded
    if name in ("ag", "ground_type", "spectrum_type"):
        return coded and model.code == "EN 1998-1"
    if name in ("SDS", "SD1", "TL"):
        return coded and model.code == "ASCE 7-16"
    if name in ("record_set", "component"):
        return form == RECORD_SET_FORM
    if name == "scaling":
        return not synthetic
    if name == "fit":
        return to_spectrum
    if name == "scale":
        return not synthetic and model.scaling == "scale factor"
    if name == "records_pga":
        return not synthetic and model.scaling == "PGA"
    return True


def applies(model, owner, name: str) -> bool:
    """Whether input ``name`` of ``owner`` (``model`` or one of its buildings) enters the case as the other
    inputs stand."""
    if isinstance(owner, BuildingInputs):
        return owner.number <= model.buildings_in_row and _storey_input_applies(model, owner, name)
    return _excitation_input_applies(model, name)


def visible(model, owner, name: str) -> bool:
    """Whether input ``name`` of ``owner`` is shown."""
    return applies(model, owner, name) and (model.advanced or name not in ADVANCED)
