"""Sweep definitions: the --vary grid, the --random samples and the output columns (docs/sweeps.md)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.stats import norm

from gearcli.sweep.columns import columns
from gearcli.sweep.spec import SweepUsageError, canonical_key, parse_random, parse_vary, spec_from_options, unit_samples


def test_range_is_inclusive_and_evenly_spaced():
    axis = parse_vary("input.speed_rpm=300:1500:5")
    assert axis.key == "input.speed_rpm"
    assert axis.values == (300, 600, 900, 1200, 1500)  # (1500 - 300) / 4 = 300 rpm apart, by hand
    assert all(isinstance(v, int) for v in axis.values)  # integer ends on integer steps stay integers (teeth)
    assert parse_vary("x.y=0.1:0.2:3").values == pytest.approx((0.1, 0.15, 0.2), rel=1e-15)
    assert parse_vary("a.b=5:5:1").values == (5,)


def test_range_whose_span_overflows_stays_finite():
    """-1e308:1e308 spans 2e308, beyond the largest float: the grid is still the two ends and their midpoint 0 (by
    hand), each point then refused by the key's own bounds as a failed row; (STOP - START) i / (N - 1) made the
    points nan, inf, inf (an empty key cell in CSV, an internal error writing JSON)."""
    assert parse_vary("input.speed_rpm=-1e308:1e308:3").values == (-1e308, 0.0, 1e308)
    assert parse_vary("input.speed_rpm=1.7e308:-1.7e308:5").values == pytest.approx(
        (1.7e308, 0.85e308, 0.0, -0.85e308, -1.7e308), rel=1e-15, abs=0.0)
    # a span that fits keeps the grid's arithmetic bit for bit (a resumed -o file compares its values)
    assert parse_vary("x.y=0.1:0.7:7").values == tuple(0.1 + (0.7 - 0.1) * i / 6 for i in range(7))


def test_uniform_whose_span_overflows_draws_finite_values():
    d = parse_random("k.x=uniform(-1e308,1e308)")
    assert list(d.ppf(np.array([0.0, 0.25, 0.5]))) == [-1e308, -0.5e308, 0.0]  # a (1 - u) + b u, by hand
    assert list(parse_random("k.x=uniform(1,3)").ppf(np.array([0.0, 0.25]))) == [1.0, 1.5]


def test_value_lists_read_as_toml_values():
    assert parse_vary("stage.0.pinion.hand=left,right").values == ("left", "right")
    assert parse_vary("stage[0].backlash_mm=0.1, 0.25").values == (0.1, 0.25)
    assert canonical_key("stage[0].pinion.teeth") == "stage.0.pinion.teeth"


@pytest.mark.parametrize("text", ["input.speed_rpm", "input.speed_rpm=", "=1,2", "input.speed_rpm=1:2",
                                  "input.speed_rpm=a:2:3", "input.speed_rpm=1,,2", "input.speed_rpm=1:2:0",
                                  "input.speed_rpm=nan,1", "input.speed_rpm=1,inf", "input.speed_rpm=-inf"])
def test_bad_vary_is_a_usage_error(text):
    with pytest.raises(SweepUsageError) as err:
        parse_vary(text)
    assert err.value.exit_code == 2


@pytest.mark.parametrize("text", ["k.x=normal(1)", "k.x=normal(1,0)", "k.x=uniform(2,1)", "k.x=gauss(1,2)",
                                  "k.x=normal(a,1)", "k.x=normal(1e308,1e308)", "k.x=normal(0,1e308)"])
def test_bad_random_is_a_usage_error(text):
    with pytest.raises(SweepUsageError):
        parse_random(text)


def test_grid_is_the_product_first_key_slowest():
    spec = spec_from_options(["input.speed_rpm=300:1500:3", "stage.0.backlash_mm=0.1,0.2"], [], None, "lhs", None,
                             None)
    points = [b[0] for b in spec.branches()]
    assert all(len(b) == 1 for b in spec.branches())  # no continuation: each point on its own
    expected = list(itertools.product((300, 900, 1500), (0.1, 0.2)))
    assert [tuple(v for _, v in p.values) for p in points] == expected
    assert [p.index for p in points] == list(range(6)) and {p.direction for p in points} == {"none"}
    assert spec.n_points == 6


def test_continuation_branches_run_along_the_first_key_both_ways():
    spec = spec_from_options(["input.speed_rpm=300:1500:3", "stage.0.backlash_mm=0.1,0.2"], [], None, "lhs", None,
                             "both")
    branches = spec.branches()
    assert len(branches) == 4 and spec.n_points == 12  # (up, down) x two backlash values
    speeds = [[p.values[0][1] for p in b] for b in branches]
    assert speeds == [[300, 900, 1500]] * 2 + [[1500, 900, 300]] * 2
    assert [b[0].direction for b in branches] == ["up", "up", "down", "down"]
    assert sorted(p.index for b in branches for p in b) == list(range(12))


def test_column_names():
    assert columns(["input.speed_rpm"], 1) == [
        "input.speed_rpm", "direction", "status", "message",
        "stage1_tangential_N_mean", "stage1_tangential_N_std", "stage1_tangential_N_min", "stage1_tangential_N_max",
        "stage1_dte_um_mean", "stage1_dte_um_rms", "stage1_dte_um_min", "stage1_dte_um_max",
        "stage1_contact_loss_fraction", "stage1_dynamic_factor", "stage1_runup_factor", "output_speed_rpm", "nfev",
        "wall_s"]
    cols = columns(["a.b", "c.d"], 3)
    assert cols[:2] == ["a.b", "c.d"] and len(cols) == 2 + 3 + 3 * 11 + 3
    assert cols.index("stage3_dynamic_factor") == len(cols) - 5


def _random_spec(seed, sampling="lhs", n=20):
    return spec_from_options([], ["stage.0.backlash_mm=normal(0.25,0.02)", "input.speed_rpm=uniform(500,700)"], n,
                             sampling, seed, None)


def _values(spec):
    return np.array([[v for _, v in b[0].values] for b in spec.branches()])


@pytest.mark.parametrize("sampling", ["lhs", "mc"])
def test_random_samples_reproduce_with_the_same_seed(sampling):
    a, b, c = _values(_random_spec(7, sampling)), _values(_random_spec(7, sampling)), _values(_random_spec(8, sampling))
    assert_allclose(a, b, rtol=0, atol=0, err_msg="same seed, same samples, bit for bit")
    assert not np.allclose(a, c)


def test_latin_hypercube_puts_one_sample_in_each_stratum():
    n = 20
    x = _values(_random_spec(3, "lhs", n))
    u = np.column_stack([norm.cdf(x[:, 0], loc=0.25, scale=0.02), (x[:, 1] - 500.0) / 200.0])  # back to [0, 1)
    for j in range(2):
        assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))  # the LHS property, per dimension
    assert x[:, 1].min() >= 500 and x[:, 1].max() < 700


def test_latin_hypercube_is_scipys_drawn_with_rng_seed():
    """docs/sweeps.md: a program draws a sweep's samples again with ``qmc.LatinHypercube(d=K, rng=S).random(N)``,
    column j the j-th --random key, through its inverse CDF (scipy 1.17's older ``seed=S`` draws other numbers)."""
    qmc = pytest.importorskip("scipy.stats.qmc")
    try:
        u = qmc.LatinHypercube(d=2, rng=29).random(20)
    except TypeError:  # scipy before 1.15 has no rng keyword
        pytest.skip("scipy without LatinHypercube(rng=...)")
    expected = np.column_stack([norm.ppf(u[:, 0], loc=0.25, scale=0.02), 500.0 + 200.0 * u[:, 1]])
    assert_allclose(_values(_random_spec(29, "lhs", 20)), expected, rtol=1e-15, atol=0)


def test_monte_carlo_is_numpys_generator():
    u = unit_samples(5, 2, "mc", 11)
    assert_allclose(u, np.random.default_rng(11).random((5, 2)), rtol=0, atol=0)


def test_spec_rules():
    with pytest.raises(SweepUsageError):
        spec_from_options([], [], None, "lhs", None, None)  # nothing to sweep
    with pytest.raises(SweepUsageError):
        spec_from_options([], ["a.b=uniform(0,1)"], None, "lhs", 1, None)  # --random without --samples
    with pytest.raises(SweepUsageError):
        spec_from_options(["a.b=1,2", "a.b=3"], [], None, "lhs", None, None)  # the same key twice
    with pytest.raises(SweepUsageError):
        spec_from_options([], ["a.b=uniform(0,1)"], 3, "lhs", 1, "up")  # continuation needs a --vary key


@pytest.mark.parametrize(("vary", "random"), [
    (["input.speed_rpm=300,600", "input.speed_deg_s=2400,3600"], []),
    (["load.torque_Nm=300,600"], ["load.torque_Nmm=normal(3e5,1e4)"]),
    (["target.output_speed_rpm=20,30", "target.output_speed_deg_s=120,180"], []),
    (["load.torque_speed=[[0, 1], [9, 2]]", "load.power_kW=5,6"], []),
    (["stage.0.pinion.teeth=20,21", "stage.0.pinion={teeth = 22, face_width_mm = 190}"], []),
])
def test_two_keys_that_give_one_quantity_are_refused(vary, random):
    """Each point applies its overrides in turn and the second of `input.speed_rpm` / `input.speed_deg_s` replaces
    the first (--set's rule), so the rows labelled 300 and 600 rpm both ran at 2400 or 3600 °/s (seen: identical
    rows under different `input.speed_rpm` values). Exit 2, naming both keys."""
    with pytest.raises(SweepUsageError) as exc:
        spec_from_options(vary, random, 2 if random else None, "lhs", 1 if random else None, None)
    assert exc.value.exit_code == 2
    assert "give one quantity" in str(exc.value) or "lies inside" in str(exc.value)
    a, b = (v.split("=")[0] for v in (*vary, *random))
    assert a in str(exc.value) and b in str(exc.value)


def test_keys_of_different_tables_or_groups_are_a_grid():
    spec = spec_from_options(["input.speed_rpm=300,600", "load.torque_Nm=1,2", "stage.0.pinion.teeth=20,21",
                              "stage.1.pinion.teeth=17,18", "stage.10.pinion.teeth=5,6"], [], None, "lhs", None, None)
    assert spec.n_points == 32  # stage.1 is no prefix of stage.10
