"""The stage-kind registry (gearcli/stages/kinds.py): one implementation per kind and facet, the built-in kinds'
facets registered by the layers that ask them, and a stage's kind read from its ``type``."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from gearcli.stages import kinds

ROOT = Path(__file__).resolve().parents[2]


def test_the_built_in_kinds_provide_every_facet():
    import gearcli.config.schema  # noqa: F401  # the tables
    import gearcli.io  # noqa: F401  # the output facets
    import gearcli.life  # noqa: F401  # the life facets
    import gearcli.stages.design  # noqa: F401
    import gearcli.stages.model  # noqa: F401

    for facet in ("table", "design", "model", "life", "io"):
        assert {"parallel", "planetary"} <= set(kinds.kinds(facet)), facet


def test_a_stage_without_type_is_parallel():
    class Table:
        pass

    class Planetary:
        type = "planetary"

    assert kinds.kind_of(Table()) == "parallel"
    assert kinds.kind_of(Planetary()) == "planetary"


def test_an_unregistered_facet_names_the_known_kinds():
    with pytest.raises(KeyError, match='stage type "bevel" has no design facet registered .the stage types with one: "parallel"'):
        kinds.facet("bevel", "design")


class _Facet:
    gear_pair = False

    def ratio(self, value: float) -> float:
        return 2.0 * value


def test_provide_and_withdraw():
    kinds.provide("test_kind", "design", _Facet())
    facet = kinds.facet("test_kind", "design")  # a plug-in's facet, behind the guard: its attributes as they are
    assert facet.gear_pair is False and facet.ratio(3.0) == 6.0
    kinds.withdraw("test_kind", "design")
    assert "test_kind" not in kinds.kinds("design")


def test_the_package_init_imports_nothing():
    """Each submodule keeps its own layer (pyproject's contract lists them one by one): the package's
    ``__init__`` must not import any of them."""
    tree = ast.parse((ROOT / "gearcli" / "stages" / "__init__.py").read_text(encoding="utf-8"))
    assert not [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
