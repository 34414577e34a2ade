"""Points: the case file with the varied keys set, loaded and validated
once, and each point's key (the hash naming its folder of results)."""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from pounding.errors import ArgumentError, CaseError
from pounding.studies.sweeps.spec import check_point_count

_FILE_FORMAT = 2  # bump when the chunk files' meaning changes: old ones are then ignored (2: every record's F_max kept)


def case_data(case) -> tuple[dict, str]:
    """The parsed case file of ``case`` (preset name, TOML path or dict) and its name."""
    import tomllib

    from pounding.presets import preset_text

    if isinstance(case, Mapping):
        data = copy.deepcopy(dict(case))
        return data, str(data.get("name", "case"))
    if isinstance(case, str) and preset_text(case) is not None:
        data = tomllib.loads(preset_text(case))
        return data, case
    if isinstance(case, (str, os.PathLike)):
        from pounding.case.case import read_case_file  # checks the file: size, encoding, TOML

        return _records_from(read_case_file(case), Path(case).parent), Path(case).stem
    raise ArgumentError(
        "case",
        f"give a preset name, a TOML file or the parsed case file as a dict (the paths of vary are keys of the file), "
        f"got {type(case).__name__}",
    )


def _records_from(data: dict, folder: Path) -> dict:
    """The case file with its recorded motions' paths made absolute: the workers read them from anywhere."""
    excitation = data.get("excitation")
    patterns = excitation.get("records") if isinstance(excitation, dict) else None
    if isinstance(patterns, str):
        patterns = [patterns]
    if isinstance(patterns, list) and all(isinstance(p, str) for p in patterns):
        excitation["records"] = [str(folder.resolve() / p) if not Path(p).is_absolute() else p for p in patterns]
    return data


def _set_path(data: dict, path: str, value: float) -> None:
    """Set key ``path`` of the case file ``data`` (lists counted from 1)."""
    parts = path.split(".")
    node = data
    for depth, part in enumerate(parts):
        where = ".".join(parts[:depth]) or "the case file"
        last = depth == len(parts) - 1
        if isinstance(node, list):
            if not part.isdigit() or not 1 <= int(part) <= len(node):
                raise ArgumentError("vary", f"{path!r}: {where} has {len(node)} entries, counted from 1; got {part!r}")
            index = int(part) - 1
            if last:
                node[index] = _like(node[index], value, path)
                return
            node = node[index]
        elif isinstance(node, dict):
            if last:
                node[part] = _like(node.get(part), value, path)
                return
            if part not in node:
                keys = ", ".join(sorted(node)) or "none"
                raise ArgumentError("vary", f"{path!r}: {where} has no {part!r}; keys there: {keys}")
            node = node[part]
        else:
            raise ArgumentError("vary", f"{path!r}: {where} is a value, not a table")


def _like(existing, value: float, path: str):
    """``value`` in the type of the key it replaces (a whole number stays an int)."""
    if existing is None:
        return value
    if isinstance(existing, bool) or not isinstance(existing, (int, float)):
        raise ArgumentError("vary", f"{path!r} is {existing!r} in the case, not a number; only numeric keys can be varied")
    if isinstance(existing, int) and float(value).is_integer():
        return int(value)
    return value


def _physics(data: dict) -> dict:
    """The part of a case file that determines the numbers (not its name)."""
    return {key: value for key, value in data.items() if key not in ("name", "description")}


@dataclass(frozen=True)
class Point:
    index: int
    values: tuple[float, ...]  # one per varied path, in the case's units
    data: dict  # the case file with the varied keys set
    key: str  # hash of the physics, the seed and the tolerance
    adjustment: dict = field(default_factory=dict)  # applied to the loaded case (pounding.case.scaling.adjusted), SI


def sweep_points(data: dict, name: str, vary: list[tuple[str, tuple[float, ...]]], seed: int, tolerance: float) -> list[Point]:
    """Every combination of the varied values, each loaded (and so validated) once here."""
    from pounding.case.case import case_from_dict

    check_point_count(vary)  # before any point is built
    paths = [path for path, _ in vary]
    points = []
    for index, values in enumerate(itertools.product(*(values for _, values in vary))):
        point = copy.deepcopy(data)
        for path, value in zip(paths, values):
            _set_path(point, path, value)
        label = ", ".join(f"{path}={value:g}" for path, value in zip(paths, values))
        point["name"] = f"{name}[{label}]" if label else name
        try:
            case_from_dict(point, name=point["name"])
        except CaseError as error:
            where = f" (at {label})" if label else ""
            raise CaseError(error.field, f"{error.message}{where}") from None
        points.append(Point(index, tuple(values), point, _point_key(point, seed, tolerance)))
    return points


def adjusted_points(data: dict, name: str, adjustments: Sequence[Mapping], seed: int, tolerance: float) -> list[Point]:
    """One point per adjustment of the case file ``data`` (:func:`pounding.case.scaling.adjusted`), each
    checked here: the case is loaded once, and an adjustment that makes it invalid names its key."""
    from pounding.case.case import case_from_dict
    from pounding.case.scaling import PeakGroundAcceleration, adjusted

    check_point_count([("adjustments", tuple(range(len(adjustments))))])
    case = case_from_dict(data, name=name)
    scaling = PeakGroundAcceleration(case) if any("pga" in a for a in adjustments) else None
    points = []
    for index, adjustment in enumerate(adjustments):
        adjustment = {key: float(value) for key, value in adjustment.items()}
        adjusted(case, adjustment, scaling)
        points.append(Point(index, (), data, _point_key(data, seed, tolerance, adjustment), adjustment))
    return points


def _point_key(data: dict, seed: int, tolerance: float, adjustment: Mapping | None = None) -> str:
    content = {"format": _FILE_FORMAT, "case": _physics(data), "seed": seed, "tolerance": tolerance}
    if adjustment:
        content["adjustment"] = dict(adjustment)
    text = json.dumps(content, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:20]
