"""The design file's inputs checked before any arithmetic: materials and hands (``checks``), a planetary
stage as its sun–planet pair and its ring (``planetary``), the rating's keys (the ``[rating] standard``'s,
``standards``).

Above the three it calls, so none of them imports another's checks (the design layer's inner contract,
ARCHITECTURE.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.design.checks import check_hands, check_material
from gearcli.design.planetary import check_planetary_inputs, pair_equivalent, planetary_key
from gearcli.design.standards import standard_of
from gearcli.errors import DesignError

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


def check_inputs(cfg: DesignFile) -> None:
    """Refuse unknown materials and impossible helix hands, before any arithmetic. A planetary stage is
    checked as its sun–planet pair (keys named ``sun``/``planet``) and its ring."""
    pairs = pair_equivalent(cfg)
    try:
        for k in range(len(pairs.stage)):
            stage = pairs.pair(k)
            for part in ("pinion", "gear"):
                check_material(getattr(stage, part).material, pairs.materials, f"stage[{k}].{part}.material")
            check_hands(stage, k)
        if cfg.rating is not None:  # the [rating] standard's required keys (gearcli.rating)
            standard_of(cfg).check_inputs(cfg)
    except DesignError as exc:
        raise DesignError(exc.message, key=planetary_key(cfg, exc.key), source=exc.source) from None
    check_planetary_inputs(cfg)
