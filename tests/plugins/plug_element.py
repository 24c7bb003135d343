"""A plug-in's own model element (docs/plugins.md, "A model element"): the built-in torsional spring-damper's law
under a name of its own, registered by ``plug_extras.register`` without the compiled engine (``compiled=False``):
a run of a scene holding it takes the Python engine, and says why."""

from __future__ import annotations

from gearcli.model.elements import adopt, spring

adopt(spring, globals())  # F = k d + c d', its partials, energy and tangent: the spring's laws as this module's own

NAME = "test_plugin_spring"
SIGNS = (1.0, -1.0)  # deflection = lever_a theta_a - lever_b theta_b
