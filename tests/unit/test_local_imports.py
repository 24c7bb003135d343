"""Every import inside a function says why it is there (ARCHITECTURE.md, "Function-local imports").

A function-local import is kept only for a reason: start-up time (scipy, numba, matplotlib, rich or a heavier
layer imported when a command needs it, so ``gearcli design`` and ``--help`` stay fast), an optional extra, a
platform-only module, or the design layer keeping pydantic's config out of its import. The reason is a
``# lazy: <reason>`` comment on the import's line (any line of a parenthesised import) or a comment line
right above it.
A circle is never a reason: the import-linter contracts (pyproject.toml) fail on one, local or not.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REASON = re.compile(r"#\s*lazy:\s*\S")


def local_imports(path: Path) -> list[tuple[int, int]]:
    """(first line, last line) of every import statement inside a function of ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = set()
    for fn in ast.walk(tree):
        if isinstance(fn, ast.FunctionDef | ast.AsyncFunctionDef):
            for node in ast.walk(fn):
                if isinstance(node, ast.Import | ast.ImportFrom):
                    found.add((node.lineno, node.end_lineno or node.lineno))
    return sorted(found)


def unexplained(path: Path) -> list[str]:
    lines = path.read_text(encoding="utf-8").splitlines()
    out = []
    for first, last in local_imports(path):
        above = lines[first - 2].strip() if first > 1 else ""
        candidates = lines[first - 1:last] + ([above] if above.startswith("#") else [])  # a comment line above
        if not any(REASON.search(line) for line in candidates):
            out.append(f"{path.relative_to(ROOT)}:{first}: {lines[first - 1].strip()}")
    return out


def test_every_function_local_import_in_gearcli_gives_its_reason():
    missing = [entry for path in sorted((ROOT / "gearcli").rglob("*.py")) for entry in unexplained(path)]
    assert missing == [], "function-local imports without a '# lazy: <reason>' comment:\n" + "\n".join(missing)


def test_the_walker_finds_nested_and_multiline_imports_and_reads_the_comment(tmp_path):
    """The checker itself: a module with an explained, an unexplained, a nested and a parenthesised import."""
    sample = tmp_path / "sample.py"
    sample.write_text(
        "import math\n"  # module level: not a local import
        "def f():\n"
        "    import json  # lazy: start-up time\n"
        "    import csv\n"
        "    def g():\n"
        "        # lazy: an optional extra\n"
        "        import fcntl\n"
        "    from os import (\n"
        "        path,\n"
        "    )\n"
        "    return g\n",
        encoding="utf-8",
    )
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        assert local_imports(sample) == [(3, 3), (4, 4), (7, 7), (8, 10)]
        assert unexplained(sample) == ["sample.py:4: import csv", "sample.py:8: from os import ("]
    finally:
        ROOT = saved
