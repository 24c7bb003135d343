"""The bad-input corpus, in one place, for the loader tests here and the CLI tests.

Each ``*.toml`` file here is a small broken design file derived from the seed reducer. Its first
line says what the error must name:

- ``# expect: FRAGMENT``: ``load_design`` raises ``ConfigError``; FRAGMENT is the key path
  (``stage[0].pinion.teath``), or ``line N`` for a TOML syntax error, or a message fragment for
  errors that have no key (``file is empty``).
- ``# expect-design: FRAGMENT``: the file loads, and ``gearcli.design.compute_design`` raises
  ``DesignError`` naming FRAGMENT (material not defined, same-hand helical pair).

Inputs that cannot be committed as text files (empty, binary, not UTF-8, too large, missing,
a directory) are made on the fly by :func:`materialize` under a temporary directory.

Usage::

    for name, fragment in CONFIG_CASES:
        path = materialize(name, tmp_path)   # a str path to pass to load_design or the CLI
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

HERE = Path(__file__).resolve().parent
_EXPECT = re.compile(r"^# (expect|expect-design): (.+?)\s*$")


def _first_comment(path: Path) -> tuple[str, str]:
    first = path.read_text(encoding="utf-8").splitlines()[0]
    m = _EXPECT.match(first)
    if not m:
        raise ValueError(f"{path.name}: first line must be '# expect: ...' or '# expect-design: ...'")
    return m.group(1), m.group(2)


def _committed() -> dict[str, tuple[str, str]]:
    return {p.name: _first_comment(p) for p in sorted(HERE.glob("*.toml"))}


def _too_large() -> bytes:
    return (HERE / "zero_module.toml").read_bytes() + b"#" * (10 * 1024 * 1024) + b"\n"


def _seed() -> bytes:
    return (HERE / "inf_speed.toml").read_bytes().replace(b"speed_deg_s = inf", b"speed_deg_s = 3600")


def _just_over_1_mib() -> bytes:
    seed = _seed() + b"#"
    return seed + b"#" * (1024 * 1024 + 1 - len(seed) - 1) + b"\n"


#: Generated cases: file name -> (bytes factory or None for "do not create", expected fragment).
GENERATED: dict[str, tuple] = {
    "empty.toml": (lambda: b"", "file is empty"),
    "whitespace_only.toml": (lambda: b"  \n\t\n", "file is empty"),
    "binary_garbage.toml": (lambda: bytes(range(256)) * 4, "binary data"),
    "not_utf8.toml": (lambda: 'title = "B\xe9ton mixer"\n'.encode("latin-1"), "not UTF-8"),
    "too_large.toml": (_too_large, "larger than 1 MiB"),
    "just_over_1_mib.toml": (_just_over_1_mib, "larger than 1 MiB"),
    "utf16_bom.toml": (lambda: _seed().decode().encode("utf-16"), "UTF-16 text"),
    "utf16_no_bom.toml": (lambda: _seed().decode().encode("utf-16-le"), "UTF-16 text"),
    "utf32_bom.toml": (lambda: _seed().decode().encode("utf-32"), "UTF-32 text"),
    "gzip.toml": (lambda: __import__("gzip").compress(_seed()), "gzip-compressed data"),
    "nul_in_middle.toml": (lambda: _seed()[:100] + b"\0" + _seed()[100:], "binary data"),
    "dotted_key_40000.toml": (lambda: b"a" + b".a" * 40000 + b" = 1\n", "nested too deeply"),
    "quoted_dotted_key_deep.toml": (lambda: b'"a"' + b' . "a"' * 5000 + b" = 1\n", "nested too deeply"),
    "inline_tables_deep.toml": (lambda: b"a = " + b"{b = " * 3000 + b"1" + b"}" * 3000 + b"\n", "nested too deeply"),
    "keys_100000.toml": (lambda: b"".join(b"k%d=1\n" % i for i in range(100000)), "keys and tables"),
    "missing_file.toml": (None, "no such file"),
    "a_directory.toml": ("dir", "is a directory"),
}

_FILES = _committed()

#: (file name, expected fragment) for every input that must raise ConfigError from load_design.
CONFIG_CASES: list[tuple[str, str]] = [
    (name, fragment) for name, (kind, fragment) in _FILES.items() if kind == "expect"
] + [(name, fragment) for name, (_, fragment) in GENERATED.items()]

#: (file name, expected fragment) for files that load but whose design compute_design rejects.
DESIGN_CASES: list[tuple[str, str]] = [
    (name, fragment) for name, (kind, fragment) in _FILES.items() if kind == "expect-design"
]


def materialize(name: str, tmp_path: Path) -> str:
    """A path to case ``name``: the committed file copied into ``tmp_path`` (so messages carry
    the plain file name), or the generated input written there. Returns it as given to gearcli."""
    target = tmp_path / name
    if name in _FILES:
        shutil.copyfile(HERE / name, target)
    else:
        make, _ = GENERATED[name]
        if make == "dir":
            target.mkdir()
        elif make is not None:
            target.write_bytes(make())
    return str(target)
