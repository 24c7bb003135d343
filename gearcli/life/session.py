"""One ``gearcli life`` run: the base file as a sweep scene, and its duty points (from the file or a series)."""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from gearcli.errors import ConfigError, DesignError
from gearcli.life.duty import (
    DEFAULT_CLASSES,
    DutyPoint,
    points_from_config,
    points_from_series,
    read_series,
    with_drive,
)

MAX_SERIES_BYTES = 64 * 1024 * 1024


@dataclass(frozen=True)
class Session:
    scene: Any  # gearcli.sweep.worker.Scene
    loaded: Any  # LoadedDesign of the base file
    design: Any  # its DesignResult
    points: tuple[DutyPoint, ...]


def _series_text(path: str) -> str:
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MAX_SERIES_BYTES + 1)
    except OSError as exc:
        raise ConfigError(f"cannot read: {exc.strerror or exc}", source=path) from None
    if len(raw) > MAX_SERIES_BYTES:
        raise ConfigError(f"larger than {MAX_SERIES_BYTES // (1024 * 1024)} MiB", source=path)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ConfigError("not UTF-8 text", source=path) from None


def prepare(file: str, sets: Sequence[str], *, series: str | None = None,
            classes: int = DEFAULT_CLASSES) -> Session:
    """Read and validate the base file (exit 2 on bad input, before any point runs) and make the points."""
    from gearcli.config import load_design
    from gearcli.config.load import read_bytes
    from gearcli.design import compute_design
    from gearcli.sweep.worker import Scene

    raw = read_bytes(file, None)
    loaded = load_design(file, sets, stdin=io.BytesIO(raw))
    try:
        design = compute_design(loaded.design)
    except DesignError as exc:
        raise DesignError(exc.message, key=exc.key, source=loaded.source) from exc
    if series is not None:
        cols = read_series(_series_text(series), series)
        points = points_from_series(*cols, source=series, classes=classes)
    else:
        points = points_from_config(loaded.design)
    points = with_drive(loaded.design, points)
    if loaded.design.rating is None:
        raise ConfigError("gearcli life rates every member by ISO 6336-2/-3: add a [rating] table (with the "
                          "materials' treatment and fatigue limits, accuracy grades, roughness and [lubricant])",
                          source=loaded.source, key="rating")
    return Session(Scene(raw, loaded.source, tuple(sets), len(design.stages)), loaded, design, tuple(points))
