"""The damping of the linearised chain at its operating point: what ``simulate`` integrates, as ``modes`` sees it.

Body coordinates over the free bodies (the angles ``theta``, the speeds ``w``). Every connector c is linearised
about its static force (:func:`gearcli.model.linear.tangent`: its own law, so a viscous mesh's ``c = 2 zeta
sqrt(k_lin m_e)``, an IMPACT mesh's STEP ramp at its static penetration, a coupling's damper), and the torques at
the two ends about the operating speed:

- the drive on body 0: a motor's ``dT_m/dw`` at its operating speed (the stable crossing of its curve with the
  load reflected to it, after its start: :func:`operating_speed_rad_s`) — the slip damping
  ``d_0 = -dT_m/dw``; a speed drive holds body 0 (no state), a torque drive's torque does not depend on speed;
- the load on the last body, resisting: ``T_L = T_ref g(w_N)`` (``[load] speed_exponent`` or a table), so
  ``d_N = T_ref dg/dw`` at the load body's operating speed.

A lossy mesh passes on ``eta`` of its force in the power-flow direction (:func:`.elements.mesh.loss_factors`):
the force on its pinion is ``f``, on its gear ``eta f`` (forward power; reversed, the other way round), so the
matrices scatter the connector forces with those factors (their dependence on speed, through the regularised
power-flow sign, vanishes at the operating point: ``1 - tanh^2`` of ~1000). Then

    J theta'' + C theta' + K theta = 0,   K = L^T diag(k) R,   C = L^T diag(c) R + diag(d),

``R`` the levers (``delta = R theta``), ``L`` the levers times the loss factors. Its eigenvalues
``lambda = -zeta omega +- i omega sqrt(1 - zeta^2)`` give each mode's damping ratio ``zeta = -Re lambda / |lambda|``
(:func:`modal_damping_ratios` matches them to the undamped modes by their shapes).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.memo import remember
from gearcli.design.drive_balance import TORQUE_BALANCE_TOLERANCE
from gearcli.model.assembly import Layout
from gearcli.model.elements import machine
from gearcli.model.planet_excitation import REPEATED

STEADY_T = 1e12  # s: a time past every start ramp (the motor's steady curve)
SPEED_SAMPLES = 4000  # grid over 0 .. the synchronous speed on which the motor's crossings are bracketed
GENERATING_SCAN = 2.0  # an overhauling load's crossing is sought up to slip -1 (twice the synchronous speed)
UNDAMPED_PER_PERIOD = 1e-6  # a mode decaying by less than this per period is undamped (e-fold after a million
# periods, past any run's 3600 s for a mode above 0.3 Hz): what is left of a chain without damping is the eigen
# solver's roundoff (zeta ~ 1e-17 .. 1e-30), which read as a decay time of 1e28 s and a resonance 1e16 x
MIN_MAC = 0.5  # a damped eigenvector matches an undamped mode when their modal assurance criterion exceeds this
MAX_FREQUENCY_RATIO = 2.0  # ... and its |lambda| lies within this factor of the mode's undamped frequency


def reflected_load_Nm(lay: Layout, w: float) -> float:
    """The load torque at the input body (N m) when it turns at w in steady state: the load law at the output's
    speed, through the train's efficiency (:meth:`Layout.train_efficiency`; with the power flowing back when the
    load drives)."""
    rho = lay.bodies[-1].ratio
    g = machine.load_factor(lay.load_law, w * rho)[0] if lay.load_law else 1.0
    t = lay.load.torque_Nm * g * rho
    return t / lay.train_efficiency() if t >= 0 else t * lay.train_efficiency(forward=False)


def breakaway_Nm(lay: Layout) -> float:
    """A ``torque_speed`` load table's torque at standstill (its first point: the breakaway a start must exceed),
    reflected to the input body through the train's ratio and efficiencies (power flowing forward); 0 for another
    law or a table that does not resist there. The model's table turns with the rotation, tanh(w / w_eps) (w_eps 0.5 %
    of the nominal output speed, docs/physics.md), which is 0 at rest: a table falling within a few w_eps of rest
    (a breakaway falling to its running torque) there carries the model's train through a breakaway that holds it."""
    law = lay.load_law
    if not law or law[machine.L_KIND] != machine.TABLE:
        return 0.0
    t = lay.load.torque_Nm * law[machine.L_TAB + int(law[machine.L_N])] * lay.bodies[-1].ratio
    return t / lay.train_efficiency() if t > 0.0 else 0.0


def back_driving_Nm(lay: Layout, forward_Nm: float) -> float:
    """What a load of ``forward_Nm`` at the input body (:func:`reflected_load_Nm`, power flowing forward) puts on it
    as it drives the train backwards: through the losses both ways, T_L eta_back / i. A start's torque at standstill
    below it lets the load turn the train back; between it and ``forward_Nm`` the losses hold the train at rest
    (design's ``soft_start_rolls_back``, simulate's ``motor_rolls_back``)."""
    return forward_Nm * lay.train_efficiency() * lay.train_efficiency(forward=False)


def curve_peak(curve, grid: np.ndarray, i: int) -> float:
    """The speed of a curve's largest value about ``grid[i]``, its maximum on the grid: a golden-section search
    over the two neighbouring cells (the grid's own argmax was up to half a cell, 0.19 rpm of a 1500 rpm motor, off
    the Kloss curve's breakdown point (1 - s_b) w_s, which design's and simulate's warnings report); a table's
    peak, at one of its points, is found as well (a unimodal cell pair)."""
    a, b = float(grid[max(i - 1, 0)]), float(grid[min(i + 1, grid.size - 1)])
    r = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - r * (b - a), a + r * (b - a)
    fc, fd = curve(c), curve(d)
    while b - a > 1e-12 * max(abs(b), 1.0):
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - r * (b - a)
            fc = curve(c)
        else:
            a, c, fc = c, d, fd
            d = a + r * (b - a)
            fd = curve(d)
    best = 0.5 * (a + b)
    return best if curve(best) >= curve(float(grid[i])) else float(grid[i])


def net_torque_scan(lay: Layout, row, samples: int = SPEED_SAMPLES):
    """The motor's steady net torque over the reflected load, f = T_m - T_load, on a grid from rest to the
    synchronous speed, continued to ``GENERATING_SCAN`` x it when the load still overhauls there (the generating
    branch, slip down to -1): (grid, f, the curve's breakdown speed w_b, the net torque as a function of w)."""
    ws = row[machine.M_WS]

    def net(w: float) -> float:
        return machine.motor_torque(row, STEADY_T, w)[0] - reflected_load_Nm(lay, w)

    grid = np.linspace(0.0, ws, samples + 1)
    curve = np.array([machine.motor_torque(row, STEADY_T, w)[0] for w in grid])
    f = curve - np.array([reflected_load_Nm(lay, w) for w in grid])
    w_b = curve_peak(lambda w: machine.motor_torque(row, STEADY_T, w)[0], grid, int(np.argmax(curve)))
    if f[-1] > 0.0:  # an overhauling load drives the motor past its synchronous speed
        above = np.linspace(ws, GENERATING_SCAN * ws, samples + 1)[1:]
        grid, f = np.concatenate([grid, above]), np.concatenate([f, [net(w) for w in above]])
    return grid, f, w_b, net


def operating_speed_rad_s(lay: Layout) -> float:
    """The input body's speed at the operating point: a motor's crossing of its curve with the reflected load where
    it settles from rest (:func:`settling_speed_rad_s`: the stable one, or a stall's below the breakdown speed), else
    its stable crossing (above the curve's largest torque, the highest one; the nominal speed when there is none);
    a torque drive's balance with a speed-dependent load (:func:`torque_drive_speed_rad_s`); a speed drive's
    nominal speed."""
    if not lay.speed_drive and not lay.motor_drive:
        return torque_drive_speed_rad_s(lay)
    if not lay.motor_drive or not lay.motor_row:
        return lay.drive.speed_rad_s
    grid, f, w_b, net = scan = net_torque_scan(lay, lay.motor_row)
    settles = _motor_settles(lay, *scan)
    if settles is not None:  # where it runs, a stall's crossing below the breakdown speed too
        return settles
    down = [i for i in range(grid.size - 1) if f[i] > 0.0 >= f[i + 1] and grid[i + 1] >= w_b]
    if not down:
        return lay.drive.speed_rad_s
    lo, hi = falling_zero(net, float(grid[down[-1]]), float(grid[down[-1] + 1]))
    return 0.5 * (lo + hi)


def settling_speed_rad_s(lay: Layout) -> float | None:
    """The input body's speed where the train settles from rest, None where it settles nowhere: a motor's first
    crossing of its curve with the reflected load (the speed it runs up to and stays at: on the stable branch or,
    a stall, below the breakdown speed), None where it cannot start (its torque at standstill short of the load)
    or nothing holds it (no crossing up to the generating scan's end); a torque drive's balance
    (:func:`torque_drive_balance_rad_s`); a speed drive's nominal speed."""
    if not lay.speed_drive and not lay.motor_drive:
        return torque_drive_balance_rad_s(lay)
    if not lay.motor_drive or not lay.motor_row:
        return lay.drive.speed_rad_s
    return _motor_settles(lay, *net_torque_scan(lay, lay.motor_row))


def _motor_settles(lay: Layout, grid, f, w_b: float, net) -> float | None:
    """:func:`settling_speed_rad_s` of a motor drive, on its :func:`net_torque_scan` (``grid``, ``f``, ``w_b``, ``net``)."""
    if f[0] > 0.0:
        down = next((i for i in range(grid.size - 1) if f[i] > 0.0 >= f[i + 1]), None)
    elif vfd_ramp_starts(lay):  # the ramp from 0 Hz carries it past the full supply's standstill shortfall
        down = next((i for i in range(grid.size - 2, -1, -1) if f[i] > 0.0 >= f[i + 1] and grid[i + 1] >= w_b), None)
    else:
        return None
    if down is None:
        return None
    lo, hi = falling_zero(net, float(grid[down]), float(grid[down + 1]))
    return 0.5 * (lo + hi)


def vfd_ramp_starts(lay: Layout) -> bool:
    """Whether a VFD's speed ramp from 0 Hz starts the motor: at a low supply frequency (full flux, below the base
    speed) its curve's largest torque is the nameplate breakdown torque at a small speed, so it starts wherever
    that, and the converter's torque limit (if any), exceed the load reflected to it at standstill, though the full
    supply's curve (field-weakened above the base speed) may be short of it there."""
    motor = lay.drive.motor
    if motor is None or motor.starting != "vfd" or motor.table:
        return False
    need, limit = reflected_load_Nm(lay, 0.0), motor.start_parameters[1]
    return motor.breakdown_torque_Nm > need and (limit <= 0.0 or limit > need)


def operating_load_factor(lay: Layout) -> float:
    """g of the load law T_L = T_ref g(w) at the output's speed in the steady state (:func:`operating_speed_rad_s`;
    1 without a law): what the load torque the train carries there is of the nominal one. Kept with the layout (a
    motor's operating point is a scan of its curve: a run's static reference and its loaded flank both ask)."""
    if not lay.load_law:
        return 1.0
    kept = lay.__dict__.get("_operating_load_factor")
    if kept is None:
        w = operating_speed_rad_s(lay) * lay.bodies[-1].ratio
        kept = lay.__dict__.setdefault("_operating_load_factor", float(machine.load_factor(lay.load_law, w)[0]))
    return kept


def torque_drive_speed_rad_s(lay: Layout) -> float:
    """The input speed a torque drive settles at: where its torque meets the load reflected to it,
    ``T_in = T_L(w rho_N) rho_N / prod eta`` (for ``speed_exponent`` p: w_0 (T_in / T_req)^(1/p), as ``gearcli
    design`` warns). The nominal speed where nothing balances (a constant load: the train accelerates or
    decelerates for the whole run) or where the drive already balances the load there."""
    settles = torque_drive_balance_rad_s(lay)
    return lay.drive.speed_rad_s if settles is None else settles


def torque_drive_balance_rad_s(lay: Layout) -> float | None:
    """The input speed where a torque drive's torque meets the load reflected to it (:func:`torque_drive_speed_rad_s`),
    None where nothing balances it: a constant load that differs from the drive's torque by more than the design
    check's tolerance (``gearcli.design.drive_balance.TORQUE_BALANCE_TOLERANCE``: the train accelerates or decelerates
    for the whole run), or a speed law the drive meets at no speed."""
    w0, t_in = lay.drive.speed_rad_s, lay.drive.torque_Nm
    if w0 <= 0.0:
        return w0
    if not lay.load_law:  # a constant load balances the drive only where it already does, at w0
        need = reflected_load_Nm(lay, w0)
        return w0 if t_in == need or (need != 0.0 and abs(t_in / need - 1.0) <= TORQUE_BALANCE_TOLERANCE) else None

    def net(w: float) -> float:
        return t_in - reflected_load_Nm(lay, w)

    f0 = net(w0)
    if f0 == 0.0:
        return w0
    lo, hi = w0, w0
    for _ in range(64):  # a factor of 2 per step: 64 steps span any speed the schema allows
        if f0 > 0.0:
            lo, hi = hi, 2.0 * hi
            if net(hi) <= 0.0:
                break
        else:
            lo, hi = 0.5 * lo, lo
            if net(lo) > 0.0:
                break
    else:
        return None
    if not net(lo) > 0.0 >= net(hi):
        return None
    lo, hi = falling_zero(net, lo, hi)
    return 0.5 * (lo + hi)


def falling_zero(net, lo: float, hi: float) -> tuple[float, float]:
    """Where ``net`` falls through 0 on [lo, hi] (net(lo) > 0 >= net(hi)), bisected to adjacent floats: the last
    bracket (lo, hi). scipy-free, for ``gearcli design``'s start-up."""
    for _ in range(200):  # 200 halvings cover any float bracket
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if net(mid) > 0.0 else (lo, mid)
    return lo, hi


def body_damping(lay: Layout) -> np.ndarray:
    """Per body, ``d = -dT/dw`` of the torques the drive and the load put on it at the operating point (N m s); kept
    with the layout (a motor's operating point is a scan of its curve, ~50 ms: a run's modes, resonance checks and
    settle test all ask), a copy each time."""
    kept = lay.__dict__.get("_body_damping")
    if kept is None:
        kept = lay.__dict__.setdefault("_body_damping", _body_damping(lay))
    return kept.copy()


def _body_damping(lay: Layout) -> np.ndarray:
    d = np.zeros(lay.n_bodies)
    w0 = operating_speed_rad_s(lay)
    if lay.motor_drive and lay.motor_row:
        d[0] -= machine.motor_torque(lay.motor_row, STEADY_T, w0)[1]
    if lay.load_law:
        d[-1] += lay.load.torque_Nm * machine.load_factor(lay.load_law, w0 * lay.bodies[-1].ratio)[1]
    return d


def loss_factors(lay: Layout) -> np.ndarray:
    """Per connector and body slot, the fraction of the connector's force that reaches that body at the operating
    point, as the simulation's loss hook scatters it (:func:`.elements.mesh.loss_factors`, its element's
    ``loss_sides``): the side that drives takes ``f``, the driven side ``eta f``, the power-flow sign that of
    ``f v`` with the static force ``f`` and the mean pitch-line speed ``v`` of the rigid chain (a pair mesh's gear
    for a forward load, its pinion for a reversed one; a planet mesh in the carrier's frame, so the planet drives
    the ring of a sun-driven stage and takes ``f`` there, its carrier ``l_a f_a + l_b f_b``); 1 elsewhere."""
    g = np.ones((lay.n_conn, max(len(x.bodies) for x in lay.connectors)))
    if not any(x.lossy for x in lay.connectors):
        return g
    from gearcli.model.linear import static_forces  # lazy: an import cycle (linear imports this module)

    F = static_forces(lay)
    ratio = [b.ratio for b in lay.bodies]
    forward = lay.load.torque_Nm >= 0.0
    for c, x in enumerate(lay.connectors):
        if not x.lossy:
            continue
        side_a, side_b = x.loss_speeds
        v = 0.5 * (sum(k * ratio[b] for b, k in side_a) + sum(k * ratio[b] for b, k in side_b))
        s = math.copysign(1.0, F[c] * v) if F[c] * v != 0.0 else (1.0 if forward else -1.0)
        half = 0.5 * (1.0 - x.efficiency)
        ga, gb = 1.0 - half * (1.0 - s), 1.0 - half * (1.0 + s)
        for j in range(len(x.bodies)):
            sa, sb = x.loss_share(j)
            if sa or sb:
                g[c, j] = sa * ga + sb * gb
    return g


def lever_matrices(lay: Layout, first: int) -> tuple[np.ndarray, np.ndarray]:
    """(R, L) over the bodies ``first`` .. last: the levers (``delta = R theta``) and the levers times the loss
    factors (the torques a connector force ``f`` puts on the bodies are ``L^T f``)."""
    n = lay.n_bodies
    R = np.zeros((lay.n_conn, n))
    L = np.zeros((lay.n_conn, n))
    g = loss_factors(lay)
    for i, x in enumerate(lay.connectors):
        for j, (b, lever) in enumerate(zip(x.bodies, x.levers, strict=True)):
            R[i, b] += lever
            L[i, b] += lever * g[i, j]
    return R[:, first:], L[:, first:]


def body_matrices(lay: Layout, k: np.ndarray, c: np.ndarray, first: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(J, K, C) over the bodies ``first`` .. last (module text): ``k``, ``c`` the connectors' tangents."""
    R, L = lever_matrices(lay, first)
    K = L.T @ (np.asarray(k)[:, None] * R)
    C = L.T @ (np.asarray(c)[:, None] * R) + np.diag(body_damping(lay)[first:])
    return np.asarray(lay.inertias[first:], dtype=float), K, C


def state_matrix(J: np.ndarray, K: np.ndarray, C: np.ndarray) -> np.ndarray:
    """The first-order matrix of ``J theta'' + C theta' + K theta = 0`` in (theta, w)."""
    n = J.size
    return np.block([[np.zeros((n, n)), np.eye(n)], [-K / J[:, None], -C / J[:, None]]])


def modal_damping_ratios(J: np.ndarray, K: np.ndarray, C: np.ndarray, shapes: np.ndarray,
                         omega: np.ndarray) -> np.ndarray:
    """The damping ratio of each undamped mode (``shapes`` its columns, body angles; ``omega`` rad/s, 0 for a
    rigid one: ratio 0): ``-Re lambda / |lambda|`` of the damped eigenvalue whose shape matches it best (modal
    assurance criterion, mass-weighted, above :data:`MIN_MAC`); a mode no oscillating eigenvalue matches (an
    overdamped one) takes the modal projection ``phi^T C phi / (2 omega phi^T J phi)`` (row 0 of
    :func:`modal_damping`)."""
    return modal_damping(J, K, C, shapes, omega)[0]


def modal_damping(J: np.ndarray, K: np.ndarray, C: np.ndarray, shapes: np.ndarray,
                  omega: np.ndarray) -> np.ndarray:
    """Per undamped mode (columns of the result): row 0 its damping ratio (:func:`modal_damping_ratios`), row 1
    the frequency ``Im lambda`` (rad/s) at which the damped eigenvalue that ratio is taken from rings, NaN where
    none is (a rigid mode, an overdamped one's projection). Strong non-proportional damping (a motor's slip
    damping) moves an eigenvalue far from the undamped mode it matches: a 11.2 Hz free mode whose eigenvalue rings
    at 8.1 Hz with zeta 0.49, so the ratio is told with the frequency it belongs to. Kept for the last few exact
    arguments: the points of a sweep over the speed share their chain's matrices and modes, whose damping is the
    same numbers (a copy each time)."""
    key = tuple((a.shape, a.tobytes()) for a in (np.asarray(x, dtype=float) for x in (J, K, C, shapes, omega)))
    found = _RATIOS.get(key)
    if found is None:
        found = remember(_RATIOS, key, _modal_damping(J, K, C, shapes, omega))
    return found.copy()


_RATIOS: dict[tuple, np.ndarray] = {}  # modal_damping by its exact arguments


def _modal_damping(J: np.ndarray, K: np.ndarray, C: np.ndarray, shapes: np.ndarray,
                   omega: np.ndarray) -> np.ndarray:
    lam, vec = np.linalg.eig(state_matrix(J, K, C))
    n = J.size
    osc = [i for i in range(lam.size) if lam[i].imag > 0.0]
    out = np.zeros(shapes.shape[1])
    rings = np.full(shapes.shape[1], np.nan)
    taken = _match_eigenvalues(J, shapes, omega, lam, vec[:n], osc)
    for j, i in taken.items():
        out[j] = -lam[i].real / abs(lam[i])
        rings[j] = lam[i].imag
    for j in range(shapes.shape[1]):
        if omega[j] > 0.0 and j not in taken:
            phi = shapes[:, j]
            out[j] = float(phi @ C @ phi) / (2.0 * omega[j] * float(phi @ (J * phi)))
    undamped = 2.0 * math.pi * np.abs(out) < UNDAMPED_PER_PERIOD  # roundoff of an undamped chain: undamped
    out[undamped] = 0.0
    rings[undamped & (omega > 0.0)] = omega[undamped & (omega > 0.0)]  # ... ringing at its own frequency
    return np.vstack([out, rings])


def _match_eigenvalues(J: np.ndarray, shapes: np.ndarray, omega: np.ndarray, lam: np.ndarray, vecs: np.ndarray,
                       osc: list[int]) -> dict[int, int]:
    """Undamped mode -> the oscillating eigenvalue it is matched to (modal assurance criterion above
    :data:`MIN_MAC`, greedily by the largest). Modes of one frequency (a planetary's N - 1 planet modes) are matched
    as their eigenspace: the undamped solver's basis of it and the damped eigenvectors are two arbitrary bases of the
    same space, which need not match vector by vector (a 5-planet stage's four planet modes found one eigenvalue of
    their four), so an eigenvector's criterion against a group is its share in the group's span, and the group
    takes as many eigenvalues as it has modes, each mode then the eigenvalue nearest its own shape."""
    groups = _repeated(omega)
    pairs = []
    for g, members in enumerate(groups):
        span = shapes[:, members]
        gram = np.linalg.inv(span.T @ (J[:, None] * span))
        for i in osc:
            if not 1.0 / MAX_FREQUENCY_RATIO <= abs(lam[i]) / omega[members[0]] <= MAX_FREQUENCY_RATIO:
                continue  # |lambda| is the mode's natural frequency (exactly for one degree of freedom): another mode's,
                # or the round-off of an unresolved one (a chain with stiffness ratios of 1e12: eps x its largest)
            v = vecs[:, i]
            p = span.T @ (J * v)
            mac = float(np.real(np.vdot(p, gram @ p))) / float(np.real(np.vdot(v * J, v)))
            pairs.append((mac, g, i))
    eigs_of: dict[int, list[int]] = {}
    used_eigs: set[int] = set()
    for mac, g, i in sorted(pairs, reverse=True):
        if mac < MIN_MAC or i in used_eigs or len(eigs_of.get(g, ())) == len(groups[g]):
            continue
        used_eigs.add(i)
        eigs_of.setdefault(g, []).append(i)
    taken: dict[int, int] = {}
    for g, eigs in eigs_of.items():
        within = sorted(((_mac(J, shapes[:, j], vecs[:, i]), j, i) for j in groups[g] for i in eigs), reverse=True)
        for _, j, i in within:
            if j not in taken and i not in taken.values():
                taken[j] = i
    return taken


def _mac(J: np.ndarray, phi: np.ndarray, v: np.ndarray) -> float:
    """The mass-weighted modal assurance criterion of a real shape and a complex eigenvector."""
    return abs(np.vdot(phi * J, v)) ** 2 / (float(phi @ (J * phi)) * float(np.real(np.vdot(v * J, v))))


def _repeated(omega: np.ndarray) -> list[list[int]]:
    """The oscillating modes (``omega`` > 0) grouped by their frequency: equal within ``REPEATED``, the fraction
    within which the mesh orders' analysis takes modes as one repeated mode (:mod:`gearcli.model.planet_excitation`)."""
    live = sorted((j for j in range(omega.size) if omega[j] > 0.0), key=lambda j: omega[j])
    groups: list[list[int]] = []
    for j in live:
        if groups and omega[j] - omega[groups[-1][0]] <= REPEATED * omega[j]:
            groups[-1].append(j)
        else:
            groups.append([j])
    return groups


def decay_rate(eigenvalue: complex) -> float:
    """``sigma = -Re lambda`` of an oscillating eigenvalue, 0 for a growing one and for one that decays by less
    than :data:`UNDAMPED_PER_PERIOD` per period (an undamped mode's roundoff)."""
    sigma, omega = -float(eigenvalue.real), abs(float(eigenvalue.imag))
    return sigma if sigma * 2.0 * math.pi >= UNDAMPED_PER_PERIOD * omega else 0.0
