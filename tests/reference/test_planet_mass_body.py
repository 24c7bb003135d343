"""A planet's mass, where the file does not give `mass_kg`, is the mass of the body whose inertia the model takes
(DESIGN §11: "Members take `inertia_kg_m2` (planets also `mass_kg`), else from geometry; the carrier body carries the
planets' translational inertia N m_p r_c²").

A planet whose body the file describes (here the NREL 5 MW stage's: bore 408.99 mm, rim and web) has ISO 6336-1's
body as its inertia, a disc of d_m = (d_a + d_f)/2 with the bore, J = π ρ b (d_m⁴ − d_bore⁴)/32 (docs/iso6336.md).
Its mass was that of another body, a disc of the pitch diameter with the bore: 1262 kg where the body the inertia is
of weighs 1501 kg, so the carrier's N m_p r_c² was 16 % light. By hand, for a hollow disc:
m = ρ π b (d_m² − d_bore²)/4, and J = m (d_m² + d_bore²)/8 ties the two."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "planetary_stage.toml"
DENSITY = 7830.0  # the planet's material, 18CrNiMo7-6 in the file


def test_a_described_planet_body_has_the_mass_of_the_body_its_inertia_is_of():
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    stage = json.loads(res.stdout)["stages"][0]
    planet, carrier = stage["planet"], stage["carrier"]
    d_m = (planet["tip_diameter_mm"] + planet["root_diameter_mm"]) / 2 * 1e-3
    bore, b = 408.99e-3, 491e-3
    m_p = DENSITY * math.pi * b * (d_m**2 - bore**2) / 4
    assert_allclose(planet["mass_kg"], m_p, rtol=1e-12)
    assert_allclose(planet["inertia_kg_m2"], m_p * (d_m**2 + bore**2) / 8, rtol=1e-12)
    r_c = stage["meshes"][0]["center_distance_mm"] * 1e-3  # a_w of the sun-planet mesh
    assert_allclose(carrier["planets_translational_inertia_kg_m2"], 3 * m_p * r_c**2, rtol=1e-12)
    assert_allclose(carrier["inertia_kg_m2"], 1500 + 3 * m_p * r_c**2, rtol=1e-12)  # carrier.inertia_kg_m2 = 1500
