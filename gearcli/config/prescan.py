"""Cheap checks on a design file's bytes and text, before ``tomllib`` sees it (docs/design-file.md, "Limits").

A design file is a few kB of UTF-8 TOML. Anything else is refused here in linear time, so a hostile
or mistaken input (a gzip archive, UTF-16 text, a 40,000-level dotted key, a million keys) costs
milliseconds, not the seconds and gigabytes that building and validating its data would.

- bytes: at most :data:`MAX_BYTES`; no NUL; not a known binary format (gzip, zip, PNG, PDF ...); UTF-8
  with or without a BOM (UTF-16/32 BOMs are named);
- text (strings and comments blanked first): at most :data:`MAX_KEYS` keys and table headers, dotted keys
  at most :data:`MAX_KEY_DEPTH` parts, arrays and inline tables nested at most :data:`MAX_NESTING` deep.
"""

from __future__ import annotations

import re

from gearcli.errors import ConfigError

MAX_BYTES = 1024 * 1024  # 1 MiB; the seed reducer is 2 kB, fifty stages ~30 kB
MAX_KEYS = 5000  # fifty stages with every optional key are ~1,600
MAX_KEY_DEPTH = 6  # the schema's deepest key is stage.mesh.exponent (3 parts); materials.x.y is 3
MAX_NESTING = 6  # arrays / inline tables inside one another (the schema needs 2)

_MAGIC = {b"\x1f\x8b": "gzip-compressed data", b"PK\x03\x04": "a zip archive", b"\x89PNG": "a PNG image",
          b"%PDF": "a PDF document", b"\x7fELF": "an executable", b"BZh": "bzip2-compressed data",
          b"\xfd7zXZ": "xz-compressed data", b"\x28\xb5\x2f\xfd": "zstd-compressed data"}
_BOMS = {b"\xff\xfe\x00\x00": "UTF-32", b"\x00\x00\xfe\xff": "UTF-32", b"\xff\xfe": "UTF-16",
         b"\xfe\xff": "UTF-16"}
_SAVE = "save it as UTF-8"


def check_bytes(raw: bytes, source: str) -> None:
    """Size, binary formats, NUL bytes and non-UTF-8 encodings that announce themselves."""
    if len(raw) > MAX_BYTES:
        raise ConfigError(f"larger than {MAX_BYTES // 2**20} MiB; a design file is a few kB (wrong file?)",
                          source=source)
    for bom, name in _BOMS.items():
        if raw.startswith(bom):
            raise ConfigError(f"{name} text, not UTF-8 ({_SAVE})", source=source)
    for magic, name in _MAGIC.items():
        if raw.startswith(magic):
            raise ConfigError(f"{name}, not a TOML design file", source=source)
    if b"\0" in raw:
        head = raw[:64]
        utf16 = len(head) > 3 and (head[1::2].count(0) > len(head) // 4 or head[0::2].count(0) > len(head) // 4)
        what = f"UTF-16 text, not UTF-8 ({_SAVE})" if utf16 else "binary data (NUL bytes), not a TOML design file"
        raise ConfigError(what, source=source)


_STRINGS_AND_COMMENTS = re.compile(
    r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*')
_DOT_SPACES = re.compile(r"[ \t]*\.[ \t]*")
_TOKEN = re.compile(r"[^\s=\[\]{},]+")
_BRACKET = re.compile(r"[\[\]{}]")


def _blank(m: re.Match) -> str:
    return "" if m.group().startswith("#") else "s"


def check_text(text: str, source: str) -> None:
    """Key count, dotted-key depth and nesting, on the text with strings and comments blanked."""
    bare = _STRINGS_AND_COMMENTS.sub(_blank, text)
    keys = bare.count("=") + len(re.findall(r"(?m)^[ \t]*\[", bare))
    if keys > MAX_KEYS:
        raise ConfigError(f"{keys} keys and tables, more than the {MAX_KEYS} a design file can have (wrong file?)",
                          source=source)
    joined = _DOT_SPACES.sub(".", bare)
    deepest = max((t.count(".") for t in _TOKEN.findall(joined)), default=0) + 1
    if deepest > MAX_KEY_DEPTH:
        raise ConfigError(f"a dotted key with {deepest} parts; the schema's keys have at most "
                          f"{MAX_KEY_DEPTH} (nested too deeply)", source=source)
    depth = most = 0
    for m in _BRACKET.finditer(bare):
        depth += 1 if m.group() in "[{" else -1
        most = max(most, depth)
        if most > MAX_NESTING:
            line = bare.count("\n", 0, m.start()) + 1
            raise ConfigError(f"arrays or inline tables nested more than {MAX_NESTING} deep at line {line} "
                              "(nested too deeply)", source=source)
