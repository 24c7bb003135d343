"""A standard of its own formulas and no K_v law of its own takes ISO 6336-1's K_v the way docs/plugins.md ("A rating
standard", K_v) says: from ISO's rating of the same stages, ``ISO6336.rate_design(cfg, stages)[0][k].rating.K_v``.
Checked on the rated reducer at the default ``dynamic_factor = "iso"``: the plug-in's K_v is ISO's of each mesh,
and its Lewis bending stress is the hand formula sigma_F = K_v F_t / (b m_n Y), Y = pi (0.154 - 0.912 / z)."""

from __future__ import annotations

import math
from dataclasses import replace

import plug_chain
from numpy.testing import assert_allclose
from test_entry_points import RATED, _json

from gearcli.design.iso6336 import ISO6336
from gearcli.rating import register
from gearcli.rating.registry import withdraw

NAME, TITLE = "test_lewis_iso_k_v", "toy Lewis at ISO's K_v (a test plug-in)"


class LewisAtIsoKv(plug_chain.ToyLewis):
    name, title = NAME, TITLE

    def rate_design(self, cfg, stages):
        iso = ISO6336.rate_design(cfg, stages)[0]
        return tuple(replace(st, rating=replace(plug_chain._rate(cfg, k, st, iso[k].rating.K_v, "iso"),
                                                standard=TITLE)) for k, st in enumerate(stages)), ()


def test_a_standard_without_its_own_k_v_takes_iso_s_as_the_docs_say():
    register(LewisAtIsoKv())
    try:
        plug = _json("design", RATED, "--set", f"rating.standard={NAME}")["stages"]
    finally:
        withdraw(NAME)
    iso = _json("design", RATED)["stages"]
    for p, i in zip(plug, iso, strict=True):
        assert i["rating"]["K_v_source"] == "iso" and p["rating"]["K_v_source"] == "iso"
        assert_allclose(p["rating"]["K_v"], i["rating"]["K_v"], rtol=1e-14)
        assert p["rating"]["K_v"] > 1.0  # the file's K_v is ISO's method B, not the 1 of "no K_v"
        y = math.pi * (0.154 - 0.912 / i["pinion"]["teeth"])
        sigma = i["rating"]["K_v"] * i["static_force_N"]["tangential"] / (i["face_width_mm"] * i["normal_module_mm"] * y)
        assert_allclose(p["rating"]["pinion"]["sigma_F_MPa"], sigma, rtol=1e-12)
