"""A test-only element joining three bodies: the damper law of ``torsional_damper`` on the deflection
``delta = r_a theta_a - r_b theta_b + r_c theta_c`` (a planet's mesh joins sun or ring, planet and carrier
the same way). Only ``NAME`` and ``SIGNS`` differ: the bodies an element joins are data."""

from __future__ import annotations

from torsional_damper import *  # noqa: F403 - the same law, element function by element function

NAME = "test_three_body_damper"
SIGNS = (1.0, -1.0, 1.0)
