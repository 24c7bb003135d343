"""The element laws as the kernel calls them: the dispatch by kind generated from the registry
(:mod:`gearcli.engine.dispatch`; the loss hook's too), the drive's and the load's laws
(:mod:`gearcli.model.elements.torque`, :mod:`gearcli.model.elements.machine`, the STEP profiles of
:mod:`gearcli.model.elements.profile`, the energy integrands of
:mod:`gearcli.model.elements.energy`), compiled from their own modules, never rewritten here.

Importing this module builds the dispatch into the checked cache directory this process loads from.
"""

from __future__ import annotations

from gearcli.engine import dispatch as _dispatch
from gearcli.model.elements import energy as _energy_mod
from gearcli.model.elements import machine as _machine_mod
from gearcli.model.elements import profile as _profile_mod
from gearcli.model.elements import torque as _torque_mod

_D = _dispatch.build()  # into the checked cache directory this process loads from
KINDS = _D.KINDS
conn_force, conn_power_gradient, conn_potential = _D.conn_force, _D.conn_power_gradient, _D.conn_potential
conn_channel, conn_n_channels, conn_damped = _D.conn_channel, _D.conn_n_channels, _D.conn_damped
conn_tv, conn_phased, conn_excited = _D.conn_tv, _D.conn_phased, _D.conn_excited
conn_phase_per_rad, conn_forces, conn_channels = _D.conn_phase_per_rad, _D.conn_forces, _D.conn_channels
_TORQUE = _dispatch.jit_module(_torque_mod)
torque_ripple, torque_fluctuation = _TORQUE["ripple"], _TORQUE["fluctuation"]
_MACHINE = _dispatch.jit_module(_machine_mod)  # the motor's curve and start, the load's speed law
motor_torque, load_factor = _MACHINE["motor_torque"], _MACHINE["load_factor"]
_PROFILE = _dispatch.jit_module(_profile_mod)  # the drive's and the load's STEP profiles
ramp, input_motion = _PROFILE["ramp"], _PROFILE["input_motion"]
_ENERGY = _dispatch.jit_module(_energy_mod)  # the energy quadratures' integrands
speed_drive_power, torque_power = _ENERGY["speed_drive_power"], _ENERGY["torque_power"]
conn_lossy, conn_loss_factors = _D.conn_lossy, _D.conn_loss_factors  # the loss hook (an element's two side forces)
