"""docs/plugins.md is what a plug-in's author writes from: every member of the protocols a plug-in implements (a
stage kind's design and model facets, a rating standard) is named on the page, so a kind written from it alone
does not meet "its design facet's … is missing" (exit 1) at its first command."""

from __future__ import annotations

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
