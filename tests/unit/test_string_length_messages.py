"""A string key of the wrong length reads as gearcli's other messages do, naming file and key (not pydantic's "String
should have at least 1 character"): ``[rating] standard`` (1 … 64 characters) and a duty point's ``name``."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.errors import ConfigError

BAD = Path(__file__).resolve().parents[1] / "badinput" / "rating_standard_empty.toml"


def test_empty_string_is_named_plainly():
    with pytest.raises(ConfigError) as info:
        load_design(str(BAD))
    assert info.value.key == "rating.standard"
    assert "must not be empty" in str(info.value) and "String should" not in str(info.value)
    assert "rating_standard_empty.toml" in str(info.value)


def test_overlong_string_gives_the_limit_and_the_length():
    with pytest.raises(ConfigError) as info:
        load_design(str(BAD), ["rating.standard=" + '"' + "x" * 70 + '"'])
    assert info.value.key == "rating.standard"
    assert "must be at most 64 characters long, got 70" in str(info.value)
