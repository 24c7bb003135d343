"""A plug-in whose module registers on import (an entry point naming a module, docs/plugins.md) keeps its own name
when another plug-in imports it while that one loads (a plug-in building on another's classes): its registration is
its own entry point's, not the importer's, so the importer registering the same name is the conflict docs/plugins.md
promises (exit 1, one line naming both) instead of silently replacing it. Before, the imported module's registration
was recorded as the importer's, the importer's own registration of the name replaced it as "the same registrant",
and the design came out with the importer's figures."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from test_entry_points import RATED, _invoke

from gearcli.core import plugins
from gearcli.errors import EXIT_FAILED
from gearcli.rating import registry

NAME = "test_shared_std"
BASE = f'''from plug_chain import ToyLewis
from gearcli.rating import register


class Base(ToyLewis):
    name = "{NAME}"
    title = "base (a test plug-in)"


register(Base())
'''
IMPORTER = f'''import gw_base
from plug_chain import ToyLewis


class Rival(ToyLewis):
    name = "{NAME}"
    title = "rival (a test plug-in)"


def register():
    from gearcli.rating import register as register_standard

    register_standard(Rival())
'''


def _dist(site: Path, package: str, text: str, value: str) -> None:
    """What ``pip install`` leaves: the package and its metadata with the entry point ``value``."""
    site.mkdir()
    (site / f"{package}.py").write_text(text, encoding="utf-8")
    info = site / f"{package}-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {package}\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(f"[{plugins.GROUP}]\n{package} = {value}\n")


@pytest.fixture
def installed(tmp_path, monkeypatch):
    """The base plug-in (a module entry point) and the importer, whose distribution comes first on the path: the
    importer loads first and imports the base, which registers while the importer is the entry point loading."""
    _dist(tmp_path / "base", "gw_base", BASE, "gw_base")
    _dist(tmp_path / "importer", "gw_importer", IMPORTER, "gw_importer:register")
    monkeypatch.syspath_prepend(str(tmp_path / "base"))
    monkeypatch.syspath_prepend(str(tmp_path / "importer"))
    plugins.reset()
    yield
    registry.withdraw(NAME)
    plugins.reset()
    for module in ("gw_base", "gw_importer"):
        sys.modules.pop(module, None)


def test_a_plugin_imported_by_another_while_it_loads_keeps_its_name(installed):
    r = _invoke("design", RATED, "--set", f"rating.standard={NAME}", "--format", "json")
    assert r.exit_code == EXIT_FAILED, r.output
    assert r.stdout == "" and "Traceback" not in r.output
    (line,) = r.stderr.strip().splitlines()
    assert (f'rating standard "{NAME}" is registered twice, by plug-in \'gw_base\' (gw_base) and by plug-in '
            "'gw_importer' (gw_importer:register)") in line, line
    assert registry._STANDARDS[NAME].title == "base (a test plug-in)"  # the first registrant keeps the name
