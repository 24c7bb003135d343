"""S–N curves as a rating standard returns them, and the Miner variants below the knee (docs/life.md, "Damage").

A standard (:mod:`gearcli.rating`) gives the S–N curve of a member and failure mode as nodes of a life-factor
curve and an endurance strength. ISO 6336's (``gearcli.design.iso6336``) is the life factor's curve (Z_NT of ISO 6336-2, Y_NT of ISO 6336-3,
for the material group) times the endurance strength: sigma(N) = sigma_inf * Z_NT(N), where sigma_inf is
the rating's limit stress sigma_HG (or sigma_FG) divided by its own Z_NT (Y_NT): every other factor (Z_L,
Z_V, Z_R, Z_W, Z_X; Y_ST, Y_delta, Y_R, Y_X) stays as the rating computed it for that operating point.
Cycles to failure at a stress sigma invert that curve. Below the knee (the endurance limit, Z_NT = 1) the
variants of ISO 6336-6's Miner rule differ, and the output names the one used:

- ``iso`` (default): the curve as ISO 6336-2/-3 give it: for ``material_quality = "normal"`` it falls on to
  0.85 at 1e10 cycles and that slope continues beyond, for ``"optimum"`` it stays at 1 (no damage below the
  endurance limit: Miner's original rule).
- ``elementary``: Miner elementary: the finite-life slope (static limit to knee) continues below the knee.
- ``modified``: Miner modified after Haibach: below the knee the exponent k of N ∝ sigma^-k becomes 2k - 1.

Above the static limit (the curve's first node) the finite-life slope is continued to fewer cycles: such a
bin is reported with ``cycles_to_failure`` below the static node and a warning.
"""

from __future__ import annotations

import math

from gearcli.core.records import record

VARIANTS = ("iso", "elementary", "modified")
VARIANT_NAMES = {
    "iso": "ISO 6336-6 Miner rule on the ISO 6336-2/-3 life-factor curve (normal quality: on to 0.85 at 1e10 "
           "cycles, slope continued; optimum: no damage below the endurance limit)",
    "elementary": "ISO 6336-6 Miner elementary: the finite-life slope continued below the knee",
    "modified": "ISO 6336-6 Miner modified (Haibach): exponent 2k-1 below the knee",
}
OWN_CURVES = ("ISO 6336-6 Miner rule on the rating standard's own life-factor curves (each mode's `curve`: its nodes "
              "past the knee; optimum: no damage below the endurance limit)")


def curve_problem(curve: SNCurve) -> str | None:
    """What makes ``curve`` no S–N curve life can use (a rating standard's, docs/plugins.md), or None: at least
    three nodes (N, factor), N finite, > 0 and rising, factors finite, > 0 and not rising, the static node's above
    the knee's (the finite-life slope), the knee (the second-last node) at factor 1, an endurance strength that is a
    finite number > 0 and a Miner variant gearcli knows."""
    nodes = curve.nodes
    try:
        pairs = [(float(n), float(y)) for n, y in nodes]
    except (TypeError, ValueError):
        return "nodes are no (N, factor) pairs of numbers"
    if len(pairs) < 3:
        return f"nodes are {len(pairs)}, not at least 3 (the static node, the knee at factor 1, a node beyond it)"
    if not all(math.isfinite(n) and n > 0.0 and math.isfinite(y) and y > 0.0 for n, y in pairs):
        return "nodes hold a number that is not finite and > 0"
    if any(b[0] <= a[0] for a, b in zip(pairs, pairs[1:], strict=False)):
        return "cycles N do not rise from node to node"
    if any(b[1] > a[1] for a, b in zip(pairs, pairs[1:], strict=False)) or pairs[0][1] <= pairs[-2][1]:
        return "factors rise somewhere, or the static node's is not above the knee's (no finite-life slope)"
    if abs(pairs[-2][1] - 1.0) > 1e-9:
        return f"knee (the second-last node) is at factor {pairs[-2][1]:.6g}, not 1"
    e = curve.endurance_MPa
    if isinstance(e, bool) or not isinstance(e, (int, float)) or not math.isfinite(e) or e <= 0.0:
        return f"endurance_MPa is {e!r}, not a finite number > 0"
    if curve.variant not in VARIANTS:
        return f"variant is {curve.variant!r}, not one of {', '.join(VARIANTS)}"
    return None


def miner_name(variant: str, *, iso_curves: bool) -> str:
    """The Miner rule's name in life's output (JSON ``life.miner``): the ``"iso"`` variant follows the curve's own
    nodes past the knee, which are ISO 6336-2/-3's only for ISO 6336 (a plug-in standard has its own)."""
    return VARIANT_NAMES[variant] if iso_curves or variant != "iso" else OWN_CURVES


@record
class SNCurve:
    """A life-factor curve as nodes (N, factor), power law between them, scaled by ``endurance_MPa``."""

    nodes: tuple[tuple[float, float], ...]  # (N, Z_NT) from the static node to the last
    endurance_MPa: float  # sigma at factor 1 (the knee)
    variant: str = "iso"
    optimum: bool = False  # material_quality = "optimum": flat at 1 beyond the knee

    @property
    def knee(self) -> tuple[float, float]:
        return self.nodes[-2]

    def _finite_exponent(self) -> float:
        """k of N ∝ sigma^-k on the finite-life branch (static node to knee)."""
        (n0, y0), (n1, y1) = self.nodes[0], self.knee
        return math.log(n1 / n0) / math.log(y0 / y1)

    def _branches(self) -> list[tuple[float, float, float]]:
        """Segments (N_a, factor_a, k) of N = N_a (factor_a / factor)^k, from the static node on."""
        k_fin = self._finite_exponent()
        segs = [(self.nodes[0][0], self.nodes[0][1], k_fin)]
        if self.variant == "elementary":
            return segs
        if self.variant == "modified":
            return [*segs, (self.knee[0], self.knee[1], 2.0 * k_fin - 1.0)]
        for (na, ya), (nb, yb) in zip(self.nodes[1:], self.nodes[2:], strict=False):
            if self.optimum:
                return [*segs, (na, ya, math.inf)]
            # a flat segment (a standard's endurance limit written as nodes) is an infinite exponent
            segs.append((na, ya, math.inf if ya == yb else math.log(nb / na) / math.log(ya / yb)))
        return segs

    def cycles_to_failure(self, stress_MPa: float) -> float:
        """N at which the curve reaches ``stress_MPa`` (math.inf below a flat endurance limit)."""
        if stress_MPa <= 0.0:
            return math.inf
        y = stress_MPa / self.endurance_MPa
        segs = self._branches()
        for i, (na, ya, k) in enumerate(segs):
            last = i == len(segs) - 1
            y_end = None if last else segs[i + 1][1]
            if last or y >= y_end:  # type: ignore[operator]
                if math.isinf(k):
                    return math.inf if y < ya else na
                try:
                    return na * (ya / y) ** k
                except OverflowError:  # a stress so far below the node that N passes every float: no damage
                    return math.inf
        return math.inf  # pragma: no cover - the last branch always answers

    def stress_at(self, cycles: float) -> float:
        """The curve's stress at N cycles (for plots)."""
        segs = self._branches()
        for i, (na, ya, k) in enumerate(segs):
            if i == len(segs) - 1 or cycles < segs[i + 1][0]:
                if math.isinf(k):
                    return self.endurance_MPa * ya
                return self.endurance_MPa * ya * (na / cycles) ** (1.0 / k)
        return math.nan  # pragma: no cover

    @property
    def endurance_limit_MPa(self) -> float:
        """The stress below which the curve has an endurance limit: for the ``iso`` variant the last node ISO
        6336-2/-3 print (normal quality: 0.85 of the knee at 1e10 cycles), the knee where the curve stays flat
        (optimum quality). A spectrum entirely below it has an infinite life (``below_endurance``). Miner elementary
        and modified have none (0): their slope below the knee is the damage the user chose to count, so their life
        is the duty's hours over that damage, never infinite while it is positive."""
        if self.variant != "iso":
            return 0.0
        return self.endurance_MPa * (self.knee[1] if self.optimum else self.nodes[-1][1])

    @property
    def static_cycles(self) -> float:
        return self.nodes[0][0]
