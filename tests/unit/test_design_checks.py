"""Design errors (DesignError with a 0-based key path) and warnings (named stage, numbers)."""

from __future__ import annotations

import copy
import dataclasses
import math
import tomllib
from pathlib import Path

import pytest

from gearcli.config.schema import DesignFile
from gearcli.design import checks, compute_design
from gearcli.errors import DesignError

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
with SEED.open("rb") as _fh:
    SEED_DOC = tomllib.load(_fh)
# the checks here are the geometry's and the train's: the mesh law is the calibrated default, whose stiffness is
# ISO's (the seed's point-contact law would add a stiffness_not_iso warning per stage, tests/reference)
SEED_DOC.pop("contact")


def design(edit=None):
    doc = copy.deepcopy(SEED_DOC)
    if edit:
        edit(doc)
    return compute_design(DesignFile.model_validate(doc))


def stage_warnings(result, index):
    return [w for w in result.warnings if w.startswith(f"stage {index}:")]


# ------------------------------------------------------------------------------------------ errors
def test_unknown_material_names_the_key_and_the_known_ones():
    def edit(d):
        d["stage"][1]["gear"]["material"] = "bronze"
    with pytest.raises(DesignError) as err:
        design(edit)
    assert err.value.key == "stage[1].gear.material"
    assert "bronze" in err.value.message and "steel" in err.value.message


def test_default_material_must_exist_too():
    def edit(d):
        d["materials"] = {"c45": d["materials"]["steel"]}
        for st in d["stage"]:
            st["pinion"]["material"] = "c45"
            del st["gear"]["material"]  # defaults to "steel", which this file no longer defines
    with pytest.raises(DesignError) as err:
        design(edit)
    assert err.value.key == "stage[0].gear.material"


def test_same_hand_external_helical_pair_is_an_error_on_the_gear():
    def edit(d):
        d["stage"][0]["gear"]["hand"] = "left"
    with pytest.raises(DesignError) as err:
        design(edit)
    assert err.value.key == "stage[0].gear.hand"
    assert '"right"' in err.value.message  # says which hand is needed


@pytest.mark.parametrize("hand", [None, "spur"])
def test_helical_gear_without_a_hand_says_which_hand_it_needs(hand):
    def edit(d):
        if hand is None:
            del d["stage"][2]["pinion"]["hand"]
        else:
            d["stage"][2]["pinion"]["hand"] = hand
    with pytest.raises(DesignError) as err:
        design(edit)
    assert err.value.key == "stage[2].pinion.hand"
    # the gear is "right", so the pinion needs "left"; β = 9° is quoted
    assert '"left"' in err.value.message and "9°" in err.value.message


def test_helical_pair_with_no_hands_at_all_asks_for_left_or_right():
    def edit(d):
        del d["stage"][0]["pinion"]["hand"], d["stage"][0]["gear"]["hand"]
    with pytest.raises(DesignError, match='"left" or "right"') as err:
        design(edit)
    assert err.value.key == "stage[0].pinion.hand"


def test_pair_that_cannot_mesh_is_a_design_error_with_a_key():
    def edit(d):
        d["stage"][1]["pinion"].update(teeth=6, profile_shift=-1.5)
        d["stage"][1]["gear"].update(teeth=6, profile_shift=-1.5)
    with pytest.raises(DesignError) as err:
        design(edit)
    assert err.value.key == "stage[1].pinion.profile_shift"


# ---------------------------------------------------------------------------------- spur and hands
def test_spur_pair_needs_no_hand_and_reports_spur():
    def edit(d):
        d["stage"][0]["helix_angle_deg"] = 0
        del d["stage"][0]["pinion"]["hand"], d["stage"][0]["gear"]["hand"]
    r = design(edit)
    assert (r.stages[0].pinion.hand, r.stages[0].gear.hand) == ("spur", "spur")
    assert stage_warnings(r, 1) == []


def test_hands_on_a_spur_pair_are_accepted_with_a_warning():
    def edit(d):
        d["stage"][0]["helix_angle_deg"] = 0  # hands left/right stay in the file
    r = design(edit)
    assert r.stages[0].pinion.hand == "spur"
    (w,) = stage_warnings(r, 1)
    assert "helix_angle_deg = 0" in w and '"left"' in w


# ---------------------------------------------------------------------------------------- warnings
def test_target_speed_within_tolerance_is_quiet_and_a_miss_below_is_signed():
    def near(d):
        d["target"] = {"output_speed_rpm": 27.5, "tolerance_percent": 5}  # 26.943 is −2.0 %
    assert design(near).warnings == ()

    def above(d):
        d["target"] = {"output_speed_deg_s": 180.0, "tolerance_percent": 5}  # 30 rpm: (26.943 − 30)/30 = −10.2 %
    (w,) = design(above).warnings
    assert "-10.2 %" in w and "the target 180 °/s" in w  # in the target's own unit (DESIGN §12), 30 rpm


def test_no_target_no_target_warning():
    def edit(d):
        del d["target"]
    assert design(edit).warnings == ()


def test_undercut_warning_names_stage_part_and_the_limit():
    def edit(d):  # 12 teeth, β = 12°: z_min = 2 cos 12° / sin² 20.4103° = 1.956295 / 0.121623 = 16.08
        d["stage"][0]["pinion"]["teeth"] = 12
    ws = stage_warnings(design(edit), 1)
    assert any("pinion z = 12 < z_min = 16.1" in w and "undercut" in w for w in ws), ws


def test_profile_shift_removes_the_undercut_warning():
    def edit(d):  # x ≥ 1 − 12 · 0.121623 / (2 · 0.978148) = 1 − 0.7461 = 0.254
        d["stage"][0]["pinion"].update(teeth=12, profile_shift=0.3)
    assert not any("undercut" in w for w in design(edit).warnings)


def _stage(**changes):
    """A seed stage-1 result with some fields replaced, to test one rule at its threshold."""
    return dataclasses.replace(design().stages[0], **changes)


@pytest.mark.parametrize("eps, expect", [(1.25, None), (1.2, None), (1.15, "< 1.2"), (1.0, "< 1.2"),
                                         (0.95, "interrupted")])
def test_contact_ratio_thresholds(eps, expect):
    w = checks.contact_ratio_warning(_stage(contact_ratio_transverse=eps, contact_ratio_total=eps + 0.99))
    if expect is None:
        assert w is None
    else:
        assert expect in w and w.startswith("stage 1:") and f"{eps:.3f}" in w


def test_interrupted_contact_says_whether_the_overlap_saves_the_motion():
    saved = checks.contact_ratio_warning(_stage(contact_ratio_transverse=0.9, contact_ratio_total=1.9))
    lost = checks.contact_ratio_warning(_stage(contact_ratio_transverse=0.9, contact_ratio_total=0.9))
    assert "only the overlap" in saved and "not continuous" in lost


def test_low_contact_ratio_end_to_end():
    # spur, z = 8/8, x = +0.25/+0.25: ε_α ≈ 1.12 with the tips shortened by the tip alteration k = −0.073
    # (full tips would give 1.19; at x = 0.5 the shortened tips drop it below 1)
    def edit(d):
        st = d["stage"][1]
        st.update(helix_angle_deg=0)
        st["pinion"].update(teeth=8, profile_shift=0.25)
        st["gear"].update(teeth=8, profile_shift=0.25)
    ws = stage_warnings(design(edit), 2)
    assert any("ε_α = 1.12" in w and "< 1.2" in w for w in ws), ws


def test_face_width_ratio_limits():
    # seed stage 1: b/d1 = 180 / 257.63 = 0.699: quiet
    assert checks.face_width_warning(_stage()) is None
    wide = checks.face_width_warning(_stage(face_width_mm=400.0))  # 400 / 257.63 = 1.55 > 1.5
    narrow = checks.face_width_warning(_stage(face_width_mm=50.0))  # 50 / 257.63 = 0.19 < 0.2
    assert "b/d1" in wide and "1.55 > 1.5" in wide
    assert "0.194 < 0.2" in narrow


def test_face_width_ratio_of_a_speed_increaser_takes_the_smaller_wheel():
    """ISO 6336's pinion (d1 of b/d1) is the wheel with fewer teeth: a speed increaser's driving 97-tooth wheel
    (d = 8 · 97 / cos 10° = 788 mm) drives a 23-tooth one (186.8 mm), b = 155 mm: b/d1 = 155 / 186.8 = 0.83, a
    usual face; the driver's diameter gave 0.197 and a false "very narrow face" warning."""
    def edit(d):
        st = d["stage"][0]
        st.update(normal_module_mm=8, helix_angle_deg=10)
        st["pinion"].update(teeth=97, face_width_mm=160, profile_shift=0.0)
        st["gear"].update(teeth=23, face_width_mm=155, profile_shift=0.3)
    result = design(edit)
    d_small = 8 * 23 / math.cos(math.radians(10))
    assert checks.smaller_pitch_diameter_mm(result.stages[0]) == pytest.approx(d_small, rel=1e-12)
    assert not [w for w in stage_warnings(result, 1) if "b/d1" in w]
    # the same pair narrowed to 30 mm is narrow on the smaller wheel's diameter: 30 / 186.8 = 0.161 < 0.2
    def narrow(d):
        edit(d)
        d["stage"][0]["pinion"]["face_width_mm"] = 30
        d["stage"][0]["gear"]["face_width_mm"] = 30
    ws = [w for w in stage_warnings(design(narrow), 1) if "b/d1" in w]
    assert len(ws) == 1 and f"= {30 / d_small:.3g} < 0.2" in ws[0] and "smaller wheel" in ws[0], ws


def test_pointed_tooth_warning():
    def edit(d):  # z = 10 spur with x = +1.0: the flanks meet below d_a = d + 4 m_n
        st = d["stage"][0]
        st.update(helix_angle_deg=0)
        st["pinion"].update(teeth=10, profile_shift=1.0)
    ws = stage_warnings(design(edit), 1)
    assert any("pinion pointed tooth" in w for w in ws), ws


def test_warnings_are_plain_strings_in_stage_order():
    def edit(d):
        d["stage"][2]["pinion"]["teeth"] = 12
        d["stage"][0]["pinion"]["teeth"] = 12
    ws = design(edit).warnings
    assert all(isinstance(w, str) for w in ws)
    stages = [w.split(":")[0] for w in ws if w.startswith("stage")]
    assert stages == sorted(stages)


def test_non_finite_stage_values_are_a_design_error_not_an_output():
    # backstop behind the schema's plausibility bounds: any inf/nan in a stage result is refused
    from dataclasses import dataclass

    import pytest

    from gearcli.design.compute import _require_finite
    from gearcli.errors import DesignError

    @dataclass(frozen=True)
    class Inner:
        inertia_kg_m2: float

    @dataclass(frozen=True)
    class Outer:
        ratio: float
        gear: Inner

    _require_finite(Outer(2.0, Inner(1.0)), "stage[0]")  # finite: no error
    with pytest.raises(DesignError) as err:
        _require_finite(Outer(2.0, Inner(float("inf"))), "stage[1]")
    assert err.value.key == "stage[1]" and "inertia_kg_m2" in err.value.message


# ------------------------------------------------------------------------------ the motor's rotor
MOTOR = {"rated_power_kW": 15, "rated_speed_rpm": 1460, "synchronous_speed_rpm": 1500, "breakdown_torque_ratio": 2.8,
         "locked_rotor_torque_ratio": 2.2}


def _motor_drive(inertia: float | None):
    def edit(d):
        d["input"] = {"speed_rpm": 1480, "drive": "motor", "motor": dict(MOTOR)}
        if inertia is not None:
            d["input"].update(inertia_kg_m2=inertia, coupling_stiffness_Nm_rad=2.0e4)
    return edit


def test_motor_drive_without_rotor_inertia_is_warned_naming_the_keys():
    result = design(_motor_drive(None))
    found = [w for w in result.diagnostics if w.data.get("check") == "motor_rotor_inertia"]
    assert len(found) == 1
    assert "input.inertia_kg_m2" in found[0].message and "massless" in found[0].message


@pytest.mark.parametrize("edit", [_motor_drive(0.12), None], ids=["rotor given", "speed drive"])
def test_rotor_inertia_warning_only_where_the_rotor_is_missing(edit):
    assert not [w for w in design(edit).diagnostics if w.data.get("check") == "motor_rotor_inertia"]
