"""A plug-in built the way docs/plugins.md tells a third party to: ``plug_chain.py`` (a roller-chain stage kind with a
loss, and a toy Lewis rating standard) installed as a package of its own in a tmp dir (its module and a
``*.dist-info`` whose ``entry_points.txt`` names its ``register`` in the group ``gearcli.plugins``: what ``pip
install`` leaves), then ``gearcli design|simulate|modes|life|report`` on a file mixing the chain with parallel stages.
Every figure is checked against a hand calculation written out here; then copies of the plug-in broken the ways a
plug-in breaks, each a one-line message with its exit code and no traceback."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
import tomli_w
from click.testing import CliRunner
from jsonschema_subset import valid
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.config.schema import DesignFile
from gearcli.core import plugins
from gearcli.rating.registry import withdraw as withdraw_standard
from gearcli.stages import kinds

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SOURCE = (HERE / "plug_chain.py").read_text(encoding="utf-8")
KIND, STD = "test_chain", "test_toy_lewis"
RATED = ROOT / "configs" / "industrial_two_stage_rated.toml"

Z1, Z2, PITCH, ETA_C, K_C, J1, J2 = 17, 34, 19.05, 0.96, 2.0e7, 0.01, 0.05  # -, -, mm, -, N/m, kg m², kg m²
CHAIN = {"type": KIND, "driver_teeth": Z1, "driven_teeth": Z2, "pitch_mm": PITCH, "chain_efficiency": ETA_C,
         "stiffness_N_m": K_C, "damping_Ns_m": 200.0, "driver_inertia_kg_m2": J1, "driven_inertia_kg_m2": J2}
N_IN, T_OUT = 1450.0, 1340.0  # rpm, N m


def _doc() -> dict:
    """The rated two-stage reducer of configs/ with the chain between its stages (no target: the ratio changes)."""
    import tomllib

    doc = tomllib.loads(RATED.read_text(encoding="utf-8"))
    doc.pop("target")
    doc["stage"] = [doc["stage"][0], CHAIN, doc["stage"][1]]
    return doc


def _install(site: Path, package: str, text: str) -> None:
    """What ``pip install`` of the plug-in leaves: its package and its metadata with the entry point."""
    (site / package).mkdir(parents=True)
    (site / package / "__init__.py").write_text(text, encoding="utf-8")
    info = site / f"{package}-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {package}\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(f"[{plugins.GROUP}]\n{package} = {package}:register\n")


def _forget(packages: list[str]) -> None:
    for facet in ("table", "design", "model", "io", "life"):
        for kind in (KIND, "test_chain_b"):
            kinds.withdraw(kind, facet)
    withdraw_standard(STD)
    DesignFile.model_rebuild(force=True)
    plugins.reset()
    for p in packages:
        sys.modules.pop(p, None)


@pytest.fixture
def install(tmp_path, monkeypatch):
    """install(text=SOURCE, package=...) puts a copy of the plug-in on the path as an installed package."""
    site = tmp_path / "site"
    site.mkdir()
    monkeypatch.syspath_prepend(str(site))
    installed: list[str] = []

    def put(text: str = SOURCE, package: str = "gearcli_test_chain") -> None:
        _install(site, package, text)
        installed.append(package)

    plugins.reset()
    yield put
    _forget(installed)


@pytest.fixture
def mixed(tmp_path) -> str:
    path = tmp_path / "mixed.toml"
    path.write_text(tomli_w.dumps(_doc()), encoding="utf-8")
    return str(path)


def _invoke(*args: str):
    return CliRunner().invoke(cli, list(args))


def _json(*args: str) -> dict:
    r = _invoke(*args, "--format", "json", "-q")
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def _r(z: int) -> float:
    """The sprocket's mean (chain-speed) radius, m: z p / (2 pi)."""
    return z * PITCH * 1e-3 / (2.0 * math.pi)


# ---------------------------------------------------------------------------------------------- the numbers
def test_design_carries_speeds_and_torques_through_the_chain_with_its_loss(install, mixed):
    install()
    d = _json("design", mixed)
    s1, ch, s3 = d["stages"]
    i1, i3 = 75 / 19, 68 / 19  # the reducer's stages (configs/industrial_two_stage_rated.toml), eta 0.98 each
    i_c = Z2 / Z1
    # speeds: 1450 rpm / i1 / i_c / i3
    assert_allclose(ch["input_speed_rpm"], N_IN / i1, rtol=1e-12)
    assert_allclose(ch["output_speed_rpm"], N_IN / i1 / i_c, rtol=1e-12)
    assert_allclose(d["output_speed_rpm"], N_IN / (i1 * i_c * i3), rtol=1e-12)
    # torques from the load back: T_in = T_out / (i eta) per stage
    t3_in = T_OUT / (i3 * 0.98)
    assert_allclose(ch["output_torque_Nm"], t3_in, rtol=1e-12)
    assert_allclose(ch["input_torque_Nm"], t3_in / (i_c * ETA_C), rtol=1e-12)
    assert_allclose(s1["gear"]["torque_Nm"], t3_in / (i_c * ETA_C), rtol=1e-12)
    assert_allclose(d["input_torque_Nm"], t3_in / (i_c * ETA_C) / (i1 * 0.98), rtol=1e-12)
    # the chain: speed v = omega_1 r_1, the driver's pull F = T_in / r_1 (r = z p / 2 pi: 51.54 mm, 103.08 mm)
    w1 = N_IN / i1 * math.pi / 30.0
    assert_allclose(ch["chain_speed_m_s"], w1 * _r(Z1), rtol=1e-12)
    assert_allclose(ch["chain_force_N"], t3_in / (i_c * ETA_C) / _r(Z1), rtol=1e-12)
    assert ch["ratio"] == 2.0 and ch["efficiency"] == ETA_C and list(ch)[:2] == ["index", "type"]
    assert ch["type"] == KIND and ch["rated"] is False and "rating" not in ch
    # the sprockets' inertias on the shafts they sit on
    shafts = d["shafts"]
    assert_allclose(shafts[1]["inertia_kg_m2"], s1["gear"]["inertia_kg_m2"] + J1, rtol=1e-12)
    assert_allclose(shafts[2]["inertia_kg_m2"], s3["pinion"]["inertia_kg_m2"] + J2, rtol=1e-12)


def test_the_parallel_stages_json_keys_are_todays(install, mixed):
    """A plug-in kind beside them changes no key of the parallel stages' objects (the contract: plug-in seams)."""
    install()
    plain = _json("design", str(RATED))["stages"]
    mixed_stages = _json("design", mixed)["stages"]
    assert list(mixed_stages[0]) == list(plain[0]) and list(mixed_stages[2]) == list(plain[1])
    assert list(mixed_stages[0]["rating"]) == list(plain[0]["rating"])
    sim_plain = _json("simulate", str(RATED))["summary"]["stages"]
    sim_mixed = _json("simulate", mixed)["summary"]["stages"]
    assert list(sim_mixed[0]) == list(sim_plain[0]) and list(sim_mixed[2]) == list(sim_plain[1])


def test_simulate_loses_the_chain_s_loss_as_the_design_does(install, mixed):
    """The chain's loss acts in the dynamics (its connector is the built-in mesh element with eta = 0.96): the
    settled force of the parallel stage before it is the design's F_t (which has 1/eta_c in it), the input torque
    the design's, the chain's force the driver's pull T_in / r_1."""
    install()
    design = _json("design", mixed)
    s = _json("simulate", mixed)["summary"]
    s1, ch, s3 = s["stages"]
    # within the loss law's tanh(f v / W) transition: sigma = 1 - O(1e-6) at the settled speed
    assert_allclose(s1["simulated_static_tangential_N"], design["stages"][0]["static_force_N"]["tangential"],
                    rtol=1e-5)
    assert_allclose(s3["simulated_static_tangential_N"], design["stages"][2]["static_force_N"]["tangential"],
                    rtol=1e-5)
    assert_allclose(s["input_torque_Nm"], design["input_torque_Nm"], rtol=1e-5)
    assert ch["type"] == KIND and set(ch) >= {"chain_force_N", "static_chain_force_N", "stretch_um"}
    assert_allclose(ch["chain_force_N"]["mean"], design["stages"][1]["input_torque_Nm"] / _r(Z1), rtol=1e-5)
    # the span's stretch F / k
    assert_allclose(ch["stretch_um"]["mean"], ch["chain_force_N"]["mean"] / K_C * 1e6, rtol=1e-5)


def test_the_chain_s_time_series_columns(install, mixed, tmp_path):
    """The series keep the gear stages' column names (docs/plugins.md, "io"): the chain's force in
    stage2_tangential_N, its stretch in stage2_dte_um, no radial or axial force (a line without angles)."""
    import csv

    install()
    r = _invoke("simulate", mixed, "-q", "-o", str(tmp_path / "run.csv"))
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader((tmp_path / "run.csv").open(encoding="utf-8")))
    last = rows[-1]
    force = T_OUT / (68 / 19 * 0.98) / (Z2 / Z1 * ETA_C) / _r(Z1)  # the chain's T_in over r_1
    assert_allclose(float(last["stage2_tangential_N"]), force, rtol=1e-4)  # settled: the ramp ended at 0.2 s
    assert_allclose(float(last["stage2_dte_um"]), force / K_C * 1e6, rtol=1e-4)
    assert float(last["stage2_radial_N"]) == 0.0 and float(last["stage2_axial_N"]) == 0.0


def test_a_sweep_s_rows_name_the_chain_as_a_gear_stage(install, mixed):
    """A sweep's rows keep the gear stages' column names for the chain too (docs/plugins.md, "io"), its points
    designed in workers that load the plug-in themselves: stage2_tangential_N_mean the chain's pull T_in / r_1 at
    each driven sprocket (T_in = T_out / (i3 eta) / (i_c eta_c), i_c = z2 / z1), its stretch F / k."""
    install()
    r = _invoke("sweep", mixed, "--vary", f"stage.1.driven_teeth={Z2},51", "--jobs", "2", "-q", "--format", "json")
    assert r.exit_code == 0, r.output
    rows = json.loads(r.stdout)["rows"]
    assert [row["status"] for row in rows] == ["ok", "ok"]
    for row, z2 in zip(rows, (Z2, 51), strict=True):
        force = T_OUT / (68 / 19 * 0.98) / (z2 / Z1 * ETA_C) / _r(Z1)
        assert_allclose(row["stage2_tangential_N_mean"], force, rtol=1e-4)
        assert_allclose(row["stage2_dte_um_mean"], force / K_C * 1e6, rtol=1e-4)


def test_modes_hold_the_chain_s_stiffness_and_the_sprockets_inertias(install, mixed):
    """Lossless stages (a lossy element's split makes the stiffness matrix unsymmetric): the natural frequencies
    of the 4-shaft chain K theta = omega^2 J theta, K = sum_e k_e v v^T, v the element's levers (a mesh: base
    radii, k_n cos^2 beta_b along the transverse line; the chain: r_1, r_2 and k), built here from the design."""
    install()
    sets = ("--set", "stage.0.efficiency=1", "--set", "stage.1.chain_efficiency=1", "--set", "stage.2.efficiency=1")
    d = _json("design", mixed, *sets)
    m = _json("modes", mixed, *sets)
    assert m["elements"][1] == "stage 2 chain" and m["element_stiffness"][1] == K_C
    s1, _, s3 = d["stages"]

    def transverse(st) -> float:
        return st["mesh_stiffness"]["linearised_N_mm"] * 1e3 * math.cos(math.radians(st["base_helix_angle_deg"]))**2

    levers = [(0, 1, s1["pinion"]["base_diameter_mm"] / 2e3, s1["gear"]["base_diameter_mm"] / 2e3, transverse(s1)),
              (1, 2, _r(Z1), _r(Z2), K_C),
              (2, 3, s3["pinion"]["base_diameter_mm"] / 2e3, s3["gear"]["base_diameter_mm"] / 2e3, transverse(s3))]
    assert_allclose(m["element_stiffness"], [e[4] for e in levers], rtol=1e-12)
    K = np.zeros((4, 4))
    for a, b, ra, rb, k in levers:
        v = np.zeros(4)
        v[a], v[b] = ra, -rb
        K += k * np.outer(v, v)
    J = np.diag([s["inertia_kg_m2"] for s in d["shafts"]])
    for boundary, keep in (("free", [0, 1, 2, 3]), ("clamped_input", [1, 2, 3])):
        w2 = np.linalg.eigvals(np.linalg.solve(J[np.ix_(keep, keep)], K[np.ix_(keep, keep)])).real
        hand = sorted(np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * math.pi))
        got = [x["frequency_Hz"] for x in m["boundaries"][boundary]]
        assert_allclose(got[-len(keep) + (boundary == "free"):], hand[(boundary == "free"):], rtol=1e-6)


def test_the_toy_lewis_standard_rates_the_gear_stages_and_leaves_the_chain(install, mixed):
    """sigma_F = F_t / (b m_n Y), Y = pi (0.154 - 0.912 / z); sigma_H = 189.8 x 2.495 sqrt(F_t / (b d_1) (u + 1) / u);
    safeties: the material's limits (1500, 500 MPa) over them; K_v = 1 (no dynamic factor given)."""
    install()
    iso = _json("design", mixed)["stages"]
    d = _json("design", mixed, "--set", f"rating.standard={STD}")
    for st, ref, (z1, z2) in ((d["stages"][0], iso[0], (19, 75)), (d["stages"][2], iso[2], (19, 68))):
        f_t, b, m = ref["static_force_N"]["tangential"], ref["face_width_mm"], ref["normal_module_mm"]
        u = z2 / z1
        sigma_h = 189.8 * 2.495 * math.sqrt(f_t / (b * ref["pinion"]["pitch_diameter_mm"]) * (u + 1) / u)
        r = st["rating"]
        assert r["standard"] == "toy Lewis (a test plug-in)"
        for member, z in (("pinion", z1), ("gear", z2)):
            sigma_f = f_t / (b * m * math.pi * (0.154 - 0.912 / z))
            assert_allclose(r[member]["sigma_F_MPa"], sigma_f, rtol=1e-12)
            assert_allclose(r[member]["S_F"], 500.0 / sigma_f, rtol=1e-12)
            assert_allclose(r[member]["sigma_H_MPa"], sigma_h, rtol=1e-12)
            assert_allclose(r[member]["S_H"], 1500.0 / sigma_h, rtol=1e-12)
    assert "rating" not in d["stages"][1]
    (note,) = [w for w in d["warnings"] if w.get("check") == "not_rated"]
    assert note["stage"] == 2 and note["type"] == KIND


def test_life_on_the_toy_standard_s_curve_and_the_chain_refused(install, tmp_path):
    """Life of a parallel file rated by the plug-in's standard: a bin above the knee takes N = 3e6 (sigma /
    sigma_lim)^-m cycles, m = ln(3e6 / 1e4) / ln 2.5 (its bending line from (1e4, 2.5) to the knee (3e6, 1));
    the stress of a class is the design's scaled by F (sigma_F proportional to F: the standard has no
    rate_at_force). On the chain file: exit 2 naming the kind (it has no life facet)."""
    install()
    doc = _doc()
    doc["stage"] = [doc["stage"][0], doc["stage"][2]]
    doc["duty"] = [{"name": "rated", "hours": 1000.0, "torque_Nm": 1340.0, "speed_rpm": 1450.0},
                   {"name": "overload", "hours": 50.0, "torque_Nm": 12000.0, "speed_rpm": 1450.0}]
    path = tmp_path / "duty.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    sets = ("--set", f"rating.standard={STD}")
    design = _json("design", str(path), *sets)
    life = _json("life", str(path), "--static", *sets)["life"]
    bending = life["stages"][1]["pinion"]["bending"]
    sigma_design = design["stages"][1]["rating"]["pinion"]["sigma_F_MPa"]
    m = math.log(3e6 / 1e4) / math.log(2.5)
    for b in bending["bins"]:
        ratio = b["force_N"] / design["stages"][1]["static_force_N"]["tangential"]
        assert_allclose(b["stress_MPa"], sigma_design * ratio, rtol=1e-9)
    (over,) = [b for b in bending["bins"] if b["point"] == "overload"]
    assert over["stress_MPa"] > 500.0  # above the endurance limit: damage on the line
    n_fail = 3e6 * (over["stress_MPa"] / 500.0) ** -m
    assert_allclose(over["cycles_to_failure"], n_fail, rtol=1e-9)
    assert_allclose(over["cycles"], 50.0 * 60.0 * 1450.0 / (75 / 19), rtol=1e-12)  # stage 2 pinion's speed
    assert_allclose(over["damage"], over["cycles"] / n_fail, rtol=1e-9)
    # the rule's name does not claim ISO 6336-2/-3's curve (0.85 at 1e10) for the standard's own S-N lines
    assert "ISO 6336-2/-3" not in life["miner"] and "standard's own" in life["miner"], life["miner"]
    doc = _doc()
    doc["duty"] = [{"name": "rated", "hours": 1000.0, "torque_Nm": 1340.0, "speed_rpm": 1450.0}]
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    r = _invoke("life", str(path), "--static", "-q")
    assert r.exit_code == 2 and f'a stage of type "{KIND}" has none to rate' in r.output and "Traceback" not in r.output


def test_report_refuses_the_chain_and_runs_on_the_toy_standard(install, mixed, tmp_path):
    install()
    r = _invoke("report", mixed, "-q", "-o", str(tmp_path / "r.html"))
    assert r.exit_code == 2 and 'stage 2 is of type "test_chain"' in r.output
    assert not (tmp_path / "r.html").exists()


# ------------------------------------------------------------------------------------------ broken plug-ins
SPRING = ('kind = elements.kind_of("mesh")  # a lossy element: the chain\'s loss acts in the dynamics\n'
          '        law = elements.law_of(kind).pack(self.line)',
          'kind = elements.kind_of("spring")\n        from gearcli.model.spec import SpringSpec\n'
          '        law = elements.law_of(kind).pack(SpringSpec(self.line.stiffness_N_m_e, 0.0))')
MODEL_ETA = ("replace(mesh, efficiency=st.efficiency))", "replace(mesh, efficiency=st.efficiency), st.efficiency)")

BROKEN = {
    "raises on import": ([("KIND = ", "raise RuntimeError('no licence')\nKIND = ")], "design", 2,
                         f'stage[1].type: unknown stage type "{KIND}"; registered: "parallel", "planetary"; '
                         "plug-in 'gearcli_test_chain' (gearcli_test_chain:register) failed to load: "
                         "RuntimeError: no licence"),
    "raises on import, --set into its table": ([("KIND = ", "raise RuntimeError('no licence')\nKIND = ")], "design-set",
                                               2, f'stage.1.pitch_mm: stage[1] is of type "{KIND}", which no stage '
                                               "kind registered (registered: \"parallel\", \"planetary\"; an "
                                               "installed plug-in's, docs/plugins.md); plug-in 'gearcli_test_chain' "
                                               "(gearcli_test_chain:register) failed to load: RuntimeError: no licence"),
    "rate_design returns a wrong count": ([("return tuple(st if st.type", "return (stages[0],) or tuple(st if st.type")],
                                          "design-rated", 1, f'rating standard "{STD}" (gearcli_test_chain): '
                                          "rate_design returned 1 stages for 3"),
    "a facet given as its class": ([("kinds.provide(KIND, \"design\", ChainDesign())",
                                     "kinds.provide(KIND, \"design\", ChainDesign)")], "design", 1,
                                   "the facet provided is the class ChainDesign, not an instance of it"),
    "the standard given as its class": ([("register_standard(ToyLewis())", "register_standard(ToyLewis)")],
                                        "design-rated", 1, "the standard registered is the class ToyLewis"),
    "a standard without check_inputs": ([("    def check_inputs(self, cfg):", "    def check_inputs_(self, cfg):")],
                                        "design-rated", 1, f'rating standard "{STD}" (gearcli_test_chain): '
                                        "check_inputs is missing"),
    "a missing method": ([("    def fastest_rad_s(", "    def fastest_rad_s_(")], "simulate", 1,
                         f'stage type "{KIND}" (gearcli_test_chain): its design facet\'s fastest_rad_s is missing'),
    "a stage model whose place raises": ([("        n = len(bodies)\n", "        n = len(bodies) // 0\n")],
                                         "simulate", 1, "its stage model's place raised ZeroDivisionError"),
    "a result that is no dataclass": ([("        return ChainResult(\n", "        return dict(\n")], "design", 1,
                                      "its design facet's result for stage 2 has a dict, not a dataclass"),
    "design tables that are no list": ([("        return [t]\n\n    def simulation_tables",
                                         "        return None\n\n    def simulation_tables")], "design-table", 1,
                                       f'stage type "{KIND}" (gearcli_test_chain): its io facet\'s design_tables '
                                       "returned None, not a list of rich renderables"),
    "a stage JSON that is no dict": ([("        stage.pop(\"rating\", None)\n        return {",
                                       "        return 5\n        return {")], "design", 1,
                                     "its io facet's json_stage returned 5, not a dict"),
    "a simulated stage JSON that is no dict": ([("        return {\"index\": stage[\"index\"], \"type\": KIND,",
                                                 "        return [stage[\"index\"]]\n        return {\"index\": "
                                                 "stage[\"index\"], \"type\": KIND,")], "simulate", 1,
                                               "its io facet's json_simulated_stage returned [2], not a dict"),
    "a stage JSON without index and type": ([("        return {\"index\": stage.pop(\"index\"), \"type\": stage.pop(\"type\"),",
                                              "        return {")], "design-csv", 1,
                                            "its io facet's json_stage returned {'index': 2, 'ratio': "),
    "a simulated stage JSON without index": ([("        return {\"index\": stage[\"index\"], \"type\": KIND,",
                                               "        return {\"type\": KIND,")], "simulate", 1,
                                             "json_simulated_stage returned {'type': 'test_chain', 'chain_force_N': "),
    "diagnostics that are texts": ([("    def diagnostics(self, result):\n        return ()",
                                     "    def diagnostics(self, result):\n        return ['chain slack']")], "design", 1,
                                   "its design facet's diagnostics returned 'chain slack' for stage 2, not a "
                                   "gearcli.diagnostics.Diagnostic"),
    # no stage model: the chain's pair of its line, which loses nothing at MeshSpec's default efficiency 1 while the
    # design loses 4 %: upstream T_in = T_out / (i eta) would be eta_design / eta_line = 0.96 x the design's
    "no stage model and a lossless line": ([("        return ChainModel(mesh.base_radius_pinion_m,",
                                             "        return None and ChainModel(mesh.base_radius_pinion_m,")],
                                           "simulate", 1, "its stage model is None, so stage 2 is placed as a pair of "
                                           "its line, whose efficiency 1 is not its design's 0.96: the simulated "
                                           "forces before it would be 0.96 x the design's"),
    "a negative speed ratio": ([("        return self.driven_teeth / self.driver_teeth", "        return -2.0")],
                               "design", 1, "its table's speed_ratio is -2.0 for stage 2, not a finite number > 0"),
    "an efficiency above 1": ([("        return self.chain_efficiency", "        return 1.5")], "design", 1,
                              "its table's efficiency is 1.5 for stage 2, not a number in (0, 1]"),
    # a table without what every stage table has: refused where it registers (its plug-in fails to load, named where
    # a file names its kind), not an AttributeError of gearcli's own far from its cause ("internal error")
    "a table without mesh": ([("    mesh: None = None\n", "")], "design", 2,
                             "failed to load: PluginError: stage type \"test_chain\" (gearcli_test_chain): its table "
                             "ChainStage has no mesh: every stage table has type: Literal[\"test_chain\"], the fields "
                             "mesh and shaft"),
    "a table without shaft nor efficiency": ([("    shaft: None = None\n", ""), ("    def efficiency(", "    def eta(")],
                                             "simulate", 2, "its table ChainStage has no shaft, efficiency: every"),
    "a table whose type names another kind": ([('type: Literal["test_chain"]', 'type: Literal["test_chains"]')],
                                              "design", 2, "its table ChainStage has type typing.Literal['test_chains']"),
    # a line of numbers the model cannot integrate: named where the plug-in returns them, not a run whose chain
    # carries nothing (a negative spring never pulls: exit 0, a 14 m "stretch") nor gearcli's "internal error"
    "a line of negative stiffness": ([("stiffness_N_m_e=st.stiffness_N_m,", "stiffness_N_m_e=-st.stiffness_N_m,")],
                                     "simulate", 1, "its model facet's line raised ValueError: "
                                     "MeshSpec.stiffness_N_m_e must be a finite number > 0, got -20000000.0"),
    "a line of a zero lever": ([("MeshSpec(base_radius_pinion_m=r1,", "MeshSpec(base_radius_pinion_m=0.0,")],
                               "simulate", 1, "MeshSpec.base_radius_pinion_m must be a finite number > 0, got 0.0"),
    "a line of a NaN static force": ([("static_tangential_N=st.chain_force_N,", "static_tangential_N=math.nan,")],
                                     "simulate", 1, "MeshSpec.static_tangential_N must be a finite number, got nan"),
    # a plug-in's sys.exit() ended the command with its code and no word (exit 0, no output: a script read success);
    # a table property that raises was gearcli's "internal error" (the schema's validation reads speed_ratio)
    "sys.exit() in a facet": ([("    def diagnostics(self, result):\n        return ()",
                                "    def diagnostics(self, result):\n        raise SystemExit(0)")], "design", 1,
                              "its design facet's diagnostics raised SystemExit: 0"),
    "sys.exit() on import": ([("KIND = ", "raise SystemExit(0)\nKIND = ")], "design", 2,
                             "(gearcli_test_chain:register) failed to load: SystemExit: 0"),
    "sys.exit() in a stage model's place": ([("        n = len(bodies)\n", "        raise SystemExit(0)\n")],
                                            "simulate", 1, "its stage model's place raised SystemExit: 0"),
    "sys.exit() in a standard": ([("    def check_inputs(self, cfg):\n", "    def check_inputs(self, cfg):\n"
                                   "        raise SystemExit(0)\n")], "design-rated", 1,
                                 f'rating standard "{STD}" (gearcli_test_chain): check_inputs raised SystemExit: 0'),
    "a table's speed_ratio that raises": ([("        return self.driven_teeth / self.driver_teeth",
                                            "        raise RuntimeError('no sprockets')")], "design", 1,
                                          f'stage type "{KIND}" (gearcli_test_chain): its table\'s speed_ratio '
                                          "raised RuntimeError: no sprockets"),
    "a table's efficiency that raises": ([("        return self.chain_efficiency", "        raise RuntimeError('no eta')")],
                                         "simulate", 1, "its table's efficiency raised RuntimeError: no eta"),
    # a non-finite figure in its result: the plug-in's (exit 1), not "check module, face width, density" (exit 2)
    "a result holding NaN": ([("chain_force_N=t_in / r1,", "chain_force_N=math.nan,")], "design", 1,
                             f'stage type "{KIND}" (gearcli_test_chain): its design facet\'s result for stage 2 has a '
                             "non-finite chain_force_N (nan)"),
    # a register that failed half-way left what it had registered: its table and design facet, so the file ran
    # into "no model facet registered" (exit 1), never naming the plug-in's error; one that failed at its end ran
    # with exit 0 and no word of the failure. A plug-in that fails to load provides nothing (docs/plugins.md)
    "register raises half-way": ([('    kinds.provide(KIND, "model", ChainModelKind())\n',
                                   '    raise RuntimeError("no licence")\n')], "simulate", 2,
                                 f'stage[1].type: unknown stage type "{KIND}"; registered: "parallel", "planetary"; '
                                 "plug-in 'gearcli_test_chain' (gearcli_test_chain:register) failed to load: "
                                 "RuntimeError: no licence"),
    "sys.exit() at the end of register": ([("    register_standard(ToyLewis())\n",
                                            "    register_standard(ToyLewis())\n    raise SystemExit(0)\n")],
                                          "design-rated", 2, "(gearcli_test_chain:register) failed to load: "
                                          "SystemExit: 0"),
    "a lossless connector for a lossy stage": ([SPRING], "simulate", 1,
                                               "stage model's connectors lose 0 of the power, its design 0.04"),
    "a model efficiency no element loses": ([SPRING, MODEL_ETA], "simulate", 1,
                                            "its stage model gives efficiency = 0.96, which no element of it loses"),
}


@pytest.mark.parametrize("case", list(BROKEN))
def test_a_broken_plug_in_is_one_line_with_its_exit_code(install, mixed, tmp_path, case):
    edits, command, code, message = BROKEN[case]
    text = SOURCE
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    install(text)
    args = {"design": ["design", mixed], "design-rated": ["design", mixed, "--set", f"rating.standard={STD}"],
            "simulate": ["simulate", mixed, "-o", str(tmp_path / "run.json")],
            "design-set": ["design", mixed, "--set", "stage.1.pitch_mm=20"],
            "design-table": ["design", mixed, "--format", "table"],
            "design-csv": ["design", mixed, "--format", "csv"]}[command]
    r = _invoke(*args, "-q", *(() if "--format" in args else ("--format", "json")))
    assert r.exit_code == code, r.output
    assert message in r.output
    assert "Traceback" not in r.output and "internal error" not in r.output
    assert len(r.output.strip().splitlines()) == 1, r.output
    assert not (tmp_path / "run.json").exists()


def test_two_plug_ins_registering_one_standard_name(install, mixed):
    """Two installed packages that both register ``test_toy_lewis`` (the second with a chain kind of another
    name): exit 1, one line naming both."""
    install()
    install(SOURCE.replace('KIND = "test_chain"', 'KIND = "test_chain_b"')
            .replace('Literal["test_chain"]', 'Literal["test_chain_b"]'), package="gearcli_test_chain_b")
    r = _invoke("design", mixed, "-q")
    assert r.exit_code == 1 and "Traceback" not in r.output
    assert f'rating standard "{STD}" is registered twice, by plug-in' in r.output  # in the entry points' order
    assert "'gearcli_test_chain' (gearcli_test_chain:register)" in r.output
    assert "'gearcli_test_chain_b' (gearcli_test_chain_b:register)" in r.output
    assert len(r.output.strip().splitlines()) == 1


def test_the_schema_holds_the_installed_plug_ins_stage_tables(install, mixed):
    """``gearcli schema`` loads the installed plug-ins first: the file with the chain is valid against it, and a
    chain table missing a key of its own is not (the schema is the one the file is validated with)."""
    import tomllib

    install()
    schema = _json_plain("schema")
    doc = tomllib.loads(Path(mixed).read_text(encoding="utf-8"))
    assert valid(doc, schema, schema)
    del doc["stage"][1]["pitch_mm"]
    assert not valid(doc, schema, schema)


def _json_plain(*args: str) -> dict:
    r = _invoke(*args)
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)
