"""The only place that formats (ARCHITECTURE.md). Importing it registers the built-in stage kinds' output facets."""

from gearcli.stages import io as _stage_output  # noqa: F401  # registers the parallel and planetary output facets
