"""A sweep over a planetary stage: its ``stage1_load_sharing_factor`` column against the hand model of
tests/reference/test_planetary_dynamics.py (a position error e on planet 1 along its sun mesh: each planet's
sun and ring meshes in series, k_eq = k_sp k_rp / (k_sp + k_rp); planet equilibrium and the carrier's moment
balance give F_j = F_mean + k_eq (e_j - mean(e)), so K_gamma = 1 + k_eq e (1 - 1/N) / F_mean along the line of
action), at two load torques; a parallel stage has no such column."""

from __future__ import annotations

import csv
import io

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

Z_S, Z_P, Z_R, N, M_N, E_UM = 24, 30, 84, 3, 4.0, 5.0

SCENE = f"""
[[stage]]
type = "planetary"
normal_module_mm = {M_N}
sun = {{ teeth = {Z_S}, face_width_mm = 40 }}
planet = {{ teeth = {Z_P}, face_width_mm = 40, count = {N}, position_error_um = [{E_UM}, 0.0, 0.0] }}
ring = {{ teeth = {Z_R}, face_width_mm = 40 }}
carrier = {{ inertia_kg_m2 = 0.8 }}
fixed = "ring"
input = "sun"

[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.2

[input]
speed_rpm = 300
ramp_s = 0.05

[load]
torque_Nm = 400
ramp_s = 0.05

[simulation]
duration_s = 0.3
steps = 600
window_start_s = 0.2
rtol = 1e-9
"""


def test_the_load_sharing_factor_column_follows_the_hand_model(tmp_path):
    path, out = tmp_path / "planetary.toml", tmp_path / "sweep.csv"
    path.write_text(SCENE)
    torques = (400.0, 800.0)  # every planet stays in contact (the hand model is linear)
    res = CliRunner().invoke(cli, ["sweep", str(path), "--vary", f"load.torque_Nm={torques[0]},{torques[1]}",
                                   "--jobs", "1", "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader(io.StringIO(out.read_text().partition("\n")[2])))
    assert "stage1_load_sharing_factor" in rows[0]
    import tomllib

    for row, torque in zip(rows, torques, strict=True):
        assert float(row["load.torque_Nm"]) == torque
        doc = tomllib.loads(SCENE)
        doc["load"]["torque_Nm"] = torque  # ISO 6336-1's c' depends on the load below 100 N/mm: each point's own
        ds = compute_design(DesignFile.model_validate(doc)).stages[0]
        k_sp = ds.iso6336_mesh_stiffness_N_mm_um * ds.face_width_mm * 1e6
        k_rp = ds.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um * ds.planetary.planet_ring.face_width_mm * 1e6
        k_eq = k_sp * k_rp / (k_sp + k_rp)
        f_mean = torque / (1 + Z_R / Z_S) / (N * 0.5e-3 * ds.pinion.base_diameter_mm)  # along the line of action
        assert_allclose(float(row["stage1_load_sharing_factor"]), 1 + k_eq * E_UM * 1e-6 * (1 - 1 / N) / f_mean,
                        rtol=1e-3)


def test_parallel_stages_have_no_sharing_column():
    from gearcli.sweep.columns import columns

    cols = columns(["a"], 3, planetary=(2,))
    assert [c for c in cols if "load_sharing" in c] == ["stage2_load_sharing_factor"]
    assert cols.index("stage2_load_sharing_factor") == cols.index("stage2_runup_factor") + 1
    assert not any("load_sharing" in c for c in columns(["a"], 3))
