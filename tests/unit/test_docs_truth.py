"""docs/tour.md and docs/errata.md quote the seed reducer's numbers; they must be what the tool prints now, to the
digits shown. The design figures are checked against the hand calculation written out here (the errata's
corrected values, from the seed's geometry), the simulated ones against a run of the seed (a doc figure that
drifts from the tool is a defect of the doc, so the page is compared with the run, digit for digit)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TOUR = (ROOT / "docs" / "tour.md").read_text()
ERRATA = (ROOT / "docs" / "errata.md").read_text()
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


def _in(text: str, figure: str) -> None:
    assert figure in text, f"the page should quote {figure!r}"


def test_seed_design_figures_are_the_hand_calculation_and_the_pages_quote_them():
    from gearcli import api

    _, design = api.load_and_design(SEED)
    # hand calculation: teeth 21/51, 17/50, 17/53; input 3600 °/s; output torque 5.31e6 N·mm (the file's load)
    ratio = (51 / 21) * (50 / 17) * (53 / 17)
    assert math.isclose(design.total_ratio, ratio, rel_tol=1e-12)
    out_deg_s = 3600 / ratio
    out_rpm = out_deg_s / 6
    # E* of two steels E = 2.07e5 MPa, ν = 0.29: 1/E* = 2 (1 − ν²)/E; K = 4/3 √R E* with stage 1's R
    e_star = 2.07e5 / (2 * (1 - 0.29**2))
    stage = design.stages[0]
    k_hertz = 4 / 3 * math.sqrt(stage.equivalent_radius_mm) * e_star
    assert math.isclose(stage.effective_modulus_MPa, e_star, rel_tol=1e-12)
    assert math.isclose(stage.hertz_stiffness_N_mm1_5, k_hertz, rel_tol=1e-12)
    # stage 1 forces from the pinion torque T1 = T_out / ratio (η = 1), d1 = z m_n / cos β
    d1 = 21 * 12 / math.cos(math.radians(12))
    ft = 2 * design.input_torque_Nmm / d1
    alpha_t = math.atan(math.tan(math.radians(20)) / math.cos(math.radians(12)))
    assert math.isclose(stage.static_force_N.tangential, ft, rel_tol=1e-9)
    for text in (TOUR, ERRATA):
        _in(text, f"{out_deg_s:.2f} °/s")
        _in(text, f"{out_rpm:.2f} rpm")
        _in(text, f"{e_star:.3e}".replace("e+05", "e5") + " MPa")
        _in(text, f"{k_hertz:.3e}".replace("e+06", "e6") + " N/mm^1.5")
    _in(TOUR, f"total ratio {ratio:.4f}")
    _in(TOUR, f"F_t {ft:.1f} N, F_r {ft * math.tan(alpha_t):.1f} N, F_a {ft * math.tan(math.radians(12)):.1f} N")
    _in(ERRATA, f"{3600 * 21 / 51:.2f} °/s")


@pytest.fixture(scope="module")
def seed_run():
    from gearcli import api

    # a fresh process runs the seed on the Python engine (fewer evaluations than loading the compiled one costs);
    # named here so that a process that has loaded the compiled engine prints the same figures
    loaded, design = api.load_and_design(SEED, ["simulation.engine=python"])
    return design, api.simulate(loaded.design, design)


def test_tour_simulation_table_and_method_line_are_what_simulate_prints(seed_run):
    design, result = seed_run
    means = [s.tangential_N.mean for s in result.stages]
    static = [s.static_force_N.tangential for s in design.stages]
    s1 = result.stages[0]
    _in(TOUR, f"| {s1.tangential_N.mean:.1f} / {s1.radial_N.mean:.1f} / {s1.axial_N.mean:.1f} |")
    for k in (1, 2):
        _in(TOUR, f"| {means[k]:.1f} | {100 * (means[k] / static[k] - 1):+.2f} %".replace("-", "−"))
    _in(TOUR, f"{100 * (means[0] / static[0] - 1):+.2f} %".replace("-", "−"))
    _in(TOUR, f"std {s1.tangential_N.std:.0f} N on stage 1")
    _in(TOUR, f"({s1.dynamic_factor:.2f} on the seed's stage 1")
    _in(TOUR, f"over it ({s1.runup_factor:.2f}, at {s1.peak_time_s:.2f} s")
    _in(TOUR, f"{s1.peak_tangential_N / 1e3:.2f} k at {s1.peak_time_s:.3f} s")
    assert result.extra is not None
    rigid = result.extra["start"]["rigid_peak_N"][0]
    _in(TOUR, f"| {rigid / 1e3:.2f} k (rigid-body")
    _in(TOUR, f"| {100 * (s1.peak_tangential_N / rigid - 1):+.1f} % (dynamic overshoot)")
    ratio = result.ratio
    _in(TOUR, f"| {ratio:.4f} | {100 * (ratio / design.total_ratio - 1):+.4f} %".replace("-", "−"))
    _in(TOUR, f"({result.natural_frequencies_Hz[0]:.0f} Hz;")


@pytest.mark.slow
@pytest.mark.bitwise
def test_tour_solver_lines_are_what_simulate_prints(seed_run):
    """The solver's counters and the energy residual (the integrator's quadrature error, fixed by its steps) are
    exact for a step sequence: the bitwise tier's, on the pinned kernel."""
    _, result = seed_run
    solver = result.solver
    _in(TOUR, f"`solver {solver.method} rtol {solver.rtol:g} steps {solver.steps} nfev {solver.nfev}`")
    _in(TOUR, f"`energy residual\n{solver.energy_residual:.2e}`")
    # the method line: its indicator and predicted evaluations (the seconds are the engine's it is priced on)
    flat = re.sub(r"\s+", " ", TOUR)
    head, _, tail = solver.choice_reason.partition(": predicted ")
    _in(flat, f"`method: {head}: predicted ")
    for method, nfev in re.findall(r"(DOP853|Radau) (\S+) evaluations", tail):
        _in(flat, f"{method} {nfev} evaluations")
    _in(flat, f"{tail.rsplit(': ', 1)[1]}` (the load time")


def test_every_warning_code_is_named_in_the_output_contract():
    """docs/output.md, "Warnings", lists the codes a script may meet; a code the tool emits that the page does
    not name is one a user cannot look up."""
    import gearcli.diagnostics as dg

    codes = {v for k, v in vars(dg).items() if k.isupper() and isinstance(v, str) and re.fullmatch(r"[a-z_0-9]+", v)}
    assert len(codes) > 30  # the module's constants were found
    text = (ROOT / "docs" / "output.md").read_text()
    assert sorted(c for c in codes if f"`{c}`" not in text) == []


# The product contract's machine-readable keys (its section 5, with section 12's `warnings` objects and factors),
# copied here: the output contract page must name each and the seed's JSON and CSV must carry each.
CONTRACT_DESIGN_TOP = ["total_ratio", "output_speed_deg_s", "output_speed_rpm", "input_torque_Nmm", "warnings",
                       "stages", "gearcli_version", "input_sha256"]
CONTRACT_DESIGN_STAGE = ["ratio", "contact_ratio_transverse", "overlap_ratio", "contact_ratio_total",
                         "center_distance_mm", "equivalent_radius_mm", "effective_modulus_MPa",
                         "hertz_stiffness_N_mm1_5", "mesh_frequency_Hz", "static_force_N",
                         "iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um"]
CONTRACT_FORCES = ["tangential", "radial", "axial", "normal"]
CONTRACT_MEMBER = ["teeth", "pitch_diameter_mm", "base_diameter_mm", "tip_diameter_mm", "root_diameter_mm",
                   "speed_deg_s", "speed_rpm", "torque_Nmm", "inertia_kg_m2"]
CONTRACT_SUMMARY = ["ratio", "output_speed_deg_s", "window_s", "stages"]
CONTRACT_SUMMARY_STAGE = ["tangential_N", "radial_N", "axial_N", "dynamic_factor", "runup_factor"]
CONTRACT_SOLVER = ["method", "rtol", "atol", "nfev", "njev", "steps", "wall_s", "energy_residual"]
CONTRACT_CSV = ["time_s", "shaft1_speed_deg_s", "shaft4_speed_deg_s", "input_torque_Nmm", "stage1_tangential_N",
                "stage1_radial_N", "stage1_axial_N", "stage3_penetration_mm"]


def test_the_contracts_keys_are_in_the_output_page_and_in_the_seeds_output(tmp_path):
    import csv
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    page = (ROOT / "docs" / "output.md").read_text()
    generic = {"shaft1_speed_deg_s": "shaft{i}_speed_deg_s", "shaft4_speed_deg_s": "shaft{i}_speed_deg_s",
               "stage1_tangential_N": "stage{k}_tangential_N", "stage1_radial_N": "stage{k}_radial_N",
               "stage1_axial_N": "stage{k}_axial_N", "stage3_penetration_mm": "stage{k}_penetration_mm"}
    for key in {*CONTRACT_DESIGN_TOP, *CONTRACT_DESIGN_STAGE, *CONTRACT_FORCES, *CONTRACT_MEMBER,
                *CONTRACT_SUMMARY, *CONTRACT_SUMMARY_STAGE, *CONTRACT_SOLVER, *CONTRACT_CSV}:
        assert f"`{generic.get(key, key)}`" in page, key
    runner = CliRunner()
    out = tmp_path / "d.json"
    assert runner.invoke(cli, ["-q", "design", SEED, "-o", str(out)]).exit_code == 0
    d = json.loads(out.read_text())
    stage = d["stages"][0]
    assert set(CONTRACT_DESIGN_TOP) <= d.keys() and set(CONTRACT_DESIGN_STAGE) <= stage.keys()
    assert set(CONTRACT_FORCES) <= stage["static_force_N"].keys()
    assert set(CONTRACT_MEMBER) <= stage["pinion"].keys() and set(CONTRACT_MEMBER) <= stage["gear"].keys()
    assert all({"code", "message"} <= w.keys() for w in d["warnings"])
    short = ["--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50"]
    out = tmp_path / "s.json"
    assert runner.invoke(cli, ["-q", "simulate", SEED, *short, "-o", str(out)]).exit_code == 0
    s = json.loads(out.read_text())
    assert set(CONTRACT_SUMMARY) <= s["summary"].keys() and set(CONTRACT_SOLVER) <= s["solver"].keys()
    for st in s["summary"]["stages"]:
        assert set(CONTRACT_SUMMARY_STAGE) <= st.keys()
        assert all({"mean", "min", "max", "std"} <= st[k].keys() for k in ("tangential_N", "radial_N", "axial_N"))
    assert "series" not in s
    out = tmp_path / "s.csv"
    assert runner.invoke(cli, ["-q", "simulate", SEED, *short, "-o", str(out)]).exit_code == 0
    header = next(csv.reader(out.open()))
    assert header[0] == "time_s" and set(CONTRACT_CSV) <= set(header)


def _key_names(doc: object, skip: frozenset[str]) -> set[str]:
    """Every object key in a JSON document, not descending into the keys in ``skip`` (objects whose keys are data:
    body and element names, a rating's factors, a warning's own data)."""
    found: set[str] = set()
    if isinstance(doc, dict):
        for k, v in doc.items():
            found.add(k)
            if k not in skip:
                found |= _key_names(v, skip)
    elif isinstance(doc, list):
        for v in doc:
            found |= _key_names(v, skip)
    return found


def test_every_key_of_the_design_simulate_modes_and_report_json_is_named_in_the_output_contract(tmp_path):
    """The reverse of the contract check above: a key the tool writes that docs/output.md does not name is one a
    script cannot look up. The drivetrain scene adds the couplings' and shafts' keys (`twist_rad`); the report its
    comparison, spectrum and accuracy study (a two-rung ladder on a short run)."""
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    page = (ROOT / "docs" / "output.md").read_text()
    drivetrain = str(ROOT / "configs" / "concrete_mixer_drivetrain.toml")
    short = ["--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50"]
    skip = frozenset({"warnings", "rating", "shape", "energy_share"})
    runs = [["design", SEED], ["modes", SEED], ["simulate", SEED, *short], ["design", drivetrain],
            ["simulate", drivetrain, *short],
            ["report", SEED, "--set", "simulation.duration_s=0.3", "--rtols", "1e-5,1e-6"]]
    missing = {}
    for k, args in enumerate(runs):
        out = tmp_path / f"{k}.json"
        r = CliRunner().invoke(cli, ["-q", *args, "-o", str(out)])
        assert r.exit_code == 0, r.output
        unnamed = sorted(key for key in _key_names(json.loads(out.read_text()), skip) if f"`{key}`" not in page)
        if unnamed:
            missing[" ".join(args[:2])] = unnamed
    assert missing == {}


@pytest.mark.slow
@pytest.mark.bitwise
def test_numerics_report_ladder_excerpt_has_the_evaluations_of_the_runs():
    """docs/numerics.md quotes the seed report's work-precision ladder: each DOP853 rung's nfev is that of a run of
    the seed at the rung's rtol (the same step sequence on either engine). The file's own rung (1e-6, which the
    tour quotes too) to the evaluation; the looser rungs within the few evaluations that the BLAS kernel numpy
    dispatches to moves them (the page says so: this suite pins OpenBLAS's Haswell kernel, tests/conftest.py)."""
    from gearcli import api

    page = (ROOT / "docs" / "numerics.md").read_text()
    rows = re.findall(r"^\| auto \(DOP853\) \[compiled\] \| (\S+) \| \S+ \| (\d+) \|", page, re.M)
    assert len(rows) == 3
    for rtol, nfev in rows:
        loaded, design = api.load_and_design(SEED, ["simulation.engine=python", "simulation.method=DOP853",
                                                    f"simulation.rtol={rtol}", "simulation.error_estimate=false"])
        found = api.simulate(loaded.design, design).solver.nfev
        if float(rtol) == 1e-6:
            assert found == int(nfev)
        else:
            assert abs(found - int(nfev)) <= 0.01 * int(nfev), (rtol, found, nfev)


def test_modes_element_stiffness_is_the_design_tangent_on_the_transverse_line_as_the_page_says():
    """docs/output.md: a mesh's `element_stiffness` is N/m along the transverse line of action, the design's normal
    tangent `linearised_N_mm` × 1000 cos² β_b (h = δ cos β_b, so dF_n/dδ = k_n cos β_b and the transverse force's
    F_n cos β_b gives the other)."""
    from gearcli import api

    loaded, design = api.load_and_design(SEED)
    clamped = api.modes(loaded.design, design)[0]
    for k, st in enumerate(design.stages):
        expected = st.linearised_stiffness_N_mm * 1e3 * math.cos(math.radians(st.base_helix_angle_deg)) ** 2
        assert clamped.connectors[k] == f"stage {k + 1} mesh"
        assert math.isclose(clamped.stiffness[k], expected, rel_tol=1e-9), k


def test_elements_page_names_the_drivetrain_channels_the_csv_has(tmp_path):
    """docs/elements.md's "New channels" are the CSV columns of its own example, configs/concrete_mixer_drivetrain.toml
    (°/s and N·mm: the names carry the file's units)."""
    import csv

    from click.testing import CliRunner

    from gearcli.cli import cli

    page = (ROOT / "docs" / "elements.md").read_text()
    paragraph = page[page.index("New channels:"):].split("\n\n")[0]
    named = re.findall(r"`([A-Za-z_{}0-9]+)`", paragraph.split("(named in")[0])
    assert len(named) == 5
    out = tmp_path / "d.csv"
    args = ["-q", "simulate", str(ROOT / "configs" / "concrete_mixer_drivetrain.toml"), "--set",
            "simulation.duration_s=0.05", "--set", "simulation.steps=50", "-o", str(out)]
    assert CliRunner().invoke(cli, args).exit_code == 0
    header = next(csv.reader(out.open()))
    for name in named:
        pattern = name.replace("{i}", r"\d+")
        assert any(re.fullmatch(pattern, col) for col in header), name
