"""The model as the kernel reads it: :func:`pack` turns :class:`~gearcli.model.ModelArrays` into a :class:`Model`
(plain Python and numpy; no numba).

The model: (kind, bodies, levers, param, inertia, ipar, fpar, ripple row, fluctuation row, tree, ptr, pairs,
motor row, load law, angle rows, loss geometry): bodies and signed levers by connector and slot (-1 / 0 padded;
gearcli.model.ModelArrays), the rows the flat (amplitude, order) / (amplitude, frequency) pairs of
gearcli.model.elements.torque, tree the connector that gives each body's angle, per body b its (connector, slot,
sided) triples ``pairs[ptr[b]:ptr[b + 1]]`` in connector order (:func:`_acting_on`), then the motor's row and the load's
speed law (gearcli.model.elements.machine; empty when there is none), and the angle rows of the bodies the tree
does not reach (gearcli.model.Layout.angle_rows; (0, 0) for none), and each lossy element's pitch-line speeds and
side-force shares from its loss hook (zero for a lossless one). ``ipar`` and ``fpar`` hold the drive's and the
load's numbers and the state layout's offsets (``IP_*``, ``FP_*``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from gearcli.model import elements

# ipar / fpar layout; the state offsets are StateLayout's (gearcli.model.layout): the first speed (the speeds are
# its one contiguous slice ``speeds``), the input angle (-1 none), the first quadrature, the scene's state count,
# and each quadrature's own state (StateLayout.quadrature, in layout.QUADRATURES' order; -1 none)
IP_DRIVE, IP_W0, IP_THETA, IP_QUAD, IP_LAST_ANGLE, IP_NTV, IP_N_STATES = 0, 1, 2, 3, 4, 5, 6
IP_Q_INPUT, IP_Q_LOAD, IP_Q_DAMPING, IP_Q_TV = 7, 8, 9, 10
FP_DRIVE, FP_DRIVE_RAMP, FP_LOAD, FP_LOAD_RAMP, FP_ANGLE, FP_CLOCK = 0, 1, 2, 3, 4, 5


class Model(NamedTuple):
    """The scene as the kernel reads it (a numba argument: a named tuple of arrays, one compilation for every
    scene)."""

    kind: np.ndarray  # per connector: its element kind (gearcli.model.elements registry), int64
    bodies: np.ndarray  # per connector and slot: the body (-1 padded), int64
    levers: np.ndarray  # per connector and slot: the signed lever (0 padded)
    param: np.ndarray  # per connector: its element's parameter row
    inertia: np.ndarray  # per body
    ipar: np.ndarray  # IP_*: the drive's kind and the state layout's offsets, int64
    fpar: np.ndarray  # FP_*: the drive's and the load's numbers
    ripple: np.ndarray  # the drive torque's (amplitude, order) pairs, flat (gearcli.model.elements.torque)
    fluct: np.ndarray  # the load's (amplitude, frequency) pairs, flat
    tree: np.ndarray  # per body: the connector that gives its angle (-1 none, -2 its angle row), int64
    ptr: np.ndarray  # per body b: its (connector, slot) pairs are pairs[ptr[b]:ptr[b + 1]], int64
    pairs: np.ndarray  # (connector, slot, sided: a lossy element's side force) in connector order, int64
    motor: np.ndarray  # the motor's row (gearcli.model.elements.machine; empty: none)
    load_law: np.ndarray  # the load's speed law (empty: none)
    angle_rows: np.ndarray  # the angle rows of the bodies the tree does not reach ((0, 0): none)
    # a lossy element's loss geometry from its loss hook (gearcli.model.parts.Connector.loss_speeds, loss_share), two
    # flat rows per connector (few arrays: the model is every kernel call's argument):
    loss_body: np.ndarray  # [side * MAX_BODIES + term]: the body whose speed makes side a's / b's v (-1 padded), int64
    loss_coef: np.ndarray  # [side * MAX_BODIES + term]: its coefficient, v = sum k w_body (0 padded); then
    # [2 MAX_BODIES + 2 slot + side]: the slot's share of f_a (side 0) and of f_b (side 1) ((0, 0): the law's f)


def pack(arrays) -> Model:
    """The kernel's model from :class:`~gearcli.model.ModelArrays`."""
    kind = np.ascontiguousarray(arrays.conn_kind, dtype=np.int64)
    bodies = np.ascontiguousarray(arrays.conn_bodies, dtype=np.int64)
    param = np.ascontiguousarray(arrays.conn_param, dtype=np.float64)
    laws = [elements.law_of(k) for k in kind]
    tv = [c for c in range(kind.size) if laws[c].time_varying(param[c])]
    phased = [c for c in range(kind.size) if laws[c].phased(param[c])]
    last_angle = max((int(bodies[c, 0]) for c in phased), default=0)
    ipar = np.array([arrays.drive_kind, arrays.i_omega0, arrays.i_theta, arrays.i_quad, last_angle, len(tv),
                     arrays.n_states, *arrays.i_quadratures], dtype=np.int64)
    fpar = np.array([arrays.drive_value, arrays.drive_ramp_s, arrays.load_value_Nm, arrays.load_ramp_s,
                     arrays.drive_angle_rad, arrays.load_clock_s], dtype=np.float64)
    ripple = np.ascontiguousarray(np.asarray(arrays.drive_ripple, dtype=np.float64).reshape(-1))
    fluct = np.ascontiguousarray(np.asarray(arrays.load_fluct, dtype=np.float64).reshape(-1))
    ptr, pairs = _acting_on(bodies, len(arrays.body_inertia), np.asarray(arrays.conn_loss_shares))
    return Model(kind, bodies, np.ascontiguousarray(arrays.conn_levers, dtype=np.float64), param,
            np.ascontiguousarray(arrays.body_inertia, dtype=np.float64), ipar, fpar, ripple, fluct,
            np.ascontiguousarray(arrays.body_tree, dtype=np.int64), ptr, pairs,
            np.ascontiguousarray(np.asarray(arrays.motor_row, dtype=np.float64).reshape(-1)),
            np.ascontiguousarray(np.asarray(arrays.load_law, dtype=np.float64).reshape(-1)),
            np.ascontiguousarray(np.atleast_2d(np.asarray(arrays.body_angle_row, dtype=np.float64))),
            *_loss_rows(arrays))


def _loss_rows(arrays) -> tuple[np.ndarray, np.ndarray]:
    """(loss_body, loss_coef) of :class:`Model` from ModelArrays' loss geometry."""
    nc = arrays.conn_loss_bodies.shape[0]
    body = np.ascontiguousarray(np.asarray(arrays.conn_loss_bodies, dtype=np.int64).reshape(nc, -1))
    coef = np.concatenate([np.asarray(arrays.conn_loss_speeds, dtype=np.float64).reshape(nc, -1),
                           np.asarray(arrays.conn_loss_shares, dtype=np.float64).reshape(nc, -1)], axis=1)
    return body, np.ascontiguousarray(coef)


def _acting_on(bodies: np.ndarray, n_bodies: int, shares: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Per body, the (connector, slot, sided) triples that act on it in connector order, as ``pairs[ptr[b]:ptr[b +
    1]]`` (the kernel's scatter of forces to bodies); ``sided`` 1 where a lossy element puts a side force on the
    slot (``shares[c, s]``, its shares of f_a and f_b, not both 0), else 0."""
    lists: list[list[tuple[int, int, int]]] = [[] for _ in range(n_bodies)]
    for c in range(bodies.shape[0]):
        for s in range(bodies.shape[1]):
            if bodies[c, s] >= 0:
                sided = shares is not None and bool(np.any(shares[c, s] != 0.0))
                lists[int(bodies[c, s])].append((c, s, int(sided)))
    ptr = np.zeros(n_bodies + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(x) for x in lists])
    pairs = np.array([p for x in lists for p in x], dtype=np.int64).reshape(-1, 3)
    return ptr, pairs
