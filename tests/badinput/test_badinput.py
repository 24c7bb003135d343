"""Every broken design file of the corpus (cases.py) fails with a ConfigError (or, for design
errors, a DesignError) that names the file and the key path, on one line per error."""

from __future__ import annotations

import io
import re

import pytest
from cases import CONFIG_CASES, DESIGN_CASES, GENERATED, HERE, materialize

from gearcli.config import ConfigErrors, load_design
from gearcli.errors import ConfigError, DesignError


def _names(fragment: str) -> re.Pattern:
    """``fragment`` not followed by more of a word (``line 2`` must not match ``line 20``)."""
    return re.compile(re.escape(fragment) + r"(?![\w])")


@pytest.mark.parametrize(("name", "fragment"), CONFIG_CASES, ids=[c[0] for c in CONFIG_CASES])
def test_bad_file_raises_config_error_naming_file_and_key(name, fragment, tmp_path):
    path = materialize(name, tmp_path)
    with pytest.raises(ConfigError) as info:
        load_design(path)
    text = str(info.value)
    assert _names(fragment).search(text), text
    lines = text.splitlines()
    assert lines and all(line.startswith(f"{path}: ") for line in lines), text
    assert "Traceback" not in text and "pydantic" not in text.lower(), text
    if isinstance(info.value, ConfigErrors):
        assert len(lines) == len(info.value.errors) > 1
    else:
        assert len(lines) == 1, text
    if " " not in fragment:  # a key path: it is the error's key, not just somewhere in the text
        keys = [e.key for e in getattr(info.value, "errors", (info.value,))]
        assert fragment in keys, (keys, text)


def test_corpus_is_complete_and_well_formed():
    committed = {p.name for p in HERE.glob("*.toml")}
    listed = {name for name, _ in CONFIG_CASES + DESIGN_CASES}
    assert committed <= listed
    assert len(CONFIG_CASES) >= 40 and len(DESIGN_CASES) >= 2
    assert not committed & set(GENERATED)
    for name in committed:  # small and derived from the seed, not random junk
        assert (HERE / name).stat().st_size < 2000, name


def test_same_error_from_stdin_names_stdin():
    data = (HERE / "teeth_not_integer.toml").read_bytes()
    with pytest.raises(ConfigError) as info:
        load_design("-", stdin=io.BytesIO(data))
    assert str(info.value) == "<stdin>: stage[0].pinion.teeth: must be a whole number, got 21.5"


def _compute_design():
    from gearcli.design import compute_design  # an import error is a failure, never a skip

    return compute_design


@pytest.mark.parametrize(("name", "fragment"), DESIGN_CASES, ids=[c[0] for c in DESIGN_CASES])
def test_design_error_files_load_then_fail_the_design_check(name, fragment, tmp_path):
    loaded = load_design(materialize(name, tmp_path))  # valid as a file: the design is wrong
    compute_design = _compute_design()
    with pytest.raises(DesignError) as info:
        compute_design(loaded.design)
    text = f"{info.value.key or ''}: {info.value}"
    assert fragment in text, text
    assert len(str(info.value).splitlines()) == 1
