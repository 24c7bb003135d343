"""``gearcli design`` must start fast: the design package never imports scipy (STYLE.md, layout)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def test_design_package_and_a_seed_design_never_import_scipy():
    code = (
        "import sys, tomllib\n"
        "import gearcli.design\n"
        "assert 'scipy' not in sys.modules, 'import gearcli.design pulled in scipy'\n"
        "from gearcli.config.schema import DesignFile\n"
        f"cfg = DesignFile.model_validate(tomllib.load(open({str(SEED)!r}, 'rb')))\n"
        "result = gearcli.design.compute_design(cfg)\n"
        "gearcli.design.contact_stiffness_N_mm_e(result.stages[0], cfg.contact_for(0))\n"
        "assert 'scipy' not in sys.modules, 'compute_design pulled in scipy'\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr


def test_public_api():
    import gearcli.design as design

    assert set(design.__all__) == {"compute_design", "contact_stiffness_N_mm_e"}
