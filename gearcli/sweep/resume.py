"""A sweep's identity (what makes two runs the same sweep), and matching rows already written to points.

Rows read back name their varied keys' columns as the run that wrote them spelled the keys (``stage[0].x`` or
``stage.0.x``); :func:`relabel` renames them to this run's spelling, so a resume matches the points by the keys
themselves, and the finished file is in this run's spelling throughout.

Identity: the input's sha256 (the design file and the base ``--set`` overrides) and the sweep's
arguments (:meth:`SweepSpec.arguments`: varied keys and values, distributions, samples, sampling, seed,
direction). How the points are run (``--jobs``, ``--scheduler``) is not part of it. Without ``--seed`` a
random sweep draws one and records it; a re-run without ``--seed`` reuses the recorded one.
"""

from __future__ import annotations

import secrets
from collections import Counter
from collections.abc import Sequence
from typing import Any

from gearcli.errors import ConfigError
from gearcli.sweep.spec import SweepSpec, _ident_value, canonical_key


def identity(spec: SweepSpec, sha256: str, version: str) -> dict:
    return {"gearcli_version": version, "input_sha256": sha256, "sweep": spec.arguments()}


def seed_for(user_seed: int | None, stored: dict | None, has_random: bool) -> int | None:
    """The seed to use: the user's, else the one recorded in the output file, else a fresh one."""
    if not has_random:
        return user_seed
    if user_seed is not None:
        return user_seed
    recorded = ((stored or {}).get("sweep") or {}).get("seed")
    return int(recorded) if isinstance(recorded, int) else secrets.randbits(32)


def check_same(stored: dict, current: dict, path: str) -> None:
    """Raise (exit 2) when ``path`` holds a different sweep than this run's."""
    diffs = []
    if stored.get("input_sha256") != current["input_sha256"]:
        diffs.append("the design file or its --set overrides changed (input sha256)")
    a, b = stored.get("sweep") or {}, current["sweep"]
    diffs += [f"--{name} differs" for name in b if a.get(name) != b[name]]
    if diffs:
        raise ConfigError(f"holds a different sweep: {'; '.join(diffs)}. Use another -o FILE, or remove this one "
                          "to start over", source=path)


def relabel(rows: Sequence[dict], spec: SweepSpec) -> list[dict]:
    """Rows read back from a file with their varied keys' columns named as ``spec`` names them: a column written in
    the other spelling of a key (``stage.0.x`` for ``stage[0].x``) takes this run's name. Other columns stay."""
    wanted = dict(zip(spec.keys, spec.columns, strict=True))
    names: dict[str, str] = {}

    def name(column: str) -> str:
        if column not in names:
            try:
                key = canonical_key(column)
            except ConfigError:  # not a key path: a statistic's column, say
                key = column
            names[column] = wanted.get(key, column)
        return names[column]

    return [{name(c): v for c, v in r.items()} for r in rows]


def _parse_cell(v: Any) -> Any:
    if isinstance(v, str):
        try:
            return float(v)
        except ValueError:
            return v
    return v


def row_ident(row: dict, keys: Sequence[str]) -> tuple:
    """The ident (:attr:`Point.ident`) of a row read back from a file (CSV strings or JSON values)."""
    return (str(row.get("direction")), *(_ident_value(_parse_cell(row.get(k))) for k in keys))


def done_counts(rows: Sequence[dict], keys: Sequence[str]) -> Counter:
    """How many rows of each ident a file holds: a sweep may list a value twice (``--vary KEY=400,400,500``), and
    each of those points is done only when a row stands for it."""
    return Counter(row_ident(r, keys) for r in rows)


def ordered(rows: Sequence[dict], spec: SweepSpec) -> list[dict]:
    """Rows in the sweep's point order (a row this sweep does not know is dropped). A row computed in this run
    carries its point's index (``_index``); a row read back from the file takes the first point of its ident that
    no other row holds (repeated values: one row per point, none lost)."""
    free: dict[tuple, list[int]] = {}
    for branch in spec.branches():
        for p in branch:
            free.setdefault(p.ident, []).append(p.index)
    keyed: dict[int, dict] = {}
    for row in rows:
        i = row.get("_index")
        if i is not None:
            keyed[i] = row
    for indices in free.values():
        indices[:] = [i for i in indices if i not in keyed]
    for row in rows:
        if row.get("_index") is None:
            left = free.get(row_ident(row, spec.columns))
            if left:
                keyed[left.pop(0)] = row
    return [keyed[i] for i in sorted(keyed)]
