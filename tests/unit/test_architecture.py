"""The layers ARCHITECTURE.md lists are the ones import-linter enforces, and the code keeps them."""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _documented_layers() -> list[str]:
    text = (ROOT / "ARCHITECTURE.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- layers:[^>]*-->\s*```text\n(.*?)```", text, re.S)
    assert block, "ARCHITECTURE.md lost its layer list"
    return [line.strip() for line in block.group(1).splitlines() if line.strip()]


def _contract_layers() -> list[str]:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["importlinter"]
    (contract,) = [c for c in config["contracts"] if c["type"] == "layers" and "containers" not in c]
    return list(contract["layers"])


def test_architecture_md_lists_the_contract_s_layers():
    assert _documented_layers() == _contract_layers()


INNER = ("gearcli.design", "gearcli.io", "gearcli.engine")  # packages with a layers contract of their own (no circle inside)


def _inner_contract(package: str) -> list[str]:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["importlinter"]
    (contract,) = [c for c in config["contracts"] if c.get("containers") == [package]]
    return list(contract["layers"])


def _documented_inner(package: str) -> list[str]:
    text = (ROOT / "ARCHITECTURE.md").read_text(encoding="utf-8")
    block = re.search(rf"<!-- layers {re.escape(package)}:[^>]*-->\s*```text\n(.*?)```", text, re.S)
    assert block, f"ARCHITECTURE.md lost the layer list of {package}"
    return [line.strip() for line in block.group(1).splitlines() if line.strip()]


@pytest.mark.parametrize("package", INNER)
def test_architecture_md_lists_each_inner_contract(package):
    assert _documented_inner(package) == _inner_contract(package)


@pytest.mark.parametrize("package", INNER)
def test_every_module_of_an_inner_contract_s_package_is_in_a_row(package):
    """A new module in design/, io/ or engine/ takes its place in the contract (an unlisted one could close a circle)."""
    named = {m.strip() for layer in _inner_contract(package) for m in re.split(r"[|:]", layer)}
    folder = ROOT / package.replace(".", "/")
    present = {p.stem for p in folder.glob("*.py") if p.stem != "__init__"}
    present |= {p.name for p in folder.iterdir() if (p / "__init__.py").exists()}
    assert present == named


def test_every_package_and_top_level_module_is_in_a_layer():
    named = {m.strip() for layer in _contract_layers() for m in re.split(r"[|:]", layer)}
    pkg = ROOT / "gearcli"
    present = {f"gearcli.{p.stem}" for p in pkg.glob("*.py") if p.stem != "__init__"}
    present |= {f"gearcli.{p.name}" for p in pkg.iterdir() if (p / "__init__.py").exists()}
    # a package whose submodules sit at different layers (gearcli.stages: its __init__ imports nothing) is in
    # the list by every one of its modules
    split = {m.rsplit(".", 1)[0] for m in named if m.count(".") > 1}
    assert present == {m for m in named if m.count(".") == 1} | split
    for package in split:
        modules = {f"{package}.{p.stem}" for p in (ROOT / package.replace(".", "/")).glob("*.py")}
        assert modules - {f"{package}.__init__"} == {m for m in named if m.startswith(package + ".")}


def test_the_code_keeps_the_layers():
    pytest.importorskip("importlinter")  # the dev extra
    script = Path(sys.executable).with_name("lint-imports")
    res = subprocess.run([str(script), "--no-cache"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stdout[-3000:]


@pytest.mark.parametrize(("module", "back"), [("io/table_kit.py", "gearcli.io.tables"),
                                             ("design/checks.py", "gearcli.design.planetary")])
def test_a_circle_inside_a_package_fails_the_contract(tmp_path, module, back):
    """The circles issue 34 removed (io: tables / table kit; design: checks / planetary) put back, even as a
    function-local import: ``lint-imports`` fails, naming the import."""
    pytest.importorskip("importlinter")
    import os
    import shutil

    shutil.copytree(ROOT / "gearcli", tmp_path / "gearcli", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    with open(tmp_path / "gearcli" / module, "a", encoding="utf-8") as f:
        f.write(f"\n\ndef _circle():\n    import {back}  # lazy: the circle under test\n")
    script = Path(sys.executable).with_name("lint-imports")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    res = subprocess.run([str(script), "--no-cache"], cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert res.returncode != 0, res.stdout[-3000:]
    assert f"gearcli.{module[:-3].replace('/', '.')} -> {back}" in res.stdout


def test_commands_reach_the_layers_only_through_the_facade():
    """The cli package imports gearcli's api (the facade), io (the formatters), errors and core.text (its own
    messages) and its own modules, nothing below: loading, designing, simulating, budgets and models are the
    facade's."""
    import ast

    allowed = ("gearcli.api", "gearcli.io", "gearcli.errors", "gearcli.core.text", "gearcli.cli")
    sources = sorted((ROOT / "gearcli" / "cli").glob("*.py"))
    assert len(sources) >= 2  # the package, not an empty glob
    nodes = [node for path in sources for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))]
    used = set()
    for node in nodes:
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("gearcli"):
            used |= {f"{node.module}.{a.name}" if node.module == "gearcli" else node.module for a in node.names}
        elif isinstance(node, ast.Import):
            used |= {a.name for a in node.names if a.name.startswith("gearcli")}
    below = sorted(m for m in used if m != "gearcli.__version__" and not m.startswith(allowed))
    assert below == []
