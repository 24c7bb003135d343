"""`gearcli report`'s mesh-order amplitudes are printed only where the run resolves them.

The seed reducer has no excitation: its F_t holds the run-up's ringing and almost nothing at the mesh orders, and
the report printed 1x-3x amplitudes such as 8.4e-05 N (a crane hoist) four digits deep, where the run's own error
estimate of its F_t spectrum (the check pass's largest amplitude difference) is ~0.5 N. An amplitude below that
estimate is now printed as `< e` (e rounded up, so that the amplitude stays below the printed number); one above it
as its number. The reference is the run's error estimate in the
same report's JSON."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")


def _report(fmt: str) -> str:
    res = CliRunner().invoke(cli, ["report", SEED, "--quick", "--format", fmt, "-q"])
    assert res.exit_code == 0, res.output
    return res.stdout


def test_unresolved_mesh_orders_print_their_bound_and_resolved_ones_their_number():
    doc = json.loads(_report("json"))
    errors = {k + 1: st["error_estimate"]["spectrum_N"] for k, st in enumerate(doc["simulation"]["summary"]["stages"])}
    md = _report("markdown")
    section = md.split("## Mesh-order amplitudes", 1)[1].split("\n## ", 1)[0]
    rows = [ln.split("|")[1:-1] for ln in section.splitlines() if ln.startswith("| ") and ln[2].isdigit()]
    cells = {(int(r[0]), r[1].strip()): r[3].strip() for r in rows}
    below = above = 0
    for st in doc["dynamics"]:
        for o in st["spectrum"]["mesh_orders"]:
            cell = cells[(st["stage"], f"{o['order']}x")]
            if o["tangential_N"] < errors[st["stage"]]:
                below += 1
                # the bound to two digits, rounded up: never printed below the estimate it states
                assert cell.startswith("< ") and errors[st["stage"]] <= float(cell[2:]) <= 1.1 * errors[st["stage"]], \
                    (st["stage"], o, cell)
            else:
                above += 1
                assert not cell.startswith("<") and abs(float(cell) / o["tangential_N"] - 1) < 1e-3, (o, cell)
    assert below and above  # the seed has both: its stage 1 orders are noise, its stage 3 orders are not
    assert "not resolved" in section
