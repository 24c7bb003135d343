"""`gearcli design --format csv` of a train that mixes stage kinds: every row names its kind in `type` (a
parallel stage's cell was empty beside a planetary stage's "planetary"); a train of parallel stages alone keeps
its columns (no `type`), as the output contract shows them."""

from __future__ import annotations

import csv
import io
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def _rows(name: str) -> list[dict[str, str]]:
    res = CliRunner().invoke(cli, ["-q", "design", str(CONFIGS / name), "--format", "csv"])
    assert res.exit_code == 0, res.output
    return list(csv.DictReader(io.StringIO(res.stdout)))


def test_every_stage_of_a_mixed_train_names_its_kind():
    # configs/wind_turbine_gearbox.toml: two planetary stages, then one parallel helical stage (its file's [[stage]]
    # tables: type = "planetary" twice, the third without a type, the parallel default)
    assert [r["type"] for r in _rows("wind_turbine_gearbox.toml")] == ["planetary", "planetary", "parallel"]


def test_a_parallel_train_has_no_type_column():
    assert "type" not in _rows("concrete_mixer.toml")[0]
