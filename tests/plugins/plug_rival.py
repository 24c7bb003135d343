"""A second third-party plug-in that takes names already taken (tests/plugins/test_name_conflicts.py): each entry
point registers one thing under a name ``plug_extras`` or gearcli itself holds, with figures of its own, so that a
silent "last one wins" would show in the numbers, not only in the message.

- :func:`same_standard`: a standard named ``test_iso6336_marine`` (the extras' name) with S_Hmin = 2.0;
- :func:`same_kind`: a schema table of stage ``type = "test_fixed_ratio"`` (the extras' kind);
- :func:`iso6336`: a standard named ``"iso6336"``, gearcli's built-in name, with S_Hmin = 2.0;
- :func:`planetary`: a model facet of gearcli's built-in ``"planetary"`` stages;
- :func:`own_standard`: a standard of a name nobody else holds (``test_rival_only``), to trigger a load;
- :func:`iso_title`, :func:`same_title`: standards of names of their own titled as ISO 6336 (gearcli's built-in
  title) or as the extras' standard: a title names one standard (tables and life find a rating's standard by it).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal

import plug_extras as px

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema import register_stage_table
from gearcli.rating import register as register_standard
from gearcli.stages import kinds

ONLY = "test_rival_only"


class RivalMarine(px.Marine):
    """ISO 6336 at S_Hmin 2.0 (not the extras' 1.4) under the extras' name (parallel stages only)."""

    title = "ISO 6336:2006 method B, S_Hmin 2.0 (a rival test plug-in)"

    def rate_design(self, cfg, stages):
        r = cfg.rating
        strict = cfg.model_copy(update={"rating": r.model_copy(update={"min_safety_pitting": 2.0})})
        rated, diags = px.ISO6336.rate_design(strict, stages)
        return tuple(replace(s, rating=replace(s.rating, standard=self.title)) for s in rated), diags


class RivalIso(RivalMarine):
    name = "iso6336"


class RivalOnly(RivalMarine):
    name = ONLY


class RivalIsoTitle(RivalMarine):
    name = "test_rival_iso_title"
    title = "ISO 6336:2006 method B"  # gearcli's ISO 6336, written out: the plug-in's own copy of the text


class RivalSameTitle(RivalMarine):
    name = "test_rival_same_title"
    title = px.TITLE


class RivalFixedRatioStage(StrictTable):
    type: Literal["test_fixed_ratio"]
    ratio: float


class RivalPlanetaryModel(px.FixedRatioModelKind):
    pass


def same_standard() -> None:
    register_standard(RivalMarine())


def same_kind() -> None:
    register_stage_table(px.KIND, RivalFixedRatioStage)


def iso6336() -> None:
    register_standard(RivalIso())


def planetary() -> None:
    kinds.provide("planetary", "model", RivalPlanetaryModel())


def own_standard() -> None:
    register_standard(RivalOnly())


def iso_title() -> None:
    register_standard(RivalIsoTitle())


def same_title() -> None:
    register_standard(RivalSameTitle())
