"""Design files: the pydantic schema (``schema``) and loading with ``--set`` overrides (``load``)."""

from gearcli.config.load import (
    MAX_BYTES,
    ConfigErrors,
    LoadedDesign,
    json_schema,
    load_design,
    starter_toml,
)
from gearcli.config.schema import DesignFile

__all__ = ["MAX_BYTES", "ConfigErrors", "DesignFile", "LoadedDesign", "json_schema", "load_design", "starter_toml"]
