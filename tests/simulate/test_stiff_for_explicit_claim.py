"""``stiff_for_explicit`` says 'method = "auto" would use Radau' of a requested explicit run: the claim must be
``auto``'s own decision. It was decided by another rule (Radau's predicted wall time below DOP853's, loading
included), not ``auto``'s (DOP853 unless Radau is ``IMPLICIT_MARGIN`` = 1.3 times cheaper, loading aside): a
rattling planetary train (4 planets, backlash, TE, star-delta start) requested with RK45 on the compiled engine,
DOP853 predicted 0.10 s and Radau 0.087 s, was told "auto would use Radau" where auto took DOP853 (and the Python
engine's run of the same scene, same numbers, said nothing: the engines' warnings disagreed)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.scene import spec_from_design
from gearcli.simulate import choice as choice_mod
from gearcli.simulate.choice import choose_method
from gearcli.simulate.run import _choice_warnings

ROOT = Path(__file__).resolve().parents[2]
STIFF = ROOT / "configs" / "stiff_linear_mesh.toml"  # max|lambda| T = 3.6e4, above the 1e4 of a stiff scene


@pytest.fixture(scope="module")
def scene():
    cfg = load_design(str(STIFF), ()).design
    return spec_from_design(cfg, compute_design(cfg)), cfg.simulation.duration_s


def _priced(monkeypatch, dop853_s: float, radau_s: float, load_s: float) -> None:
    """The cost model's wall times (DOP853, Radau), each with ``load_s`` of loading the compiled engine in them."""
    def costs(*args, **kwargs):
        return (1e5, 1e4), (dop853_s + load_s, radau_s + load_s), ("compiled", "compiled"), (load_s, load_s)

    monkeypatch.setattr(choice_mod, "predicted_costs", costs)


# (DOP853 s, Radau s, load s) and auto's method by the documented rule, by hand: DOP853 unless its time (loading
# aside) exceeds 1.3x Radau's
CASES = [
    (0.10, 0.087, 0.23, "DOP853"),  # 0.10 <= 1.3 x 0.087 = 0.113: the margin keeps DOP853 (the case found)
    (0.12, 0.10, 0.0, "DOP853"),  # 0.12 <= 0.13
    (0.14, 0.10, 0.0, "Radau"),  # 0.14 > 0.13
    (2.0, 0.5, 0.6, "Radau"),
    (0.5, 2.0, 0.0, "DOP853"),
]


@pytest.mark.parametrize(("dop", "radau", "load", "auto_takes"), CASES)
@pytest.mark.parametrize("requested", ["DOP853", "RK45"])
def test_the_warning_says_what_auto_does(monkeypatch, scene, dop, radau, load, auto_takes, requested):
    _priced(monkeypatch, dop, radau, load)
    spec, duration = scene
    auto = choose_method(spec, duration, "auto")
    assert auto.method == auto_takes  # the rule of docs/numerics.md, by hand above
    warned = _choice_warnings(choose_method(spec, duration, requested))
    assert [w.code for w in warned] == (["stiff_for_explicit"] if auto_takes == "Radau" else [])
    if warned:
        assert 'method = "auto" would use Radau' in warned[0].message
