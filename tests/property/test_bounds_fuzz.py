"""Fuzzing the bounds: generated design files with values at the edges of every numeric key of the schema.

Every number key the JSON Schema lists (it is generated from the validation models), and every array of
numbers, gets values below, at and above each of its bounds, inside its "not tiny" gap, subnormals, 1e15,
nan/inf, huge integers and values of the wrong type; hypothesis combines up to three such edits of the seed
reducer into one TOML document, through ``gearcli design`` and ``gearcli modes``, and one edit at a time
through ``gearcli simulate`` on a short, coarse run; an exhaustive pass sends every key alone at every edge
through ``design``. The outcome must be exit 0 or exit 2 with a clean message naming the file, never an
internal error (exit 1), and no output may contain NaN or infinity. Bugs it found are pinned, one
regression test each, in tests/cli/test_cli_fuzz_findings.py.
"""

from __future__ import annotations

import copy
import csv
import datetime as dt
import io
import json
import math
import re
import tomllib
from functools import cache
from pathlib import Path

import tomli_w
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearcli.cli import cli
from gearcli.config import json_schema

ROOT = Path(__file__).resolve().parents[2]
SEED = tomllib.loads((ROOT / "configs" / "concrete_mixer.toml").read_text(encoding="utf-8"))

#: Keys of which at most one may be given; setting one removes the others so the edge value is what is tested.
EXCLUSIVE = [("input", ("speed_deg_s", "speed_rpm", "speed_rad_s")),
             ("input", ("torque_Nm", "torque_Nmm", "power_kW")),
             ("load", ("torque_Nmm", "torque_Nm", "power_kW")),
             ("target", ("output_speed_rpm", "output_speed_deg_s"))]
#: Where each table of the schema sits in a design file (stage tables at the first and the last stage).
PLACES = {"Material": [("materials", "steel")], "Contact": [("contact",)], "Input": [("input",)],
          "Load": [("load",)], "Target": [("target",)], "Simulation": [("simulation",)],
          "Stage": [("stage", 0), ("stage", 2)], "PairGear": [("stage", 0, "pinion"), ("stage", 2, "gear")],
          "ContactOverride": [("stage", 1, "mesh")], "ShaftSpring": [("stage", 1, "shaft")],
          "BasicRack": [("stage", 0, "basic_rack")], "Ripple": [("input", "torque_ripple", 0)],
          "Fluctuation": [("load", "fluctuation", 0)]}
#: A complete entry for the array-of-tables keys, so that an edge value in one of its keys is what is tested;
#: a torque ripple needs a torque drive (the seed's input torque is ~240 N m: 5310 N m / 22.27).
ENTRIES = {"torque_ripple": {"amplitude_percent": 5.0, "order": 1.0},
           "fluctuation": {"amplitude_percent": 5.0, "frequency_Hz": 10.0}}
NUMBER_RE = re.compile(r"(?i)(?<![\w.])[-+]?(nan|inf|infinity)(?![\w])")


def _number_schema(prop: dict) -> dict | None:
    for alt in prop.get("anyOf", [prop]):
        if alt.get("type") in ("number", "integer"):
            return alt
        if alt.get("type") == "array" and alt.get("items", {}).get("type") in ("number", "integer"):
            return alt
    return None


@cache
def numeric_keys() -> list[tuple[tuple, str, dict]]:
    """(path in the document, "number"/"integer", the bounds) for every numeric key of the schema."""
    defs = json_schema()["$defs"]
    out = []
    for name, places in PLACES.items():
        for key, prop in defs[name]["properties"].items():
            num = _number_schema(prop)
            if num is None:
                continue
            for place in places:
                out.append(((*place, key), num["type"], num))
    return out


def edge_values(kind: str, bounds: dict) -> list:
    """Values below, at and above each bound, in a "not tiny" gap, and the classics of a careless file.
    An array of numbers gets each edge value of its items alone, none, and one entry too many."""
    if kind == "array":
        item = bounds["items"]
        too_many = (bounds.get("maxItems") or 1000) + 1
        return [[v] for v in edge_values(item["type"], item)] + [[], [1.0] * too_many, 1.0]
    lo = bounds.get("minimum", bounds.get("exclusiveMinimum"))
    hi = bounds.get("maximum", bounds.get("exclusiveMaximum"))
    vals: list = [0, -1, 10**20, 2**63 - 1, -(2**63), "12", True, [1.0], {"x": 1.0}, dt.date(1979, 5, 27)]
    if kind == "integer":
        vals += [v for b in (lo, hi) if b is not None for v in (int(b) - 1, int(b), int(b) + 1)]
        vals += [float(lo or 1), 1.5]
        return vals
    vals += [0.0, -0.0, 5e-324, 1e-320, 2.2250738585072014e-308, 1e-300, 1e15, -1e15, 1e300, -1e300,
             math.nan, math.inf, -math.inf]
    for b in (lo, hi):
        if b is None:
            continue
        b = float(b)
        vals += [b, -b, math.nextafter(b, -math.inf), math.nextafter(b, math.inf), b * (1 - 1e-9) - 1e-300,
                 b * (1 + 1e-9) + 1e-300]
    for gap in bounds.get("not", {}).get("anyOf", []):
        a, z = gap["exclusiveMinimum"], gap["exclusiveMaximum"]
        vals += [(a + z) / 2, math.nextafter(z, 0.0) if z else math.nextafter(a, 0.0), a, z]
    return vals


def _set(doc: dict, path: tuple, value) -> None:
    node = doc
    for part in path[:-1]:
        if isinstance(node, list):
            node = node[part]
        elif part in ENTRIES:
            node = node.setdefault(part, [dict(ENTRIES[part])])
        else:
            node = node.setdefault(part, {})
    if "torque_ripple" in path:
        doc["input"].update(drive="torque", torque_Nm=240.0)
    key = path[-1]
    for table, group in EXCLUSIVE:
        if path[0] == table and key in group:
            for other in group:
                node.pop(other, None)
    if path[:2] == ("stage", 1) and path[2] == "shaft" and key != "stiffness_Nm_rad":
        node.setdefault("stiffness_Nm_rad", 1e6)
    node[key] = value


def document(edits) -> bytes:
    doc = copy.deepcopy(SEED)
    for path, value in edits:
        _set(doc, path, value)
    return tomli_w.dumps(doc).encode("utf-8")


def _finite_json(text: str) -> None:
    def bad(s):
        raise AssertionError(f"non-finite constant {s} in the JSON output")

    def num(s):
        v = float(s)
        assert math.isfinite(v), f"non-finite number {s} in the JSON output"
        return v

    json.loads(text, parse_constant=bad, parse_float=num)


def _finite_csv(text: str) -> None:
    for row in csv.reader(io.StringIO(text)):
        for cell in row:
            assert not NUMBER_RE.fullmatch(cell.strip()), f"non-finite cell {cell!r} in the CSV output"


def check_run(args: list[str], raw: bytes, fmt: str) -> int:
    """Run one command on ``raw`` (stdin); the invariants of the module text. Returns the exit code."""
    res = CliRunner().invoke(cli, [*args, "-", "--format", fmt], input=raw)
    detail = (args, res.exit_code, res.stderr[-2000:], raw.decode()[-600:])
    assert res.exit_code in (0, 2), detail
    assert "internal error" not in res.stderr and "Traceback" not in res.stderr, detail
    assert res.exception is None or isinstance(res.exception, SystemExit), (detail, repr(res.exception))
    if res.exit_code == 0:
        assert not NUMBER_RE.search(res.stderr), detail  # no warning computed from a NaN
        if fmt == "json":
            _finite_json(res.stdout)
        else:
            _finite_csv(res.stdout)
    else:
        errors = [line for line in res.stderr.splitlines() if line.startswith("gearcli: ")]
        assert errors and errors[0].startswith(("gearcli: <stdin>: ", "gearcli: --set: ")), detail  # file named
    return res.exit_code


@st.composite
def edits(draw, max_edits: int = 3):
    keys = numeric_keys()
    out = []
    for _ in range(draw(st.integers(1, max_edits))):
        path, kind, bounds = draw(st.sampled_from(keys))
        out.append((path, draw(st.sampled_from(edge_values(kind, bounds)))))
    return out


@settings(max_examples=1000, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(changes=edits(), command=st.sampled_from(["design", "modes"]), fmt=st.sampled_from(["json", "csv"]))
def test_design_and_modes_exit_0_or_2_and_never_print_nan(changes, command, fmt):
    check_run([command], document(changes), fmt)


SHORT_RUN = [(("simulation", "duration_s"), 0.02), (("simulation", "steps"), 20),
             (("input", "ramp_s"), 0.01), (("load", "ramp_s"), 0.01)]
#: Simulation keys worth the cost of a run: the ones that shape the dynamics (not the geometry, which
#: design covers), at their edges.
SIM_PREFIXES = (("input",), ("load",), ("contact",), ("simulation",), ("stage", 1, "mesh"), ("stage", 1, "shaft"),
                ("materials", "steel"))


@settings(max_examples=150, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_simulate_short_runs_exit_0_or_2_and_never_print_nan(data):
    keys = [k for k in numeric_keys() if any(k[0][:len(p)] == p for p in SIM_PREFIXES)]
    path, kind, bounds = data.draw(st.sampled_from(keys))
    value = data.draw(st.sampled_from(edge_values(kind, bounds)))
    changes = [*(e for e in SHORT_RUN if e[0] != path), (path, value)]
    check_run(["simulate"], document(changes), data.draw(st.sampled_from(["json", "csv"])))


def test_every_numeric_key_at_every_edge_through_design():
    """The exhaustive pass behind the random one: each key alone at each of its edge values (~2,800 runs)."""
    for path, kind, bounds in numeric_keys():
        for value in edge_values(kind, bounds):
            check_run(["design"], document([(path, value)]), "json")
