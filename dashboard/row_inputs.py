"""Which floors meet, as the dashboard's inputs give them and a case file writes them: pure functions between the
inputs (the number of buildings, :data:`FLOORS_MEET`, each building's contact floor, one gap and contact law) and
the case file's ``[contact]`` table or ``[[contacts]]`` array (README.md, "Rows of buildings"). The library expands
``levels = "aligned"`` and checks every contact; a case file whose contacts no choice describes (floors of its own,
a gap or a law per contact) is kept as written (:data:`AS_IN_FILE`), and an input changed on the page applies to
every contact."""

from __future__ import annotations

from pounding.case.case import ALIGNED, Case, case_from_dict
from pounding.errors import CaseError
from pounding.mechanics.contact import contact_law
from pounding.units import UnitSystem, unit_system

__all__ = ["ALIGNED_FLOORS", "AS_IN_FILE", "CHOSEN_FLOORS", "FLOORS_MEET", "LAW_KEYS", "ROOF", "contacts_of_inputs",
           "floors_of_case"]

ALIGNED_FLOORS = "aligned floors"
"""Every floor two neighbours share, floor k with floor k (equal storey heights): the default."""
ROOF = "roof of the lower building"
"""The lower building's roof against the floor of its neighbour at the same height (equal storey heights)."""
CHOSEN_FLOORS = "one floor each"
"""One contact between neighbours, at the floor of each that the building's 'contact floor' names."""
AS_IN_FILE = "as in the case file"
"""The uploaded case file's own contacts (offered only while its case is shown)."""
FLOORS_MEET = (ALIGNED_FLOORS, ROOF, CHOSEN_FLOORS)
"""The choices of which floors meet, the default first."""
LAW_KEYS = {"gap": "gap", "contact_model": "model", "contact_stiffness": "stiffness", "restitution": "restitution"}
"""The inputs that apply to every contact, and their key in a contact's table."""


def _law(values: dict) -> dict:
    """A contact's gap and law from the inputs' values ``values`` (in the case file's units)."""
    return {key: values[name] for name, key in LAW_KEYS.items()}


def contacts_of_inputs(values: dict, floors: list[int], storeys: list[int], system: UnitSystem,
                       file_contacts: list | None = None, changed=()) -> dict:
    """The case file's contacts: ``{"contact": {...}}`` where they come to one contact between two buildings, else
    ``{"contacts": [...]}``. ``values`` are the case's input values in the case file's units ``system``
    (``floors_meet``, the gap and the law), ``floors`` each building's contact floor, ``storeys`` each building's
    storeys, left to right. For :data:`AS_IN_FILE`, ``file_contacts`` are the uploaded file's own contacts (SI,
    :func:`floors_of_case`), each as written but for the inputs named in ``changed`` (:data:`LAW_KEYS`), which the
    page changed and which apply to every contact."""
    law = _law(values)
    choice = values["floors_meet"]
    pairs = [(b, b + 1) for b in range(1, len(storeys))]
    if choice == AS_IN_FILE and file_contacts:
        return {"contacts": [_in_file_units(contact, system) | {LAW_KEYS[name]: law[LAW_KEYS[name]] for name in changed}
                             for contact in file_contacts]}
    if choice == ROOF:
        levels = [[min(storeys[left - 1], storeys[right - 1])] * 2 for left, right in pairs]
    elif choice == CHOSEN_FLOORS:
        levels = [[floors[left - 1], floors[right - 1]] for left, right in pairs]
    else:
        levels = [[1, 1] if min(storeys[left - 1], storeys[right - 1]) == 1 else ALIGNED for left, right in pairs]
    if len(pairs) == 1 and levels[0] != ALIGNED:
        return {"contact": {**law, "levels": levels[0]}}
    return {"contacts": [{"between": list(pair), "levels": level, **law} for pair, level in zip(pairs, levels)]}


def _in_file_units(contact: dict, system: UnitSystem) -> dict:
    """A contact kept in SI (:func:`floors_of_case`) as a case file's table in ``system``."""
    exponent = contact_law(contact["model"]).stiffness_exponent
    return {**contact, "gap": system.from_si(contact["gap"], length=1),
            "stiffness": system.from_si(contact["stiffness"], force=1, length=-exponent)}


_STAND_IN = {"spectrum": "kanai-tajimi", "G0": 1.0, "omega_g": 15.0, "xi_g": 0.6, "duration": 10.0}
"""An excitation for reading only a case file's buildings and contacts."""


def floors_of_case(case: Case, data: dict) -> tuple[str, list[dict] | None]:
    """Which floors of ``case`` (loaded from the case file ``data``) meet, as the inputs say it: one of
    :data:`FLOORS_MEET` where it gives exactly the case's contacts with one gap and law (the library reads the
    choice's contacts); else :data:`AS_IN_FILE` and the contacts as written, in SI.

    Raises :class:`CaseError` for a row the dashboard does not take (more than three buildings)."""
    if len(case.buildings) > 3:
        raise CaseError("buildings", f"the dashboard takes two or three buildings, this case has {len(case.buildings)}; "
                                     "use the command line")
    first = case.contacts[0]
    same_law = all((c.gap, c.model, c.stiffness, c.restitution) == (first.gap, first.model, first.stiffness, first.restitution)
                   for c in case.contacts)
    found = [(c.between, c.levels) for c in case.contacts]
    storeys = [b.n_storeys for b in case.buildings]
    floors = [1] * len(storeys)
    for c in case.contacts:
        for building, level in zip(c.between, c.levels):
            floors[building - 1] = level
    system = unit_system(data.get("units", "SI"))
    law = {"gap": system.from_si(first.gap, length=1), "contact_model": first.model, "restitution": first.restitution,
           "contact_stiffness": system.from_si(first.stiffness, force=1, length=-first.stiffness_exponent)}
    for choice in FLOORS_MEET if same_law else ():
        table = {"units": system.name, "excitation": _STAND_IN, "buildings": data["buildings"],
                 **contacts_of_inputs({**law, "floors_meet": choice}, floors, storeys, system)}
        try:
            contacts = case_from_dict(table).contacts
        except (CaseError, ValueError):
            continue
        if [(c.between, c.levels) for c in contacts] == found:
            return choice, None
    return AS_IN_FILE, [{"between": list(c.between), "levels": list(c.levels), "gap": c.gap, "model": c.model,
                         "stiffness": c.stiffness, "restitution": c.restitution} for c in case.contacts]
