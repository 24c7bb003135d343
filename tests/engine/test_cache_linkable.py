"""A cached kernel function is loaded without parsing its linkable LLVM module (gearcli.engine.numba_cache): the
symbols its machine code defines come from the entry, and the module is parsed when a compilation first links the
function in. Checked against numba's own loader: the symbols the entry lists are the ones numba reads off the
parsed module (``JitEngine._load_defined_symbols``), and the module parsed late is a linkable one (its functions
made ``linkonce_odr`` by numba for linking)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytest.importorskip("numba")
pytestmark = [pytest.mark.slow]  # a built cache (a whole compilation where there is none yet)

PROBE = """
import json
from numba.core.codegen import JitEngine
from gearcli.engine import loader

loader.entry("DOP853")  # rk_run, loaded from the cache as a run loads it
dispatcher = loader.loaded_kernel().rk_run
(cres,) = dispatcher.overloads.values()
library = cres.library
out = {"class": type(library).__name__, "unparsed": library._linkable is not None}
cache = dispatcher._cache
tag, listed, _ = cache._cache_file.load(cache._index_key(tuple(cres.signature.args), dispatcher.targetctx.codegen()))
module = library._get_module_for_linking()  # what a compilation linking rk_run in asks for: parsed now
numba_reads = JitEngine.__new__(JitEngine)
numba_reads._defined_symbols = set()
numba_reads._load_defined_symbols(module)  # what numba's own loader lists from the parsed module
out.update(parsed=library._linkable is None, same=set(listed) == numba_reads._defined_symbols, n=len(listed),
           in_engine=set(listed) <= library.codegen._engine._defined_symbols,
           functions=sum(1 for f in module.functions if not f.is_declaration))
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def env() -> dict[str, str]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    subprocess.run([sys.executable, "-m", "gearcli", "engine", "build", "-q"], env=env, check=True,
                   stdout=subprocess.DEVNULL, timeout=900)
    return env


def test_a_loaded_entry_lists_numbas_symbols_and_parses_its_module_on_first_link(env):
    res = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr[-2000:]
    out = json.loads(res.stdout.splitlines()[-1])
    assert out["class"] == "_Library" and out["unparsed"]  # loaded without the parse
    assert out["same"] and out["n"] > 0 and out["in_engine"]  # the symbols numba's loader would have listed
    assert out["parsed"] and out["functions"] > 0  # the linkable module, parsed on the first link
