"""`[rating] K_gamma`: DESIGN §11 rates a planetary stage's meshes "with the load-sharing factor `K_gamma` from
`[rating]` or 1". The key was `load_sharing_factor` only, and `K_gamma` (the contract's name) was an unknown key
(exit 2). Both names now give the same factor; one of the two, never both.

The check against the contract: with K_gamma = 1.1 each mesh's rating lists K_gamma = 1.1, and its pitting stress is
ISO 6336-2's sigma_H = sigma_H0 sqrt(K_A K_gamma K_v K_Hbeta K_Halpha) (DESIGN §11, docs/planetary.md) with that
factor; the design is the same, number for number, as with `load_sharing_factor = 1.1`."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "planetary_stage.toml"


def _file(tmp_path: Path, rating_line: str | None) -> Path:
    lines = [ln for ln in CONFIG.read_text(encoding="utf-8").splitlines() if not ln.startswith("load_sharing_factor")]
    text = "\n".join(lines) + "\n"
    if rating_line is not None:
        text = text.replace("[rating]\n", f"[rating]\n{rating_line}\n", 1)
    path = tmp_path / "planetary.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _design(path: Path) -> dict:
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_k_gamma_is_the_load_sharing_factor(tmp_path):
    by_symbol = _design(_file(tmp_path, "K_gamma = 1.1"))
    by_name = _design(_file(tmp_path, "load_sharing_factor = 1.1"))
    stage = by_symbol["stages"][0]
    assert stage["load_sharing_factor"] == 1.1
    for mesh in stage["meshes"]:
        r = mesh["rating"]
        assert r["K_gamma"] == 1.1
        assert_allclose(r["sigma_H_MPa"],
                        r["sigma_H0_MPa"] * math.sqrt(r["K_A"] * 1.1 * r["K_v"] * r["K_Hbeta"] * r["K_Halpha"]),
                        rtol=1e-12)
    assert by_symbol.pop("input_sha256") != by_name.pop("input_sha256")  # two files, one design
    assert by_symbol == by_name


def test_both_names_at_once_is_exit_2_naming_the_table(tmp_path):
    path = _file(tmp_path, "K_gamma = 1.1\nload_sharing_factor = 1.1")
    res = CliRunner().invoke(cli, ["design", str(path)])
    assert res.exit_code == 2
    assert str(path) in res.stderr and "rating" in res.stderr and "K_gamma" in res.stderr
    assert "Traceback" not in res.stderr


def test_k_gamma_without_a_planetary_stage_names_the_key(tmp_path):
    config = Path(__file__).resolve().parents[2] / "configs" / "wind_turbine_allowances.toml"
    res = CliRunner().invoke(cli, ["design", str(config), "--set", "rating.K_gamma=1.1"])
    assert res.exit_code == 2
    assert "rating.K_gamma" in res.stderr
