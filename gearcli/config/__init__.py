"""Design files: the pydantic schema (``schema``) and loading with ``--set`` overrides (``load``)."""

from gearcli.config.load import (
    MAX_BYTES,
    ConfigErrors,
    LoadedDesign,
    check_override_keys,
    json_schema,
    load_design,
    load_variant,
    starter_toml,
)
from gearcli.config.schema import DesignFile

__all__ = ["MAX_BYTES", "ConfigErrors", "DesignFile", "LoadedDesign", "check_override_keys", "json_schema", "load_design",
           "load_variant", "starter_toml"]
