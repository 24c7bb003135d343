"""The window-ringing advice names the element that dominates the mode with the verb its number takes: a planetary
stage's identical planets hold equal shares and are named together ("stage 1 planets 1, 2, 3 sun meshes"), which
read "..., which dominates the mode" (tr27d's report)."""

from __future__ import annotations

from gearcli.simulate.ringing import Ringing, message

RING = Ringing(stage=1, frequency_Hz=512.0, decay_time_s=0.2, damping_ratio=0.0015, amplitude_start_N=400.0,
               amplitude_end_N=120.0, reference_N=2000.0, settle_time_s=1.1)


def test_several_meshes_dominate_and_one_element_dominates():
    several = message(RING, (0.3, 0.5), "stage 1 planets 1, 2, 3 sun meshes")
    assert "on the stage 1 planets 1, 2, 3 sun meshes, which dominate the mode" in several
    one = message(RING, (0.3, 0.5), "stage 2 mesh")
    assert "on the stage 2 mesh, which dominates the mode" in one
    assert "which dominat" not in message(RING, (0.3, 0.5), "")
