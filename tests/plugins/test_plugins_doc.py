"""docs/plugins.md is what a plug-in's author writes from: every member of the protocols a plug-in implements (a
stage kind's design and model facets, a rating standard) is named on the page, so a kind written from it alone
does not meet "its design facet's … is missing" (exit 1) at its first command."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest

from gearcli.rating.standard import RatingStandard
from gearcli.stages.design import DesignKind
from gearcli.stages.model import ModelKind

PAGE = (Path(__file__).resolve().parents[2] / "docs" / "plugins.md").read_text()


def _members(protocol: type) -> list[str]:
    return sorted(n for n in vars(protocol) if not n.startswith("_"))


@pytest.mark.parametrize("protocol", [DesignKind, ModelKind, RatingStandard], ids=lambda p: p.__name__)
def test_every_member_of_a_plugin_protocol_is_named_on_the_page(protocol):
    members = _members(protocol)
    assert len(members) >= 2  # the protocol's members were found
    assert [m for m in members if not re.search(rf"`{m}\b", PAGE)] == []


def test_every_field_of_mesh_spec_is_in_the_page_s_table():
    """``line`` gives a ``MeshSpec``: every field of its definition (``law``, ``full_damping_m``,
    ``iso_normal_stiffness_N_m`` were missing) has a row of the page's MeshSpec table, and the page says which
    fields have no default (the ones ``line`` must give)."""
    from gearcli.model.spec import MeshSpec

    table = PAGE[PAGE.index("**`MeshSpec`, field by field**"):]
    rows = [line for line in table.splitlines()[:40] if line.strip().startswith("| `")]
    named = {m for row in rows for m in re.findall(r"`(\w+)`", row.split("|")[1])}
    fields = dataclasses.fields(MeshSpec)
    assert sorted(f.name for f in fields) == sorted(named)
    required = [f.name for f in fields if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]
    words = ("zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten")
    assert re.search(rf"the {words[len(required)]} fields without a\s+default", table)
