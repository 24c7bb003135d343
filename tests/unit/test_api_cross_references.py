"""docs/api.md documents every function the facade's own docstrings point a reader to (``:func:`name```): a
reference to a function the page does not list (``check_budget``, named by ``simulate_file`` and ``report_file``,
was missing from ``__all__``) sends a script's author to nothing."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

from gearcli import api
from gearcli.errors import ResourceError

ROOT = Path(__file__).resolve().parents[2]


def test_every_function_the_facade_s_docstrings_name_is_documented():
    named = set()
    for name in api.__all__:
        doc = inspect.getdoc(getattr(api, name)) or ""
        named |= {m for m in re.findall(r":func:`~?([A-Za-z_][\w.]*)`", doc) if "." not in m}
    assert named, "the docstrings name functions (simulate_file names check_budget)"
    page = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    for name in sorted(named):
        assert name in api.__all__, name
        assert f"### `{name}`" in page, name


def test_check_budget_refuses_a_run_over_the_memory_limit_naming_the_file_and_key(monkeypatch):
    """2e6 samples of the seed's channels kept as JSON series are far over a 1 MiB limit."""
    monkeypatch.setenv("GEARCLI_MEMORY_LIMIT_MB", "1")
    path = str(ROOT / "configs" / "industrial_two_stage.toml")
    loaded, design = api.load_and_design(path, ["simulation.steps=2000000", "simulation.duration_s=100"])
    with pytest.raises(ResourceError, match=r"industrial_two_stage\.toml: simulation\.steps"):
        api.check_budget(loaded, design, series=True)


def test_a_documented_choice_given_wrong_is_a_clear_error_not_a_silent_default_or_a_key_error():
    """api.life's ``variant`` (iso, elementary, modified: a typo was a bare KeyError deep in the life layer) and
    api.prepare_sweep's ``fmt`` (csv, json: 'xml' wrote CSV without a word), as the CLI's choices refuse them."""
    from gearcli.sweep.spec import SweepUsageError

    path = str(ROOT / "configs" / "mixer_duty.toml")
    with pytest.raises(SweepUsageError, match=r"--format: must be one of csv, json, got 'xml'"):
        api.prepare_sweep(path, [], vary=["input.speed_rpm=600,700"], fmt="xml", jobs=1)
    session = api.prepare_life(path)
    with pytest.raises(ValueError, match=r"variant: must be one of iso, elementary, modified, got 'bogus'"):
        api.life(session, static=True, variant="bogus")
