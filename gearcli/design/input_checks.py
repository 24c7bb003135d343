"""Design-input errors that stop the design: a member's material the file does not define, a helical pair's
hands. Each raises ``DesignError`` with a 0-based key path (``stage[0].gear.hand``); the CLI adds the file.
(Split from :mod:`gearcli.design.checks`, which keeps the warnings that do not stop it.)"""

from __future__ import annotations

import json
import re
from typing import TYPE_CHECKING

from gearcli.config.keys import suggest
from gearcli.errors import DesignError

if TYPE_CHECKING:
    from gearcli.config.schema import Material, Stage

HANDS = ("left", "right")
OPPOSITE = {"left": "right", "right": "left"}


def check_material(name: str, materials: dict[str, Material], key: str) -> None:
    """Refuse a member's material that ``[materials]`` does not define, suggesting the defined one it most likely
    means (``stel`` -> ``steel``) and the table to add (its name quoted where TOML needs it: ``[materials."a.b"]``)."""
    if name not in materials:
        known = ", ".join(sorted(materials)) or "none"
        hint = ("; the built-in steel applies only to a file without a [materials] table"
                if name == "steel" and materials else "")
        best = suggest(name, list(materials))
        meant = f" (did you mean {best!r}?)" if best else ""
        table = name if _BARE_KEY.fullmatch(name) else json.dumps(name, ensure_ascii=False)
        raise DesignError(f"unknown material {name!r}{meant}: define [materials.{table}] (defined: {known}){hint}",
                          key=key)


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")  # a TOML bare key; any other name is written quoted


def check_hands(stage: Stage, k: int, names: tuple[str, str] = ("pinion", "gear")) -> None:
    """A helical pair (β > 0) needs a hand on each gear, and opposite hands (external pair). ``names``: what the
    design file calls the pair's members (a planetary's sun–planet pair: "sun", "planet"), for the messages."""
    if stage.helix_angle_deg == 0.0:
        return
    name = dict(zip(("pinion", "gear"), names, strict=True))
    hands = {"pinion": stage.pinion.hand or "", "gear": stage.gear.hand or ""}
    for part, other in (("pinion", "gear"), ("gear", "pinion")):
        if hands[part] not in HANDS:
            need = f'"{OPPOSITE[hands[other]]}" (opposite to the {name[other]})' if hands[other] in HANDS \
                else '"left" or "right"'
            got = f'"{hands[part]}"' if hands[part] else "no hand"
            raise DesignError(f"helix angle β = {stage.helix_angle_deg:g}° needs hand = {need}, got {got}",
                              key=f"stage[{k}].{part}.hand")
    if hands["pinion"] == hands["gear"]:
        raise DesignError(f'an external helical pair needs opposite hands: the {name["pinion"]} is '
                          f'"{hands["pinion"]}", so the {name["gear"]} must be "{OPPOSITE[hands["pinion"]]}"',
                          key=f"stage[{k}].gear.hand")
