"""The "0 or not nearly 0" bound of design-file numbers (docs/design-file.md, "0 or magnitude ≥ …").

Quantities that may be 0 (a ramp, damping, backlash, a torque, a profile shift, an excitation amplitude) may
not be *nearly* 0: a nonzero magnitude below ``tiny`` (a subnormal like 1e-320 is the usual case: a unit
mistake or garbage) is refused with the bound named. Used by :mod:`gearcli.config.schema` and
:mod:`gearcli.config.excitation`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pydantic import GetCoreSchemaHandler, GetJsonSchemaHandler
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import core_schema


@dataclass(frozen=True)
class NotTiny:
    """Annotation: 0 is allowed, but no magnitude in (0, tiny); in the JSON Schema a "not" range."""

    tiny: float

    def check(self, v: float) -> float:
        if v != 0 and abs(v) < self.tiny:
            raise ValueError(f"must be 0 or at least {self.tiny:g} in magnitude, got {v!r} (a value this small "
                             "is a mistake)")
        return v

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> Any:
        return core_schema.no_info_after_validator_function(self.check, handler(source))

    def __get_pydantic_json_schema__(self, schema: Any, handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        out = handler(schema)
        ranges = [{"exclusiveMinimum": 0, "exclusiveMaximum": self.tiny},
                  {"exclusiveMinimum": -self.tiny, "exclusiveMaximum": 0}]
        out["not"] = {"anyOf": ranges if out.get("minimum", 0) < 0 else ranges[:1]}
        return out
