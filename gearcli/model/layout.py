"""Where each unknown lives in the state vector.

Coordinates: mesh deflections and shaft speeds, not absolute shaft angles. The penetration of a mesh
(~1e-5 m) is ``delta = r_bp theta_p - r_bg theta_g``; formed from two absolute angles of ~10-100 rad it
would be the difference of two ~1-10 m products and lose 5-6 of its 16 digits, so at rtol 1e-6 the
force would be noise. Integrating ``delta_k`` directly (``delta_k' = r_bp,k w_k - r_bg,k w_{k+1}``)
keeps its full relative precision.

    y = [delta_1 .. delta_m | w of the free shafts | theta_1 (torque drive, time-varying only)
         | W_in, W_load, E_damp (, W_el)]

With ``drive = "speed"`` shaft 1 has no state (its motion is the analytic STEP profile); with
``drive = "torque"`` it is free. Absolute angles, needed only for the mesh phase of time-varying
stiffness, come from theta_1 (analytic or the extra state) and ``theta_{k+1} = (r_bp,k theta_k - delta_k) / r_bg,k``.
The trailing quadrature states integrate the energy balance (see :mod:`gearcli.model.equations`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

from gearcli.model.spec import DriveSpec, LoadSpec, MeshSpec, ModelSpec

QUADRATURES = ("input_work_J", "load_work_J", "damping_loss_J", "elastic_work_tv_J")


@dataclass(frozen=True)
class Layout:
    meshes: tuple[MeshSpec, ...]
    inertias: tuple[float, ...]
    drive: DriveSpec
    load: LoadSpec
    n_meshes: int = field(init=False)
    n_shafts: int = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "n_meshes", len(self.meshes))
        object.__setattr__(self, "n_shafts", len(self.meshes) + 1)

    @classmethod
    def of(cls, spec: ModelSpec) -> "Layout":
        return cls(spec.meshes, spec.inertias_kg_m2, spec.drive, spec.load)

    # ----------------------------------------------------------------------------------- flags
    @property
    def speed_drive(self) -> bool:
        return self.drive.kind == "speed"

    @property
    def n_tv(self) -> int:
        return sum(m.time_varying for m in self.meshes)

    @property
    def needs_angles(self) -> bool:
        return self.n_tv > 0

    @property
    def last_tv_mesh(self) -> int:
        return max((k for k, m in enumerate(self.meshes) if m.time_varying), default=-1)

    @property
    def has_theta_state(self) -> bool:
        return self.needs_angles and not self.speed_drive

    # --------------------------------------------------------------------------------- indices
    @property
    def free_shafts(self) -> range:
        return range(1 if self.speed_drive else 0, self.n_shafts)

    def i_delta(self, k: int) -> int:
        return k

    def i_omega(self, shaft: int) -> Optional[int]:
        """State index of a shaft's speed; None for the speed-driven input shaft."""
        first = self.free_shafts.start
        return None if shaft < first else self.n_meshes + shaft - first

    @property
    def i_theta(self) -> Optional[int]:
        return self.n_meshes + len(self.free_shafts) if self.has_theta_state else None

    @property
    def i_quad(self) -> int:
        return self.n_meshes + len(self.free_shafts) + int(self.has_theta_state)

    @property
    def n_quad(self) -> int:
        return 3 + int(self.n_tv > 0)

    @property
    def n_states(self) -> int:
        return self.i_quad + self.n_quad

    @property
    def n_dynamic(self) -> int:
        """States that carry the dynamics (step control); the quadratures follow them."""
        return self.i_quad

    @property
    def state_names(self) -> list[str]:
        names = [f"d{k}" for k in range(self.n_meshes)] + [f"w{i}" for i in self.free_shafts]
        if self.has_theta_state:
            names.append("th0")
        return names + [f"_q{j}" for j in range(self.n_quad)]

    def angle_gradient(self, k: int) -> dict[int, float]:
        """d(theta_k)/dy as {column: coefficient}: theta_{j+1} = (r_bp,j theta_j - delta_j) / r_bg,j."""
        grad: dict[int, float] = {self.i_theta: 1.0} if self.has_theta_state else {}
        for j in range(k):
            m = self.meshes[j]
            ratio = m.base_radius_pinion_m / m.base_radius_gear_m
            grad = {c: ratio * v for c, v in grad.items()}
            grad[self.i_delta(j)] = grad.get(self.i_delta(j), 0.0) - 1.0 / m.base_radius_gear_m
        return grad
