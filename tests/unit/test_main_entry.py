"""The entry point's command word: the commands that read a design file import their libraries first
(gearcli/__main__.py)."""

import subprocess
import sys
from pathlib import Path

from gearcli.__main__ import (
    INTEGRATING,
    INTEGRATING_FIRST,
    MODELS_FIRST,
    NUMERIC,
    NUMERIC_FIRST,
    command_word,
    first_imports,
)
from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]


def test_command_word_skips_the_global_options():
    assert command_word(["-q", "--debug", "simulate", "seed.toml", "-o", "run.csv"]) == "simulate"
    assert command_word(["report", "-", "-o", "r.md"]) == "report"


def test_no_command_word():
    assert command_word([]) is None
    assert command_word(["--version"]) is None


def test_the_numeric_commands_are_commands():
    assert INTEGRATING <= NUMERIC <= set(cli.commands)


def test_first_imports_by_command():
    assert first_imports("simulate") == NUMERIC_FIRST + INTEGRATING_FIRST + MODELS_FIRST
    assert first_imports("design") == NUMERIC_FIRST + MODELS_FIRST
    assert first_imports("engine") == first_imports(None) == ()
    assert INTEGRATING_FIRST[-1] == "scipy.integrate"  # numpy's submodules before scipy reaches them


def test_pydantic_comes_after_numpy_and_scipy():
    """typing_extensions (pydantic imports it) replaces typing's parameter collection, which numpy's and scipy's
    generic aliases would then go through: the entry point imports pydantic's modules after them."""
    code = ("import sys, typing\nbefore = typing._collect_parameters\nimport numpy, scipy.integrate\n"
            "print('typing_extensions' in sys.modules, typing._collect_parameters is before)\nimport pydantic.main\n"
            "print(typing._collect_parameters is before)\n")
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["False", "True", "False"]  # the replacement comes with pydantic, not before
    order = first_imports("simulate")
    assert max(order.index(m) for m in NUMERIC_FIRST + INTEGRATING_FIRST) < min(order.index(m) for m in MODELS_FIRST)


def test_the_first_imports_are_modules_the_commands_load_anyway():
    """The entry point only moves imports: a command's modules, imported without it in a fresh interpreter, load
    every module it imports first (a library that stops loading one would make the entry point's import a cost)."""
    code = ("import sys\nimport gearcli.api\nprint(' '.join(sys.modules))\n"  # the design's (design, modes)
            "import gearcli.simulate.run\nprint(' '.join(sys.modules))\n")  # a run's
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    designing, running = (set(line.split()) for line in proc.stdout.splitlines())
    assert "gearcli.__main__" not in running
    assert set(NUMERIC_FIRST + MODELS_FIRST) <= designing
    assert not set(INTEGRATING_FIRST) & designing  # a design does not pay for scipy
    assert set(INTEGRATING_FIRST) <= running
