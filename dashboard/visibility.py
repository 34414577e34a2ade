"""Which inputs apply as the others stand (a yield drift only where the storeys are given by it, the design
code's parameters only under a design spectrum, ...), and which are shown: those that apply, the advanced ones
only with the advanced switch on."""

from __future__ import annotations

__all__ = ["ADVANCED", "applies", "visible"]

ADVANCED = {"contact_model", "contact_stiffness", "n_1", "n_2", "beta_share_1", "beta_share_2", "seed"}
"""Inputs shown only with the advanced switch (they always apply)."""

_YIELDING = ("yield drift", "yield force")


def _storey_input_applies(model, name: str) -> bool:
    key, b = name.rsplit("_", 1)
    form = getattr(model, f"hysteresis_{b}")
    if key == "yield_drift":
        return form == "yield drift"
    if key == "yield_force":
        return form == "yield force"
    if key in ("post_yield_ratio", "beta_share"):
        return form in _YIELDING
    if key == "n":
        return form in _YIELDING or form == "Bouc-Wen"
    if key in ("alpha", "A", "beta", "gamma"):
        return form == "Bouc-Wen"
    return True


def _excitation_input_applies(model, name: str) -> bool:
    form = model.ground_motion
    synthetic = form != "recorded motions"
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
    if name == "code":
        return form == "design spectrum"
    if name in ("ag", "ground_type", "spectrum_type"):
        return form == "design spectrum" and model.code == "EN 1998-1"
    if name in ("SDS", "SD1", "TL"):
        return form == "design spectrum" and model.code == "ASCE 7-16"
    if name == "scaling":
        return form == "recorded motions"
    if name == "scale":
        return form == "recorded motions" and model.scaling == "scale factor"
    if name == "records_pga":
        return form == "recorded motions" and model.scaling == "PGA"
    return True


_EXCITATION = {"duration", "envelope", "B1", "B2", "intensity", "omega_g", "xi_g", "pga", "G0", "code", "ag", "ground_type",
               "spectrum_type", "SDS", "SD1", "TL", "scaling", "scale", "records_pga"}
_STOREY = {"yield_drift", "yield_force", "post_yield_ratio", "beta_share", "n", "alpha", "A", "beta", "gamma"}


def applies(model, name: str) -> bool:
    """Whether input ``name`` enters the case as the other inputs stand."""
    if name in _EXCITATION:
        return _excitation_input_applies(model, name)
    if name.rsplit("_", 1)[0] in _STOREY and name[-1] in "12":
        return _storey_input_applies(model, name)
    if name in ("level_1", "level_2"):
        return max(model.storeys_1, model.storeys_2) > 1
    return True


def visible(model, name: str) -> bool:
    """Whether input ``name`` is shown."""
    return applies(model, name) and (model.advanced or name not in ADVANCED)
