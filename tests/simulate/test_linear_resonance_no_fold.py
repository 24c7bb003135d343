"""A linear oscillator at resonance has one response: its Floquet multipliers near +1 are no fold.

tr20c: data/linear_te_resonance.toml is a single-DOF mesh oscillator (linear mesh, no backlash, damping ratio 0.01)
forced by its transmission error at its natural frequency. `steady = "periodic"` found its orbit, then judged the
multiplier pair 0.939 +- 0.0002i (within 0.1 of +1, imaginary part below 0.05) a fold and warned
`near_bifurcation`: "the branch turns back nearby, the response may jump to another branch". A linear system has
one periodic response; its multipliers are exp(lambda T) of lambda = -zeta w_n +- i w_d, a complex pair of modulus
exp(-zeta w_n T), which sits near +1 because w_d T is close to 2 pi (resonance), not because a branch turns.

Independent reference, the oscillator's closed form (m_e = J / r_b^2, c = 2 zeta sqrt(k m_e), Omega = z n):
    m_e q'' + c q' + k q = F_0 + m_e Omega^2 e_1 cos(Omega t),
    |q| = m_e Omega^2 e_1 / sqrt((k - m_e Omega^2)^2 + (c Omega)^2),  F_t amplitude = sqrt(k^2 + (c Omega)^2) |q| cos(alpha).
"""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner
from te_oscillator import orbit

from gearcli.cli import cli

SCENE = Path(__file__).parent / "data" / "linear_te_resonance.toml"


def test_a_linear_resonance_is_no_fold():
    res = CliRunner().invoke(cli, ["simulate", str(SCENE), "--format", "json", "-q"])
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    static, amplitude, mu = orbit(0.01, 2398.2)
    ft = doc["summary"]["stages"][0]["tangential_N"]
    assert abs(ft["mean"] - static) <= 1e-4 * static  # the orbit is the closed form's ...
    assert abs(ft["max"] - (static + amplitude)) <= 1e-3 * static
    assert abs(ft["min"] - (static - amplitude)) <= 1e-3 * static
    steady = doc["summary"]["steady"]
    got = sorted((complex(*m) for m in steady["multipliers"]), key=lambda m: -m.imag)[0]
    assert abs(got - mu) <= 1e-3  # ... its multipliers exp(lambda T), a complex pair near +1 (|mu - 1| < 0.1) ...
    assert abs(mu - 1) < 0.1
    assert steady["bifurcation"] == "none"  # ... and no fold: a linear system has one response
    assert "near_bifurcation" not in [w["code"] for w in doc["warnings"]]
