"""Fixtures shared by the unit tests."""

from __future__ import annotations

import pytest

from gearcli.model import outputs


@pytest.fixture(params=["scalar laws", "compiled"])
def laws(request, monkeypatch):
    """The output sampling with the elements' scalar laws, and with the compiled engine's where it is installed."""
    from gearcli import engine

    if request.param == "compiled":
        if not engine.available():
            pytest.skip("the compiled engine is not installed")
        engine.load(quiet=True)
        assert outputs._loaded_kernel() is not None
    else:
        monkeypatch.setattr(outputs, "_compiled", [])
    return request.param
