"""A chain of lossy parallel stages as a design file, from one tuple a stage, and its pitch radii: the hand
models of tests/reference/test_rigid_start_losses.py and test_speed_law_static_reference.py read the same
tuples the file is written from."""

from __future__ import annotations

import math

# a stage: (m_n, beta, z_p, z_g, eta, J_p, J_g, b_p); the gear's face 2 mm narrower, hands opposite


def scene(stages, tail: str, mesh: str = "") -> str:
    """The design file: the stages (each with ``mesh`` as its ``[stage.mesh]`` inline table when given), then
    ``tail`` ([input], [load], [simulation])."""
    hands = ("left", "right")
    text = 'title = "lossy chain"\n'
    for k, (mn, beta, zp, zg, eta, jp, jg, b) in enumerate(stages):
        hp, hg = hands[k % 2], hands[1 - k % 2]
        text += (f"[[stage]]\nnormal_module_mm = {mn}\nhelix_angle_deg = {beta}\nefficiency = {eta}\n"
                 f'pinion = {{ teeth = {zp}, face_width_mm = {b}, hand = "{hp}", inertia_kg_m2 = {jp} }}\n'
                 f'gear = {{ teeth = {zg}, face_width_mm = {b - 2}, hand = "{hg}", inertia_kg_m2 = {jg} }}\n'
                 + (f"mesh = {mesh}\n" if mesh else ""))
    return text + tail


def pitch_radius_m(z: int, m_n: float, beta_deg: float) -> float:
    """r = z m_n / (2 cos beta), m."""
    return z * m_n / (2.0 * math.cos(math.radians(beta_deg))) / 1e3
