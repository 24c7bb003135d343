"""The generated reference pages are fresh: ``docs/cli.md`` is every command's ``--help`` and ``docs/api.md`` the
facade's signatures and docstrings, as ``python docs/generate.py`` writes them today; the README is a door
(at most ~200 lines) whose links into docs/ all resolve."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _generator():
    spec = importlib.util.spec_from_file_location("docs_generate", ROOT / "docs" / "generate.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("page", ["cli.md", "api.md"])
def test_committed_page_is_the_generated_one(page):
    make = _generator().PAGES[page]
    assert (ROOT / "docs" / page).read_text() == make(), f"regenerate: python docs/generate.py (docs/{page})"


def test_cli_reference_has_every_command():
    from gearcli.cli import cli

    text = (ROOT / "docs" / "cli.md").read_text()
    for name in cli.commands:
        assert f"## gearcli {name}" in text


def test_readme_is_a_door_and_its_links_resolve():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 200
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", readme)
    assert links, "the README links into the manual"
    missing = [link for link in links if not link.startswith("http") and not (ROOT / link).exists()]
    assert missing == []


def test_docs_links_resolve():
    broken = []
    for page in sorted((ROOT / "docs").glob("*.md")):
        for link in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", page.read_text()):
            if not link.startswith("http") and not (page.parent / link).exists():
                broken.append(f"{page.name}: {link}")
    assert broken == []
