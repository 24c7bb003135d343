"""One ``gearcli life`` run: the base file as a sweep scene, and its duty points (from the file or a series).

The facade (:func:`gearcli.api.prepare_life`) loads and designs the base file; this module makes the points.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from gearcli.config import LoadedDesign
from gearcli.errors import ConfigError
from gearcli.life.duty import (
    DEFAULT_CLASSES,
    DutyPoint,
    points_from_config,
    points_from_series,
    read_series,
    with_drive,
)
from gearcli.results import DesignResult
from gearcli.sweep.worker import Scene

MAX_SERIES_BYTES = 64 * 1024 * 1024


@dataclass(frozen=True)
class Session:
    scene: Scene
    loaded: LoadedDesign  # the base file
    design: DesignResult  # its design
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


def prepare(raw: bytes, loaded: LoadedDesign, design: DesignResult, sets: Sequence[str], *,
            series: str | None = None, classes: int | None = None) -> Session:
    """The duty points of the base file ``raw`` (``loaded`` and ``design`` with the ``sets`` applied): its
    ``[[duty]]`` tables, or the history ``series`` classed into ``classes`` torque classes (exit 2 on bad
    input, before any point runs)."""
    classes = DEFAULT_CLASSES if classes is None else classes
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
