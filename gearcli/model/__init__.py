"""The torsional model (docs/physics.md, "Torsional model"): parameters, equations, Jacobian, outputs, linearisation.

Layers: :mod:`spec` (plain SI parameters, and their assembly from a design), :mod:`layout` (the state
vector), :mod:`codegen` (the scene's generated ``rhs``/``jac``), :mod:`equations` (``TorsionalModel``),
:mod:`outputs` (vectorised channels and energies), :mod:`linear` (rigid-body loads, linearisation),
:mod:`contact_lines` (time-varying mesh stiffness), :mod:`step` (STEP and the drive profile).
"""

from gearcli.model.contact_lines import contact_length_factor
from gearcli.model.equations import Energy, TorsionalModel
from gearcli.model.linear import Linearisation, linearise, rigid_line_forces_N, static_line_forces_N
from gearcli.model.spec import DriveSpec, LoadSpec, MeshSpec, ModelSpec, spec_from_design


def build_model(cfg, design) -> TorsionalModel:
    """The compiled torsional model of a validated ``DesignFile`` and its ``DesignResult``."""
    return TorsionalModel(spec_from_design(cfg, design))


__all__ = ["DriveSpec", "Energy", "Linearisation", "LoadSpec", "MeshSpec", "ModelSpec", "TorsionalModel",
           "build_model", "contact_length_factor", "linearise", "rigid_line_forces_N", "spec_from_design",
           "static_line_forces_N"]
