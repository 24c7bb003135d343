"""The leaf core: what every layer may use and which imports no other gearcli package.

:mod:`gearcli.core.methods` (the one registry of integration methods) and :mod:`gearcli.core.text` (user text
printed literally). ``gearcli.errors`` and ``gearcli.diagnostics`` belong to the same layer (ARCHITECTURE.md);
they keep their historical paths. ``gearcli.results`` (the design's results) is a layer of its own, below
``design`` and ``rating``.
"""
