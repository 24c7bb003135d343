"""Same numbers before and after a refactoring: every scene of configs/ and configs/extreme/ against
the summary recorded by ``make_golden.py`` (before the element-model redesign), to 1e-9 relative.

The fast scenes run in the default suite; the slow ones (``"slow": true``, > 3 s when recorded) only
with ``GEARCLI_GOLDEN_ALL=1``. Integer counters (nfev, steps) and the method must match exactly: an
adaptive integrator that took one step differently would show there first.
"""

from __future__ import annotations

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

RTOL = 1e-9  # the acceptance bound
ALL = os.environ.get("GEARCLI_GOLDEN_ALL") == "1"


def _cases():
    for path in scene_files():
        gold = HERE / f"{golden_name(path)}.json"
        if not gold.exists():
            continue
        slow = json.loads(gold.read_text()).get("slow", False)
        marks = [pytest.mark.skipif(slow and not ALL, reason="slow golden scene: set GEARCLI_GOLDEN_ALL=1")]
        yield pytest.param(path, gold, id=golden_name(path), marks=marks)


def _close(got, want, floor: float, what: str) -> None:
    """Relative 1e-9 with an absolute floor for values that are ~0 (a channel of a scale ``floor``)."""
    assert_allclose(np.asarray(got, float), np.asarray(want, float), rtol=RTOL, atol=RTOL * floor, err_msg=what)


@pytest.mark.parametrize(("path", "gold"), list(_cases()))
def test_same_numbers_as_recorded(path: Path, gold: Path) -> None:
    want = json.loads(gold.read_text())
    got = summary_numbers(path)
    assert got["method"] == want["method"]
    assert got["nfev"] == want["nfev"], "the integrator took other steps than before"
    assert got["steps"] == want["steps"]
    _close(got["ratio"], want["ratio"], abs(want["ratio"]), "ratio")
    _close(got["output_speed_deg_s"], want["output_speed_deg_s"], abs(want["input_speed_deg_s"]), "output speed")
    _close(got["input_speed_deg_s"], want["input_speed_deg_s"], abs(want["input_speed_deg_s"]), "input speed")
    # the energy residual is itself a relative number (~1e-7): compare it to 1e-9 of the balance's scale
    assert_allclose(got["energy_residual"], want["energy_residual"], rtol=1e-6, atol=1e-12, err_msg="energy residual")
    freqs = want["natural_frequencies_Hz"]
    _close(got["natural_frequencies_Hz"], freqs, max(freqs, default=1.0), "natural frequencies")
    assert len(got["stages"]) == len(want["stages"])
    for k, (g, w) in enumerate(zip(got["stages"], want["stages"], strict=True)):
        for q, values in w.items():
            scale = float(np.max(np.abs(values))) or 1.0
            _close(g[q], values, scale, f"stage {k + 1} {q}")
