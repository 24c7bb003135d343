"""The torsional model: bodies and connectors, their elements, equations, Jacobian, outputs, linearisation.

Layers: :mod:`spec` (plain SI parameters), :mod:`elements` (one force law per element type),
:mod:`assembly` (the chain of bodies and connectors, the state vector, plain arrays — the only place that
knows indices), :mod:`codegen` (the scene's generated ``rhs``/``jac``), :mod:`equations`
(``TorsionalModel``), :mod:`outputs` (channels and energies), :mod:`linear` (rigid-body loads,
linearisation), :mod:`modes` (natural frequencies, mode shapes, strain-energy shares),
:mod:`contact_lines` (time-varying mesh stiffness), :mod:`step` (STEP and the drive profile).
The model never imports the design or the config layer: :mod:`gearcli.scene` builds its spec.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout, ModelArrays
    from gearcli.model.contact_lines import contact_length_factor
    from gearcli.model.equations import Energy, TorsionalModel
    from gearcli.model.linear import Linearisation, linearise, rigid_line_forces_N, static_line_forces_N
    from gearcli.model.spec import CoupledInertia, DriveSpec, FlexibleShaft, LoadSpec, MeshSpec, ModelSpec, SpringSpec

#: where each name lives: imported on first use (``gearcli design`` reads the spec only, not the equations)
_HOME = {"Layout": "assembly", "ModelArrays": "assembly", "contact_length_factor": "contact_lines",
         "Energy": "equations", "TorsionalModel": "equations", "Linearisation": "linear", "linearise": "linear",
         "rigid_line_forces_N": "linear", "static_line_forces_N": "linear", "CoupledInertia": "spec",
         "DriveSpec": "spec", "FlexibleShaft": "spec", "LoadSpec": "spec", "MeshSpec": "spec", "ModelSpec": "spec",
         "SpringSpec": "spec"}


def __getattr__(name: str) -> Any:
    if name in _HOME:
        value = getattr(importlib.import_module(f"gearcli.model.{_HOME[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'gearcli.model' has no attribute {name!r}")


__all__ = ["CoupledInertia", "DriveSpec", "Energy", "FlexibleShaft", "Layout", "Linearisation", "LoadSpec",
           "MeshSpec", "ModelArrays", "ModelSpec", "SpringSpec", "TorsionalModel", "contact_length_factor",
           "linearise", "rigid_line_forces_N", "static_line_forces_N"]
