"""Same numbers before and after a refactoring: every scene of configs/ and configs/extreme/ against the
summary recorded by ``make_golden.py``. Every scene file has a golden file or a reason in ``skipped.json``.

Two tiers:

- **Statistics** (every platform): each window statistic agrees with the recorded one within what the run
  itself can resolve — four times the larger of the two runs' estimated errors (the check pass's estimate,
  recorded with the numbers) plus 20 rtol of the stage's reference force. A refactoring that changes the
  steps an adaptive integrator takes but not the physics passes; a change of the physics does not. The
  ratio and speeds agree to 10 rtol; natural frequencies (linear algebra, no integration) to 1e-9.
- **Bitwise** (``bitwise``; slow tier, which CI runs): the method and the integer counters (nfev, steps)
  exactly and every statistic to 1e-9 relative. Exact step counts hold only for the OpenBLAS kernel
  tests/conftest.py pins (x86-64 with AVX2); elsewhere the tier skips and says why.

Scenes recorded as slow (> ``SLOW_S`` s) run in the slow tier only; so do the statistics of scenes recorded above
``DEFAULT_TIER_S`` (the default tier keeps the quicker ones, one of each kind of scene: speed and motor drives,
DOP853 and Radau, parallel and planetary stages, TE, backlash, duty, excited and extreme ones).
"""

from __future__ import annotations

import functools
import json
import os
import sys
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

from make_golden import golden_name, scene_files, summary_numbers  # noqa: E402

BITWISE_RTOL = 1e-9
ESTIMATE_FACTOR = 4.0  # an error estimate is an estimate: a factor of four covers its own scatter
RTOL_FACTOR = 20.0  # the global error of an adaptive run is a small multiple of its local tolerance
STATS = ("mean", "min", "max", "std")
DEFAULT_TIER_S = 0.5  # a scene recorded above this (wall_s_when_recorded) runs its statistics in the slow tier
DEFAULT_TIER_ALSO = ("configs__concrete_mixer_te", "configs__backlash_oscillator")  # TE and backlash, kept


def _skipped() -> dict[str, str]:
    return json.loads((HERE / "skipped.json").read_text())


def _cases(bitwise: bool):
    for path in scene_files():
        gold = HERE / f"{golden_name(path)}.json"
        if not gold.exists():
            continue
        recorded = json.loads(gold.read_text())
        slow = recorded.get("slow", False) or (recorded.get("wall_s_when_recorded", 0.0) > DEFAULT_TIER_S
                                               and golden_name(path) not in DEFAULT_TIER_ALSO)
        # both tiers of a scene on one xdist worker (--dist loadgroup, pyproject): the scene runs once per session
        marks = [pytest.mark.xdist_group(golden_name(path))] + ([pytest.mark.slow] if (slow or bitwise) else [])
        if bitwise:
            marks.append(pytest.mark.bitwise)
        yield pytest.param(path, gold, id=golden_name(path), marks=marks)


@functools.cache
def _run(path: Path) -> dict:
    return summary_numbers(path)


def test_every_scene_has_a_golden_file_or_a_reason():
    skipped = _skipped()
    missing = [golden_name(p) for p in scene_files()
               if not (HERE / f"{golden_name(p)}.json").exists() and not skipped.get(golden_name(p), "").strip()]
    assert missing == [], "record them: python tests/golden/make_golden.py --only NAME (or give the reason)"
    stale = [name for name in skipped if not any(golden_name(p) == name for p in scene_files())]
    assert stale == [], "skipped.json names scenes that no longer exist"


def _reference(stage: dict) -> float:
    mean = abs(stage["tangential_N"][0])
    return mean if mean > 0 else max(abs(v) for v in stage["tangential_N"]) or 1.0


def _tolerance(got_stage: dict, want_stage: dict, rtol: float) -> np.ndarray:
    """Per statistic (mean, min, max, std) of F_t: the tolerance in N."""
    est = np.zeros(4)
    for s in (got_stage, want_stage):
        e = s.get("error_N")
        if e is not None:
            est = np.maximum(est, np.asarray(e, float))
    return ESTIMATE_FACTOR * est + RTOL_FACTOR * rtol * _reference(want_stage)


@pytest.mark.parametrize(("path", "gold"), list(_cases(bitwise=False)))
def test_statistics_agree_within_what_the_run_resolves(path: Path, gold: Path) -> None:
    want = json.loads(gold.read_text())
    got = _run(path)
    rtol = want["rtol"]
    for key in ("ratio", "output_speed_deg_s", "input_speed_deg_s"):
        assert_allclose(got[key], want[key], rtol=10 * rtol, atol=10 * rtol * abs(want["input_speed_deg_s"]),
                        err_msg=key)
    freqs = want["natural_frequencies_Hz"]
    assert_allclose(got["natural_frequencies_Hz"], freqs, rtol=1e-9, atol=1e-9 * max(freqs, default=1.0))
    assert abs(got["energy_residual"]) <= max(10 * abs(want["energy_residual"]), 10 * rtol), "energy balance"
    assert len(got["stages"]) == len(want["stages"])
    for k, (g, w) in enumerate(zip(got["stages"], want["stages"], strict=True)):
        tol_t = _tolerance(g, w, rtol)
        ft = abs(w["tangential_N"][0]) or _reference(w)
        for q in ("tangential_N", "radial_N", "axial_N", "penetration_mm"):
            # radial, axial and penetration follow F_t through constants of the stage: its relative tolerance
            scale = 1.0 if q == "tangential_N" else (abs(w[q][0]) or max(map(abs, w[q])) or 1.0) / ft
            diff = np.abs(np.asarray(g[q], float) - np.asarray(w[q], float))
            bad = [STATS[i] for i in range(4) if diff[i] > tol_t[i] * scale + 1e-12 * max(map(abs, w[q]))]
            assert bad == [], f"stage {k + 1} {q} {bad}: {g[q]} vs {w[q]} (tolerance {tol_t * scale})"


@pytest.mark.parametrize(("path", "gold"), list(_cases(bitwise=True)))
def test_same_steps_and_numbers_as_recorded(path: Path, gold: Path) -> None:
    if os.environ.get("OPENBLAS_CORETYPE") != "Haswell":
        pytest.skip("exact step counts need the OpenBLAS kernel tests/conftest.py pins (x86-64 with AVX2)")
    want = json.loads(gold.read_text())
    got = _run(path)
    assert got["method"] == want["method"]
    assert got["nfev"] == want["nfev"], "the integrator took other steps than before"
    assert got["steps"] == want["steps"]
    for key in ("ratio", "output_speed_deg_s", "input_speed_deg_s"):
        assert_allclose(got[key], want[key], rtol=BITWISE_RTOL, err_msg=key)
    assert_allclose(got["energy_residual"], want["energy_residual"], rtol=1e-6, atol=1e-12, err_msg="energy")
    for k, (g, w) in enumerate(zip(got["stages"], want["stages"], strict=True)):
        for q, values in w.items():
            if q == "error_N":
                continue  # an estimate, not a result
            scale = float(np.max(np.abs(values))) or 1.0
            assert_allclose(np.asarray(g[q], float), np.asarray(values, float), rtol=BITWISE_RTOL,
                            atol=BITWISE_RTOL * scale, err_msg=f"stage {k + 1} {q}")
