"""The design file's inputs checked before any arithmetic: materials and hands (``checks``), every stage as
the pair its kind designs and then by its kind (a planetary's ring: ``gearcli.stages``), the rating's keys (the
``[rating] standard``'s, ``standards``).

Above the three it calls, so none of them imports another's checks (the design layer's inner contract,
ARCHITECTURE.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.design.input_checks import check_hands, check_material
from gearcli.design.standards import standard_of
from gearcli.errors import DesignError
from gearcli.stages.design import design_kind, file_key, gear_pairs, pair_view

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


def check_inputs(cfg: DesignFile) -> None:
    """Refuse unknown materials and impossible helix hands, before any arithmetic. A planetary stage is
    checked as its sun–planet pair (keys named ``sun``/``planet``) and its ring."""
    pairs = pair_view(cfg)
    try:
        for k, _ in gear_pairs(cfg.stage):
            stage = pairs.pair(k)
            for part in ("pinion", "gear"):
                check_material(getattr(stage, part).material, pairs.materials, f"stage[{k}].{part}.material")
            try:
                check_hands(stage, k)
            except DesignError:  # again, its members named as the file names them (a planetary: sun, planet),
                # which only its message reads: the same check, the same error
                first, second = (str(file_key(cfg, f"stage[{k}].{part}.hand")).split(".")[-2]
                                 for part in ("pinion", "gear"))
                check_hands(stage, k, (first, second))
                raise
        if cfg.rating is not None:  # the [rating] standard's required keys (gearcli.rating)
            standard_of(cfg).check_inputs(cfg)
    except DesignError as exc:
        raise DesignError(exc.message, key=file_key(cfg, exc.key), source=exc.source) from None
    given = cfg.rating.load_sharing_factor if cfg.rating is not None else None
    if given is not None and not any(design_kind(s).shares_load for s in cfg.stage):
        name = "load_sharing_factor" if cfg.rating is None or cfg.rating.K_gamma is None else "K_gamma"
        raise DesignError(f"{name} = {given:g} is the load-sharing factor K_gamma of a planetary stage's planets, "
                          "and this train has no planetary stage: remove it", key=f"rating.{name}")
    for k, s in enumerate(cfg.stage):
        design_kind(s).check_inputs(cfg, k)
