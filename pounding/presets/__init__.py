"""The built-in cases: TOML files beside this module, one per preset.

Kept free of the physics modules so that listing the presets is instant.
"""

from __future__ import annotations

import tomllib
from importlib import resources

__all__ = ["preset_description", "preset_names", "preset_text", "preset_title"]


def _files() -> dict:
    folder = resources.files(__name__)
    return {entry.name.removesuffix(".toml"): entry for entry in folder.iterdir() if entry.name.endswith(".toml")}


def preset_names() -> list[str]:
    """Names of the built-in cases, sorted."""
    return sorted(_files())


def preset_text(name: str) -> str | None:
    """The TOML text of preset ``name``, or None when there is no such preset."""
    entry = _files().get(name)
    return None if entry is None else entry.read_text()


def preset_description(name: str) -> str:
    """The one-paragraph description of a built-in case."""
    return str(tomllib.loads(preset_text(name)).get("description", ""))


def preset_title(name: str) -> str:
    """The short human name of a built-in case, for lists: "Section 5 (one storey each), T2 = 0.4 s"."""
    return str(tomllib.loads(preset_text(name))["title"])
