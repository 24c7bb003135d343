"""The state vector's layout (:class:`gearcli.model.layout.StateLayout`): the one place that knows where each
state sits. Reference: the layout written out by hand from the module text of gearcli.model.assembly,
``y = [deflections | free-body speeds | theta_0 (torque drive with angles) | W_in, W_load, E_damp (, W_el_tv)]``,
and the generated Python's own state names (the rhs returns its derivatives in that order)."""

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.model.assembly import Layout
from gearcli.model.layout import QUADRATURES, StateLayout
from gearcli.scene import spec_from_design


def test_a_speed_driven_chain_by_hand():
    # 5 connectors, 6 bodies, body 0 speed-driven (no state), no angle state, no time-varying spring
    st = StateLayout(n_conn=5, n_bodies=6, first_free=1, theta=False, n_quad=3)
    assert (st.deflections, st.speeds, st.mechanical) == (slice(0, 5), slice(5, 10), slice(0, 10))
    assert st.i_theta is None and st.i_quad == 10 and st.n_states == 13 and st.dynamic == slice(0, 10)
    assert [st.omega(b) for b in range(6)] == [None, 5, 6, 7, 8, 9]
    assert [st.quadrature(n) for n in QUADRATURES] == [10, 11, 12, None]  # no work on time-varying springs
    assert st.names == ["d0", "d1", "d2", "d3", "d4", "w1", "w2", "w3", "w4", "w5", "_q0", "_q1", "_q2"]
    assert st.kernel_offsets == (5, -1, 10)
    assert st.kernel_quadratures == (10, 11, 12, -1)  # the compiled kernel's: -1 for the absent one
    assert (st.n_augmented, st.variational) == (13 + 100, slice(13, 113))  # [y | Phi], Phi 10 x 10


def test_a_torque_driven_chain_with_an_angle_state_by_hand():
    # 3 connectors, 4 bodies all free, the input angle a state, four quadratures
    st = StateLayout(n_conn=3, n_bodies=4, first_free=0, theta=True, n_quad=4)
    assert st.speeds == slice(3, 7) and st.i_theta == 7 and st.i_quad == 8 and st.n_states == 12
    assert st.dynamic == slice(0, 8) and st.quadratures == slice(8, 12) and st.n_mechanical == 7
    assert [st.quadrature(n) for n in QUADRATURES] == [8, 9, 10, 11]
    assert st.kernel_offsets == (3, 7, 8)
    assert st.kernel_quadratures == (8, 9, 10, 11)
    with pytest.raises(ValueError):
        st.quadrature("kinetic_energy_J")


@pytest.mark.parametrize("name", ["concrete_mixer", "concrete_mixer_te", "planetary_stage", "conveyor_motor", "mixer_time_varying_backlash"])
def test_the_scene_layout_matches_the_generated_states_and_the_kernel_offsets(name):
    loaded = load_design(f"configs/{name}.toml")
    lay = Layout.of(spec_from_design(loaded.design, compute_design(loaded.design)))
    st = lay.state
    assert st.n_conn == len(lay.connectors) and st.n_bodies == len(lay.bodies)
    names = st.names
    assert len(names) == st.n_states
    assert [names[st.delta(c)] for c in range(st.n_conn)] == [f"d{c}" for c in range(st.n_conn)]
    assert [names[st.omega(b)] for b in lay.free_bodies] == [f"w{b}" for b in lay.free_bodies]
    assert (st.i_theta is not None) == ("th0" in names)
    arrays = lay.arrays(np.zeros(st.n_states))
    assert (arrays.i_omega0, arrays.i_theta, arrays.i_quad, arrays.n_states) == (*st.kernel_offsets, st.n_states)
    assert tuple(arrays.i_quadratures) == tuple(-1 if st.quadrature(n) is None else st.quadrature(n) for n in QUADRATURES)
    Y = np.arange(st.n_states, dtype=float)[:, None]  # one sample
    assert np.array_equal(lay.body_speeds(Y, np.array([-1.0]))[st.first_free:], Y[st.speeds])
