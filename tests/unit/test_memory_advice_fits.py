"""The memory guard's advice is a ``simulation.steps`` it accepts (gearcli/config/bounds.py, check_memory).

A run holds (samples + 1) x values x bytes: a two-stage chain writes 21 values per sample (time, 3 shaft speeds, the
input torque, 5 channels per stage, 2 states per shaft), 28 bytes each in JSON. The refusal advised half the steps
that fit (it divided by the bytes of 2 samples), and on a ``steady = "periodic"`` run, which holds the run-up's steps
and 100000 statistics samples, a number of steps that could not fit at all (30 MiB: "≤ 26749", whose run needs
126749 samples, 71 MiB).
"""

from __future__ import annotations

import re

import pytest

from gearcli.config import load_design
from gearcli.config.bounds import check_memory
from gearcli.errors import ResourceError

BYTES = 21 * 28  # one sample of a two-stage chain in JSON


def scene(tmp_path, steps: int, steady: str = "window"):
    path = tmp_path / "mem.toml"
    path.write_text(
        'title = "memory"\n'
        "[[stage]]\nnormal_module_mm = 4\npinion = { teeth = 20, face_width_mm = 40 }\n"
        "gear = { teeth = 60, face_width_mm = 40 }\n"
        "[[stage]]\nnormal_module_mm = 6\npinion = { teeth = 18, face_width_mm = 60 }\n"
        "gear = { teeth = 72, face_width_mm = 60 }\n"
        "[input]\nspeed_rpm = 1500\nramp_s = 0.1\n[load]\ntorque_Nm = 800\nramp_s = 0.1\n"
        f'[simulation]\nduration_s = 1.0\nsteps = {steps}\nsteady = "{steady}"\n')
    return load_design(str(path)).design


def advice(tmp_path, steps: int, steady: str = "window") -> str:
    with pytest.raises(ResourceError) as err:
        check_memory(scene(tmp_path, steps, steady), fmt="json", series=False, source="mem.toml")
    return str(err.value)


def accepted(tmp_path, steps: int, steady: str = "window") -> bool:
    try:
        check_memory(scene(tmp_path, steps, steady), fmt="json", series=False, source="mem.toml")
    except ResourceError:
        return False
    return True


def test_a_window_run_is_advised_the_most_steps_that_fit(tmp_path, monkeypatch):
    monkeypatch.setenv("GEARCLI_MEMORY_LIMIT_MB", "10")
    most = 10 * 2**20 // BYTES - 1  # (samples + 1) x BYTES <= 10 MiB: 17831
    msg = advice(tmp_path, 20000)
    assert f"set simulation.steps ≤ {most} " in msg, msg
    assert accepted(tmp_path, most) and not accepted(tmp_path, most + 1)


def test_a_periodic_run_is_advised_steps_beside_its_statistics_samples_or_told_none_fit(tmp_path, monkeypatch):
    monkeypatch.setenv("GEARCLI_MEMORY_LIMIT_MB", "60")
    most = 60 * 2**20 // BYTES - 1  # 106996 samples, of which 100000 are the statistics periods'
    msg = advice(tmp_path, 20000, "periodic")
    assert f"set simulation.steps ≤ {most - 100000} " in msg, msg
    assert accepted(tmp_path, most - 100000, "periodic") and not accepted(tmp_path, most - 100000 + 1, "periodic")
    monkeypatch.setenv("GEARCLI_MEMORY_LIMIT_MB", "30")  # 53498 samples: under the 100001 of the least periodic run
    msg = advice(tmp_path, 2000, "periodic")
    assert "no run fits in it" in msg and "set simulation.steps" not in msg, msg
    assert not accepted(tmp_path, 1, "periodic")
    assert int(re.search(r"(\d+) samples", msg).group(1)) == 102000
