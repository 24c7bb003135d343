"""What a sweep runs: the ``--vary`` grid, the ``--random`` samples, and the points they make.

``--vary KEY=START:STOP:N`` is ``N`` evenly spaced values from START to STOP inclusive; ``--vary
KEY=v1,v2,...`` is the listed values (each read as a TOML value, as ``--set`` reads it). Several
``--vary`` make the grid of every combination; the first ``--vary`` changes slowest.

``--random KEY=normal(mu,sigma)`` or ``KEY=uniform(a,b)`` with ``--samples N``: N points whose
values are drawn by Latin hypercube sampling (``scipy.stats.qmc.LatinHypercube``, default) or plain
Monte Carlo (``numpy.random.Generator``), reproducible with the seed. The uniform [0, 1) draws are
mapped through each distribution's inverse CDF (``scipy.stats.norm.ppf``; ``a + (b - a) u``).

A grid may be combined with random keys: every grid point gets the same N samples.

``--direction up|down|both`` turns the grid into continuation branches along the FIRST ``--vary``
key: ascending (``up``), descending (``down``) or both, one branch per combination of the other keys;
each point of a branch starts from the final state of the previous one. Without ``--direction``
every point starts cold (``direction = none``) and points run independently.
"""

from __future__ import annotations

import itertools
import math
import re
import tomllib
from collections.abc import Sequence
from typing import cast

import numpy as np
import tomli_w

from gearcli.config.overrides import EXCLUSIVE, parse, parse_value
from gearcli.core.jsontypes import JsonObject, JsonScalar
from gearcli.core.records import record
from gearcli.core.text import sweep_text_cell
from gearcli.errors import ConfigError

# the input-speed keys of the design file (a speed axis: the Campbell diagram; a motor drive's refusal)
SPEED_KEYS = ("input.speed_rpm", "input.speed_deg_s", "input.speed_rad_s")


DIRECTIONS = ("up", "down", "both")
NO_DIRECTION = "none"
SAMPLINGS = ("lhs", "mc")
MAX_POINTS = 1_000_000
NORMAL_REACH = 9.0  # |z| of the farthest normal draw (8.3 at u = 1 - 2**-53), rounded up
_RANGE = re.compile(r"^\s*([^:]+):([^:]+):\s*(\d+)\s*$")
_DIST = re.compile(r"^\s*(normal|uniform)\s*\(\s*([^,()]+)\s*,\s*([^,()]+)\s*\)\s*$", re.IGNORECASE)


class SweepUsageError(ConfigError):
    """A malformed ``--vary``/``--random``/``--samples`` option (exit 2)."""


def canonical_key(key: str) -> str:
    """``stage[0].pinion.teeth`` -> ``stage.0.pinion.teeth``: what identifies a varied key (the overrides, the
    sweep's recorded arguments, resume), whichever of the two spellings the user wrote."""
    return ".".join(str(s) for s in parse(f"{key}=0").path)


def _check_exclusive(keys: Sequence[str]) -> None:
    """Two varied keys of one table that give one quantity (``input.speed_rpm`` and ``input.speed_deg_s``), or a
    key inside a varied table (``stage.0.pinion.teeth`` and ``stage.0.pinion``): each point's second override
    replaces (part of) the first (``--set``'s rule), so a column would name values the point never ran at."""
    groups = {group for table in EXCLUSIVE.values() for group in table}
    for i, a in enumerate(keys):
        for b in keys[i + 1:]:
            outer, inner = (a, b) if b.startswith(a + ".") else (b, a)
            if inner.startswith(outer + "."):
                raise SweepUsageError(f"{inner} lies inside {outer}, which is varied too: vary one of them",
                                      source="--vary/--random")
            (pa, _, la), (pb, _, lb) = a.rpartition("."), b.rpartition(".")
            group = next((g for g in groups if la in g and lb in g), None)
            if pa == pb and group is not None:
                raise SweepUsageError(f"{a} and {b} give one quantity ({pa} takes one of {', '.join(group)}): vary "
                                      "one of them", source="--vary/--random")


@record
class Axis:
    key: str  # canonical dotted key path
    values: tuple[JsonScalar, ...]
    label: str = ""  # the key path as the user wrote it (``stage[0].backlash_mm``): the column's name

    @property
    def column(self) -> str:
        return self.label or self.key


@record
class Distribution:
    key: str
    kind: str  # "normal" | "uniform"
    a: float  # mu or lower bound
    b: float  # sigma or upper bound
    label: str = ""  # the key path as the user wrote it: the column's name

    @property
    def column(self) -> str:
        return self.label or self.key

    def ppf(self, u):
        """Inverse CDF on uniform draws in [0, 1)."""
        if self.kind == "uniform":
            return _between(self.a, self.b, u)
        from scipy.stats import norm  # lazy: scipy.stats, start-up time

        return norm.ppf(u, loc=self.a, scale=self.b)


def _number(text: str, option: str, what: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise SweepUsageError(f"{what} must be a number, got {text.strip()!r}", source=option) from None
    if not math.isfinite(x):
        raise SweepUsageError(f"{what} must be finite, got {text.strip()!r}", source=option)
    return x


def _between(a, b, num, den=1.0):
    """The point ``num / den`` of the way from ``a`` to ``b``: ``a + (b - a) num / den`` as grids and uniform draws
    have always been computed (the same bits), or, where ``b - a`` overflows (-1e308:1e308), ``a (1 - f) + b f``
    with f = num / den, which stays finite (the overflowing form made nan and inf points: an empty key cell in
    CSV, an internal error writing JSON)."""
    if math.isfinite(b - a):
        return a + (b - a) * num / den
    f = num / den
    return a * (1.0 - f) + b * f


def _split(text: str, option: str, example: str) -> tuple[str, str, str]:
    """``KEY=VALUE`` -> (canonical key, the key as written, value)."""
    key, sep, value = text.partition("=")
    if not sep or not key.strip() or not value.strip():
        raise SweepUsageError(f"expected KEY={example}, got {text!r}", source=option)
    try:
        return canonical_key(key), key.strip(), value
    except ConfigError as exc:
        raise SweepUsageError(exc.message, source=option, key=key.strip()) from None


def parse_vary(text: str) -> Axis:
    """``input.speed_rpm=300:1500:13`` or ``stage.0.backlash_mm=0.1,0.2,0.3`` -> an :class:`Axis`."""
    option = "--vary"
    canonical, key, value = _split(text, option, "START:STOP:N or KEY=v1,v2,...")
    m = _RANGE.match(value)
    if m:
        start, stop = _number(m[1], option, f"{key}: START"), _number(m[2], option, f"{key}: STOP")
        n = int(m[3])
        if n < 1:
            raise SweepUsageError(f"{key}: N must be at least 1, got {n}", source=option)
        if n > MAX_POINTS:  # before the values are built: 1:2:1000000000 would take minutes and gigabytes
            raise SweepUsageError(f"{key}: {n} values is more than the {MAX_POINTS} points a sweep may have",
                                  source=option)
        values: tuple[float, ...] = (start,) if n == 1 else tuple(_between(start, stop, i, n - 1) for i in range(n))
        if all(re.fullmatch(r"\s*[+-]?\d+\s*", t) for t in (m[1], m[2])) and all(float(v).is_integer() for v in values):
            values = tuple(int(v) for v in values)  # 17:25:9 is teeth 17, 18, ..., 25 (integers)
        return Axis(canonical, values, key)
    if ":" in value and "," not in value and not value.strip().startswith(("[", "{", '"')):
        raise SweepUsageError(f"{key}: expected START:STOP:N with an integer N, got {value!r}", source=option)
    listed = _toml_items(value)
    if listed is not None:  # TOML values, arrays and quoted strings whose own commas are not separators
        items, values = [toml_value(v) for v in listed], tuple(listed)
    else:
        items = [v.strip() for v in value.split(",")]
        if any(not v for v in items):
            raise SweepUsageError(f"{key}: empty value in {value!r}", source=option)
        values = tuple(parse_value(v) for v in items)
    bad = next((t for t, v in zip(items, values, strict=True) if not _finite(v)), None)
    if bad is not None:  # nan/inf would make a point no output format can write (JSON has no NaN)
        raise SweepUsageError(f"{key}: values must be finite, got {bad!r}", source=option)
    return Axis(canonical, values, key)


def _toml_items(value: str) -> list | None:
    """``v1,v2,...`` read as the items of one TOML array, so that an array value keeps its commas
    (``[1.0, 0.5],[2.0, 0.1]`` is two values, not four); None when it is not all TOML (bare words such as
    ``speed,torque``: then each item is read on its own, as ``--set`` reads it) or has an empty item (TOML
    allows a trailing comma; a sweep's value list does not)."""
    text = value.strip()
    if not text or text.endswith(",") or text.startswith(","):
        return None
    try:
        parsed = tomllib.loads(f"v = [{text}]")
    except (ValueError, RecursionError):  # TOMLDecodeError is a ValueError
        return None
    items = parsed.get("v")
    return items if list(parsed) == ["v"] and isinstance(items, list) and items else None


def _finite(value: object) -> bool:
    """No nan or inf anywhere in a parsed value (a number, or an array or table of them)."""
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    if isinstance(value, dict):
        return all(_finite(v) for v in value.values())
    return True


def parse_random(text: str) -> Distribution:
    """``stage.0.backlash_mm=normal(0.25,0.02)`` or ``...=uniform(0.2,0.3)`` -> a :class:`Distribution`."""
    option = "--random"
    canonical, key, value = _split(text, option, "normal(mu,sigma) or KEY=uniform(a,b)")
    m = _DIST.match(value)
    if not m:
        raise SweepUsageError(f"{key}: expected normal(mu,sigma) or uniform(a,b), got {value!r}", source=option)
    kind = m[1].lower()
    a, b = _number(m[2], option, f"{key}: {kind} parameter"), _number(m[3], option, f"{key}: {kind} parameter")
    if kind == "normal" and b <= 0:
        raise SweepUsageError(f"{key}: normal(mu, sigma) needs sigma > 0, got {b:g}", source=option)
    if kind == "uniform" and not b > a:
        raise SweepUsageError(f"{key}: uniform(a, b) needs b > a, got ({a:g}, {b:g})", source=option)
    if kind == "normal" and not math.isfinite(abs(a) + NORMAL_REACH * b):
        # a draw reaches |z| ~ 8.3 (u = 1 - 2**-53): beyond the largest float it would be inf, a point no output
        # format can write
        raise SweepUsageError(f"{key}: normal(mu, sigma) draws up to mu ± {NORMAL_REACH:g} sigma, beyond the largest "
                              f"number, got ({a:g}, {b:g})", source=option)
    return Distribution(canonical, kind, a, b, key)


def unit_samples(n: int, dims: int, sampling: str, seed: int):
    """``n x dims`` uniform draws in [0, 1): Latin hypercube (scipy) or plain Monte Carlo (numpy)."""
    if sampling == "lhs":
        from scipy.stats import qmc  # lazy: scipy.stats, start-up time

        return qmc.LatinHypercube(d=dims, seed=np.random.default_rng(seed)).random(n)
    return np.random.default_rng(seed).random((n, dims))


@record
class Point:
    """One operating point: its position in the sweep's canonical order, and the values to set."""

    index: int
    values: tuple[tuple[str, JsonScalar], ...]  # (canonical key, value) in column order
    direction: str  # "up" | "down" | "none"
    columns: tuple[str, ...] = ()  # the varied keys' column names (as the user wrote them); () = the keys

    def cells(self) -> tuple[tuple[str, JsonScalar], ...]:
        """(column, value) of the varied keys: the row's first cells."""
        if not self.columns:
            return self.values
        return tuple((c, v) for c, (_, v) in zip(self.columns, self.values, strict=True))

    @property
    def ident(self) -> tuple[str, ...]:
        """What identifies a point in an output file (resume): direction and values."""
        return (self.direction, *(_ident_value(v) for _, v in self.values))

    def overrides(self) -> list[str]:
        return [f"{k}={toml_value(v)}" for k, v in self.values]

    def shown(self) -> str:
        """The point's values with the keys as the user wrote them (``stage[0].backlash_mm=0.1, ...``): messages."""
        return ", ".join(f"{c}={toml_value(v)}" for c, v in self.cells())


def _ident_value(v: JsonScalar) -> str:
    """A varied value as a point's ident holds it: a number by its float's repr, a text as a sweep's CSV file
    writes it (``=b`` as ``'=b``, ``#1`` as ``No.1``), so the cell read back from a CSV file, the value a JSON
    file holds and the value given to ``--vary`` all identify the same point; anything else by ``str``."""
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return repr(float(v))
    return sweep_text_cell(v) if isinstance(v, str) else str(v)


def toml_value(v: JsonScalar) -> str:
    """A value as ``--set`` reads it (TOML: ``true``, ``"text"``, ``1.5``)."""
    return tomli_w.dumps({"v": v})[4:].strip()


@record
class SweepSpec:
    axes: tuple[Axis, ...] = ()
    randoms: tuple[Distribution, ...] = ()
    samples: int | None = None
    sampling: str = "lhs"
    seed: int | None = None
    direction: str | None = None

    def __post_init__(self) -> None:
        keys = [a.key for a in self.axes] + [d.key for d in self.randoms]
        dup = next((k for k in keys if keys.count(k) > 1), None)
        if dup:
            written = list(dict.fromkeys(c for k, c in zip(keys, self.columns, strict=True) if k == dup))
            raise SweepUsageError(f"{' and '.join(written)} {'is' if len(written) == 1 else 'are one key,'} varied "
                                  "twice", source="--vary/--random")
        _check_exclusive(keys)
        if not keys:
            raise SweepUsageError("nothing to sweep: give --vary KEY=START:STOP:N or --samples N --random KEY=...")
        if self.randoms and not self.samples:
            raise SweepUsageError("--random needs --samples N", source="--random")
        if self.samples and not self.randoms:
            raise SweepUsageError("--samples needs at least one --random KEY=normal(mu,sigma)", source="--samples")
        if self.direction and not self.axes:
            raise SweepUsageError("--direction continues along the first --vary key; give one", source="--direction")
        if self.direction and self.direction not in DIRECTIONS:
            raise SweepUsageError(f"must be one of {', '.join(DIRECTIONS)}", source="--direction")
        if self.sampling not in SAMPLINGS:
            raise SweepUsageError(f"must be one of {', '.join(SAMPLINGS)}", source="--sampling")
        if self.randoms and self.seed is None:
            raise ValueError("random samples need a seed (the CLI draws one when --seed is absent)")
        if self.n_points > MAX_POINTS:
            raise SweepUsageError(f"{self._count_words()} = {self.n_points} points is more than the {MAX_POINTS} a "
                                  "sweep may have", source=self._count_options())

    def _count_words(self) -> str:
        """How the point count comes about: ``--vary input.speed_rpm (1000) x ... x --samples 5 x 2 directions``."""
        parts = [f"--vary {a.key} ({len(a.values)})" for a in self.axes]
        parts += [f"--samples {self.samples}"] if self.samples else []
        parts += ["2 directions (--direction both)"] if self.direction == "both" else []
        return " x ".join(parts)

    def _count_options(self) -> str:
        """The options that make the point count (the error's source)."""
        return "/".join(o for o, used in (("--vary", self.axes), ("--samples", self.samples),
                                          ("--direction", self.direction == "both")) if used)

    @property
    def keys(self) -> tuple[str, ...]:
        """The varied keys, canonical (``stage.0.backlash_mm``): what the points set and resume compares."""
        return tuple(a.key for a in self.axes) + tuple(d.key for d in self.randoms)

    @property
    def columns(self) -> tuple[str, ...]:
        """The varied keys' column names: each key path as the user wrote it (``stage[0].backlash_mm``)."""
        return tuple(a.column for a in self.axes) + tuple(d.column for d in self.randoms)

    @property
    def n_points(self) -> int:
        n = math.prod(len(a.values) for a in self.axes) * (self.samples or 1)
        return n * (2 if self.direction == "both" else 1)

    def branches(self) -> list[list[Point]]:
        """The points in canonical order, grouped into branches: without a direction one single-point
        branch per point (the grid product, first key slowest, then the samples); with one, a
        continuation branch per direction and combination of the other keys and samples, running
        along the first key (ascending for up, descending for down)."""
        samples = self.random_values()
        grids = [tuple(a.values) for a in self.axes]
        if not self.direction:
            combos = [g + s for g in itertools.product(*grids) for s in samples]
            return [[Point(i, tuple(zip(self.keys, c, strict=True)), NO_DIRECTION, self.columns)]
                    for i, c in enumerate(combos)]
        out: list[list[Point]] = []
        index = 0
        for direction in ("up", "down") if self.direction == "both" else (self.direction,):
            ascending = _ascending(grids[0])
            first = ascending[::-1] if direction == "down" else ascending
            for rest in itertools.product(*grids[1:]):
                for sample in samples:
                    branch = [Point(index + j, tuple(zip(self.keys, (v, *rest, *sample), strict=True)), direction,
                                    self.columns) for j, v in enumerate(first)]
                    index += len(branch)
                    out.append(branch)
        return out

    def random_values(self) -> list[tuple[float, ...]]:
        """The ``--random`` keys' values of each sample, in sample order (``[()]`` without random keys)."""
        if not self.randoms:
            return [()]
        assert self.samples is not None and self.seed is not None
        u = unit_samples(self.samples, len(self.randoms), self.sampling, self.seed)
        cols = [d.ppf(u[:, j]) for j, d in enumerate(self.randoms)]
        return [tuple(float(c[i]) for c in cols) for i in range(self.samples)]

    def arguments(self) -> JsonObject:
        """The sweep's definition as plain data, stored in the output file (resume compares it)."""
        return {"vary": [{"key": a.key, "values": [_plain(v) for v in a.values]} for a in self.axes],
                "random": [{"key": d.key, "distribution": d.kind, "parameters": [d.a, d.b]} for d in self.randoms],
                "samples": self.samples, "sampling": self.sampling if self.randoms else None,
                "seed": self.seed if self.randoms else None, "direction": self.direction}


def _ascending(values: tuple[JsonScalar, ...]) -> tuple[JsonScalar, ...]:
    """The values of a continuation key in ascending order (``1500:300:3`` runs up as 300, 900, 1500);
    values that do not compare (strings and numbers mixed) keep the order given."""
    try:
        return tuple(sorted(values, key=lambda v: cast(float, v)))
    except TypeError:
        return tuple(values)


def _plain(v: object) -> JsonScalar:
    return v if isinstance(v, (bool, int, float, str)) else str(v)


def spec_from_options(vary: Sequence[str], random: Sequence[str], samples: int | None, sampling: str,
                      seed: int | None, direction: str | None) -> SweepSpec:
    return SweepSpec(tuple(parse_vary(v) for v in vary), tuple(parse_random(r) for r in random), samples,
                     sampling, seed, direction)
