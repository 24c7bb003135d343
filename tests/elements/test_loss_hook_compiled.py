"""The loss hook on the compiled engine: the test-only lossy coupling (``lossy_coupling.py``, beside this file),
registered with ``compiled=True``, runs through the kernel's dispatch generated from the registry (``conn_lossy``,
``conn_loss_factors``) and the loss geometry packed from its hook (``loss_sides``), with nothing in gearcli edited
for it.

Reference: the same scene on the Python engine (the generated right-hand side around scipy's DOP853, whose steps
the compiled DOP853 takes bit for bit), and the run's energy balance (input = load + damping + kinetic +
potential, each its own quadrature: the side forces' work is all in them).

The run is in a child process with its own cache directory: registering a compiled element changes the kernel's
cache key for the whole process, and the build a run would start (:mod:`gearcli.engine.builder`, a separate
``python -m gearcli.engine.builder_child``) knows only the built-in registry, so the child compiles the kernel
itself, as that build process does (:func:`gearcli.engine.builder_child.child`), after registering the element.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from numpy.testing import assert_allclose

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

CHILD = r"""
import dataclasses, json, sys
import lossy_coupling
from gearcli import api, engine
from gearcli.engine import builder_child
from gearcli.model import elements

coupling = elements.register(lossy_coupling, compiled=True)
assert engine.cache_problem() is None
builder_child.child(engine.cache_dir())  # the kernel with the lossy coupling in its dispatch
loaded, design = api.load_and_design(sys.argv[1])
spec = api.model_spec(loaded.design, design)
spec = dataclasses.replace(spec, elements=(api.ElementSpec(coupling.name, (0, 1), (1.0, 1.0), (2.0e5, 5.0, 0.8),
                                                           "lossy coupling"),))
out = {}
for eng in ("compiled", "python"):
    r = api.simulate_spec(spec, duration_s=0.5, steps=500, method="DOP853", rtol=1e-8, engine=eng)
    out[eng] = {"engine": r.solver.engine, "reason": r.solver.engine_reason, "nfev": r.solver.nfev,
                "final": [float(v) for v in r.final_state], "residual": r.energy.residual_relative,
                "damping": r.energy.damping_loss_J}
print("RESULT " + json.dumps(out))
"""


def test_the_lossy_coupling_runs_compiled_as_it_runs_in_python(tmp_path):
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path),
               PYTHONPATH=os.pathsep.join([str(ROOT), str(HERE), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, "-c", CHILD, str(ROOT / "configs" / "concrete_mixer_drivetrain.toml")],
                          env=env, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr[-2000:]
    line = next(x for x in proc.stdout.splitlines() if x.startswith("RESULT "))
    runs = json.loads(line[len("RESULT "):])
    compiled, python = runs["compiled"], runs["python"]
    assert compiled["engine"] == "compiled", compiled["reason"]
    assert python["engine"] == "python"
    assert compiled["nfev"] == python["nfev"]  # the compiled DOP853 takes scipy's steps
    # the same right-hand side in the same floating-point order: agreement far inside the run's rtol (1e-8)
    assert_allclose(compiled["final"], python["final"], rtol=1e-10, atol=1e-14)
    assert abs(compiled["residual"]) < 1e-9  # the side forces' work is all in the quadratures
    assert compiled["damping"] > 0.0
