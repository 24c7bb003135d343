"""A drive against its load (``gearcli design``): a torque drive's balance (check ``torque_drive_balance``), where
the train settles when the drive's torque is not the one the load needs at the nominal speed, or that nothing
balances it; a load table read past its last point (check ``load_table_beyond``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from gearcli.config.machine import table_value
from gearcli.core.jsontypes import JsonObject

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile

TORQUE_BALANCE_TOLERANCE = 0.01  # |T_in / T_req - 1| of a torque drive: 1 % (a fan law: 0.5 % in speed)


def load_table_beyond_warning(cfg: DesignFile, output_speed_rpm: float) -> tuple[str | None, JsonObject]:
    """A load ``torque_speed`` table whose last point lies below the nominal output speed: the design and the run
    take its last segment extended (:func:`gearcli.config.machine.table_value`), a torque nobody measured (a table
    ending at 20 rpm with 4500 N·m, run at 50 rpm, loads the train with ~7000 N·m, unwarned until 2026-12-01).
    The nominal speed is where the design reads the load; a motor or torque drive settles where its curve meets
    the table, which ``motor_speed_mismatch`` and ``torque_drive_balance`` name."""
    table = cfg.load.torque_speed
    n = abs(output_speed_rpm)
    if table is None or n <= float(table[-1][0]):
        return None, {}
    last_rpm, last_Nm = float(table[-1][0]), float(table[-1][1])
    torque = table_value(table, n)
    data: JsonObject = {"check": "load_table_beyond", "output_speed_rpm": n, "table_last_rpm": last_rpm,
                        "table_last_torque_Nm": last_Nm, "load_torque_Nm": torque}
    share = f" ({torque / last_Nm:.3g}x the last point's)" if last_Nm != 0.0 else ""
    return (f"load.torque_speed: the table ends at {last_rpm:.5g} rpm ({last_Nm:.5g} N·m), below the nominal output "
            f"speed {n:.5g} rpm, where its last segment extended gives {torque:.5g} N·m{share}: a load nobody "
            "measured; extend the table to the operating speed"), data


def torque_drive_warning(cfg: DesignFile, required_input_Nm: float, input_speed_rpm: float,
                         output_speed_rpm: float = 0.0, reflect: Callable[[float], float] | None = None) -> str | None:
    """A torque drive whose torque differs from the one the load needs at the nominal speed (the design's input
    torque: load / ratio, with the stage efficiencies) by more than :data:`TORQUE_BALANCE_TOLERANCE`: the train does
    not run at the nominal speed. A load torque T_L (n / n_0)^p (``speed_exponent`` p = 1, 2) balances the drive at
    n* = n_0 (T_in / T_req)^(1/p) (the steady speed the run settles to), a ``torque_speed`` table where it meets
    the drive's torque reflected to the output (:func:`_table_settle_rpm`, at the nominal ``output_speed_rpm``'s
    scale; ``reflect``, the load torque to the input's, sets the table's torque there: a load that drives the
    train reaches the input through the losses the other way); a constant load (p = 0), or a table the train never
    meets, does not: the train accelerates (decelerates, reverses) for the whole run and every window statistic
    drifts."""
    t_in = cfg.input.torque_Nm_value
    if cfg.input.drive != "torque" or t_in is None:
        return None
    p = cfg.load.speed_exponent if cfg.load.torque_speed is None else 0
    if p > 0 and required_input_Nm < 0.0:  # the load drives the train, harder the faster it turns: no stable balance
        return (f'input: drive = "torque" gives {t_in:.5g} N·m against a load that drives the train ({required_input_Nm:.5g} '
                f"N·m at the input at {input_speed_rpm:.5g} rpm) harder the faster it turns (speed^{p}): no speed is a "
                f"stable balance, the train runs away (without bound{', in a finite time' if p == 2 else ''}) or stops "
                "and reverses at the slightest difference; drive it by speed or by a motor, whose curve brakes it")
    if required_input_Nm != 0.0 and abs(t_in / required_input_Nm - 1.0) <= TORQUE_BALANCE_TOLERANCE:
        return None
    if t_in == required_input_Nm:
        return None
    excess = t_in - required_input_Nm
    lead = (f'input: drive = "torque" gives {t_in:.5g} N·m, the load needs {required_input_Nm:.5g} N·m at the input '
            f"at its nominal {input_speed_rpm:.5g} rpm (the load torque over the ratio, with the stage efficiencies)")
    ratio = t_in / required_input_Nm if required_input_Nm != 0.0 else 0.0
    table = cfg.load.torque_speed
    target = _balancing_load_Nm(t_in, ratio * table_value(table, output_speed_rpm), reflect) if table else 0.0
    met = (_table_settle_rpm(table, target, excess > 0.0, output_speed_rpm)
           if table is not None and output_speed_rpm > 0.0 else None)
    # a table resisting at rest (its first point, turning with the rotation) beyond the drive's torque holds the
    # train there once the drive has let it slow down: it stops, it does not reverse
    held = table is not None and met is None and excess < 0.0 and 0.0 <= target < table_value(table, 0.0)
    if p > 0 and ratio > 0.0:
        settle = input_speed_rpm * ratio ** (1.0 / p)
        fate = (f"; the load's torque grows with speed^{p}, so the train settles at {settle:.5g} rpm "
                f"(n_0 (T_in / T_req)^(1/{p})), not at {input_speed_rpm:.5g} rpm")
    elif p > 0 and t_in < 0.0:  # the law, odd in speed, brakes the train turning backwards: it settles there
        settle = -input_speed_rpm * (-ratio) ** (1.0 / p)
        fate = (f"; the drive turns the train backwards, where the load's torque (speed^{p}, odd in speed) brakes it: "
                f"it stops, reverses and settles at {settle:.5g} rpm (-n_0 (|T_in| / T_req)^(1/{p})), not at "
                f"{input_speed_rpm:.5g} rpm")
    elif p > 0:  # no drive torque: the load's torque falls with the speed, so the train never quite stops
        fate = (f"; without a drive torque the load brakes the train towards rest, ever more slowly (its torque falls "
                f"with speed^{p}, so it stops in no finite time), for the whole run, and its speeds and window "
                "statistics drift")
    elif held:
        fate = (f"; the train slows down to rest, where the load's torque_speed table holds it: its torque at "
                f"standstill, {table_value(table, 0.0):.5g} N·m (its first point), exceeds the {target:.5g} N·m the drive "
                "balances at the output, so it stays at rest (it does not reverse)")
    elif met is not None:
        fate = (f"; the load's torque_speed table meets it at {met:.5g} rpm of the output, so the train settles at "
                f"{met * input_speed_rpm / output_speed_rpm:.5g} rpm, not at {input_speed_rpm:.5g} rpm")
    else:
        # the net torque along the train's running direction (speeds positive there, a reversed load's negative
        # requirement included): T_in - T_req > 0 speeds it up whatever the signs of either
        way = "accelerates" if excess > 0.0 else "decelerates (and reverses)"
        fate = (f"; nothing balances the difference ({excess:+.4g} N·m), so the train {way} for the whole run and "
                "its speeds and window statistics drift")
    return (lead + fate + f": set the drive's torque to {required_input_Nm:.5g} N·m for the nominal speed"
            + ("" if p > 0 or met is not None or held else " (or give the load a speed law, load.speed_exponent)"))


def _balancing_load_Nm(t_in: float, scaled: float, reflect: Callable[[float], float] | None) -> float:
    """The load torque (N·m at the output) that a torque drive's ``t_in`` balances: the inverse of ``reflect``, which
    is linear on either side of 0 (the losses against the power flow: T_L / (i eta) forward, T_L eta / i back),
    so the balancing load has the drive's sign; ``scaled`` (the nominal load times T_in / T_req, right while the
    load keeps its sign) without ``reflect``."""
    if reflect is None or t_in == 0.0:
        return scaled if reflect is None else 0.0
    unit = 1.0 if t_in > 0.0 else -1.0
    return unit * t_in / reflect(unit)


def _table_settle_rpm(table: list[list[float]], target: float, up: bool, n0: float) -> float | None:
    """The output speed at which the load table (rpm, N·m: linear between its points, constant below the first, its
    last segment extended, as the model takes it) reaches ``target`` (N·m), first met from the nominal output speed
    ``n0`` in the way the train moves (``up`` where the drive exceeds the load there); None where it never is."""
    xs, ys = [float(x) for x, _ in table], [float(y) for _, y in table]

    def y(n: float) -> float:
        return table_value(table, n)  # the design's and the model's reading of the table

    slope = (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
    ends = [x for x in xs if x > n0] + ([xs[-1] + (target - ys[-1]) / slope] if slope > 0.0 and ys[-1] < target
                                       else []) if up else sorted((x for x in xs if x < n0), reverse=True)
    a = n0
    for b in ends:
        if (y(b) >= target) if up else (y(b) <= target):
            return a + (target - y(a)) * (b - a) / (y(b) - y(a)) if y(b) != y(a) else b
        a = b
    return None
