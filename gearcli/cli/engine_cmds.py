"""``gearcli engine``: the compiled integration engine's cache."""

from __future__ import annotations

import click

from gearcli.cli.common import fail, guarded, is_quiet, quiet_option
from gearcli.errors import EXIT_FAILED


@click.group(epilog="""\b
Examples:
  gearcli engine build
  gearcli engine build --force
""")
def engine() -> None:
    """The compiled integration engine (the fast extra, numba): its cache."""


@engine.command("build", epilog="""\b
Examples:
  gearcli engine build          # once after installing (CI and the install instructions run it)
  gearcli engine build --force  # discard the cache and compile again
""")
@click.option("--force", is_flag=True, help="Discard the cached kernel and compile it again.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def engine_build(force: bool) -> None:
    """Compile the integration kernel into the cache now (with progress), so that no run pays for it."""
    from gearcli import api  # lazy: start-up time of --help

    built = api.engine_build(force=force, quiet=is_quiet())
    if built.refused:  # compiled, but nothing cached: the command's purpose failed
        fail(f"the kernel compiled, but nothing was cached: {built.refused}", EXIT_FAILED)
    why = api.engine_cache_refusal()
    if why and built.directory is not None and not is_quiet():
        click.echo(f"gearcli: {why}; the engine is cached in {built.directory} instead", err=True)
    if built.build_s:
        click.echo(f"engine: compiled in {built.build_s:.1f} s; cached in {built.directory}")
    else:
        click.echo(f"engine: already compiled; cached in {built.directory}")
    click.echo(f"engine: a process loads it in {built.load_s:.2f} s (numba import, kernel module, one entry; measured now)")

