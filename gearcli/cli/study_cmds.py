"""The commands that run studies: ``report`` (the accuracy ladder), ``sweep`` (many operating points) and
``life`` (a duty cycle)."""

from __future__ import annotations

import math
import sys

import click
from click.core import ParameterSource

from gearcli.cli.common import (
    check_plots_dir,
    check_sweep_plots_dir,
    check_target,
    context_inputs,
    csv_table_option,
    emit,
    emit_as,
    emit_tables,
    guarded,
    io_options,
    is_quiet,
    load_and_design,
    quiet_option,
    wants_bearing_csv,
    warn,
    write_figures,
)
from gearcli.core.text import visible
from gearcli.errors import EXIT_FAILED
from gearcli.io import output as outfiles

# ------------------------------------------------------------------------------------------ report
REPORT_FORMATS = ("table", "json", "markdown")
MAX_RTOLS = 12  # the default ladder has 7 rungs; each rung is a full simulation


def _parse_rtols(ctx, param, value: str | None):
    if value is None:
        return None
    try:
        rtols = tuple(float(v) for v in value.split(",") if v.strip())
    except ValueError:
        raise click.BadParameter(f"{value!r}: give comma-separated numbers, e.g. 1e-3,1e-6,1e-9") from None
    bad = [r for r in rtols if not 1e-13 <= r <= 1e-2]
    if not rtols or bad:
        raise click.BadParameter("every rtol must lie in [1e-13, 1e-2]" + (f", got {bad[0]:g}" if bad else ""))
    if len(rtols) > MAX_RTOLS:
        raise click.BadParameter(f"at most {MAX_RTOLS} tolerances, got {len(rtols)}")
    if len(set(rtols)) != len(rtols):
        twice = next(r for r in rtols if rtols.count(r) > 1)
        raise click.BadParameter(f"{twice:g} is given twice; each tolerance once")
    return rtols


def _finite_accuracy(ctx, param, value: float) -> float:
    if not math.isfinite(value) or not 1e-12 <= value <= 0.5:
        raise click.BadParameter(f"must be a number in [1e-12, 0.5], got {value!r}")
    return value


@click.command(epilog="""\b
Examples:
  gearcli report mixer.toml -o report.md
  gearcli report mixer.toml --quick --format json -o report.json
  gearcli report mixer.toml --plots figures --accuracy 1e-5
  gearcli report mixer.toml --rtols 1e-4,1e-6,1e-8 --set simulation.duration_s=0.3
""")
@click.argument("file", type=str)
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override a design-file key, e.g. --set simulation.duration_s=0.25 (repeatable).")
@click.option("--format", "fmt", type=click.Choice(REPORT_FORMATS),
              help="Output format [default: table on a terminal, markdown in a pipe].")
@outfiles.output_option("Write to FILE atomically ('-' is stdout; format from the suffix: .json, .md, .txt).")
@click.option("--accuracy", type=float, callback=_finite_accuracy, default=1e-4, show_default=True,
              help="Relative accuracy the recommended solver setting must meet.")
@click.option("--quick", is_flag=True, help="Skip the accuracy study (one simulation).")
@click.option("--rtols", callback=_parse_rtols, metavar="LIST",
              help="The accuracy ladder's tolerances, comma-separated [default: 1e-3,1e-4,...,1e-9].")
@click.option("--plots", "plots_dir", type=click.Path(), metavar="DIR",
              help="Also write campbell.png, speeds.png, mesh_forces.png, spectrum.png and (not with --quick) "
                   "work_precision.png to DIR. Needs "
                   "matplotlib (pip install 'gearcli[plot]'); without it: a warning, the rest of the report, exit 0.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def report(file: str, overrides, fmt, output, accuracy: float, quick: bool, rtols, plots_dir) -> None:
    """Theory against simulation, the numerical error against run time, and plots."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import serialize  # lazy: start-up time of --help

    target = check_target(fmt, output, REPORT_FORMATS, pipe_format="markdown")
    if plots_dir:
        _check_plots_dir(plots_dir, file, target)
    if quick:
        warn(f"{o} sets the accuracy study, which --quick skips: it has no effect" for o in _given("accuracy", "rtols"))
    loaded, design_result = load_and_design(file, overrides)
    api.check_budget(loaded, design_result)  # the file's own run; the ladder's runs bound themselves
    warn(design_result.warnings)
    fmt = target.fmt
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("report", enabled=not is_quiet()) as progress:
        rep = api.report_file(loaded, design_result, accuracy=accuracy, quick=quick, rtols=rtols, progress=progress,
                              overrides=overrides)
    if fmt == "json":
        from gearcli.io.report_json import report_dict  # lazy: start-up time of --help

        emit(serialize.to_json(serialize.with_meta(report_dict(rep), loaded.sha256)), target)
    elif fmt == "markdown":
        from gearcli.io.markdown import report_markdown  # lazy: start-up time of --help

        emit(report_markdown(rep, loaded.sha256), target)
    else:
        from gearcli.io.report_tables import report_tables  # lazy: start-up time of --help

        emit_tables(report_tables(rep), target)
    failed = {d.message for d in rep.diagnostics if d.code == "accuracy" and d.data.get("failed")}  # said below
    warn(w for w in rep.warnings if w not in design_result.warnings and w not in failed)  # design ones went first
    if plots_dir:
        _write_report_plots(rep, plots_dir)
    if rep.accuracy_failure is not None:  # the report is written whole; the run's verdict is a failure (exit 1)
        click.echo(f"gearcli: {visible(loaded.source)}: the report is written without its accuracy study, which "
                   f"failed: {rep.accuracy_failure}", err=True)
        sys.exit(EXIT_FAILED)



def _given(*names: str) -> list[str]:
    """The options among ``names`` that the command line gave (not left at their defaults), as typed."""
    ctx = click.get_current_context()
    return [f"--{n}" for n in names if ctx.get_parameter_source(n) == ParameterSource.COMMANDLINE]


def _check_plots_dir(plots_dir: str, file: str, target) -> None:
    from gearcli.io.plots import FIGURE_NAMES  # lazy: start-up time of --help

    check_plots_dir(plots_dir, FIGURE_NAMES, target)


def _write_report_plots(rep, plots_dir: str) -> None:
    from gearcli.io.plots import write_plots  # lazy: start-up time of --help

    if write_figures(lambda: write_plots(rep, plots_dir), plots_dir, "the report") and not is_quiet() \
            and rep.accuracy is None and rep.accuracy_failure is None:
        click.echo("work_precision.png needs the accuracy study: run without --quick", err=True)


# ------------------------------------------------------------------------------------------- sweep
SWEEP_FORMATS = ("csv", "json")  # gearcli.sweep.session.FORMATS (not imported: start-up time)


@click.command(epilog="""\b
Examples:
  gearcli sweep mixer.toml --vary input.speed_rpm=300:1500:13 -o speed.csv --plots figures
  gearcli sweep mixer.toml --vary input.speed_rpm=300:1500:13 --direction both -o hysteresis.csv
  gearcli sweep mixer.toml --vary load.torque_Nmm=2e6,5.31e6 --vary stage.0.backlash_mm=0,0.2 -o grid.json
  gearcli sweep mixer.toml --random 'stage.0.backlash_mm=normal(0.25,0.02)' --samples 50 --seed 1 -o mc.csv
""")
@click.argument("file", type=str)
@click.option("--vary", multiple=True, metavar="KEY=START:STOP:N|KEY=v1,v2,...",
              help="Vary a key over N evenly spaced values (inclusive) or a list; several make a grid (repeatable).")
@click.option("--random", "randoms", multiple=True, metavar="KEY=normal(MU,SIGMA)|KEY=uniform(A,B)",
              help="Draw a key from a distribution, --samples times (repeatable).")
@click.option("--samples", type=click.IntRange(1, 1_000_000), help="Number of random samples.")
@click.option("--sampling", type=click.Choice(("lhs", "mc")), default="lhs", show_default=True,
              help="Latin hypercube (lhs) or plain Monte Carlo (mc).")
@click.option("--seed", type=click.IntRange(0, 2**63 - 1), help="Seed of the random samples (recorded in -o FILE).")
@click.option("--direction", type=click.Choice(("up", "down", "both")),
              help="Continuation along the first --vary key: each point starts from the previous one's final state.")
@click.option("--jobs", type=click.IntRange(1, 4096), help="Local worker processes [default: all cores].")
@click.option("--scheduler", metavar="ADDRESS",
              help="Run the points on a Dask distributed cluster (pip install 'gearcli[distributed]').")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a key of the base scene.")
@click.option("--format", "fmt", type=click.Choice(SWEEP_FORMATS), help="[default: from -o's suffix, else csv]")
@outfiles.output_option("Write rows to FILE as they finish (.csv or .json; '-' is stdout); a re-run skips the "
                        "points done.")
@click.option("--plots", "plots_dir", type=click.Path(), metavar="DIR",
              help="Response curves, Campbell diagram, histograms into DIR (pip install 'gearcli[plot]').")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def sweep(file: str, vary, randoms, samples, sampling, seed, direction, jobs, scheduler, overrides, fmt, output,
          plots_dir) -> None:
    """Simulate many operating points: grids, tolerance samples, continuation up and down in speed."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.sweep_progress import SweepProgress  # lazy: start-up time of --help

    target = outfiles.check_output(output, formats=SWEEP_FORMATS, fmt=fmt, inputs=context_inputs())  # before work
    if plots_dir:
        check_sweep_plots_dir(plots_dir, file, target, vary)
    output = target.shown if target.path is not None else None
    if not randoms:
        warn(f"{o} sets how the --random samples are drawn, and there are none: it has no effect"
             for o in _given("seed", "sampling"))
    session = api.prepare_sweep(file, overrides, vary=vary, randoms=randoms, samples=samples, sampling=sampling, seed=seed,
                      direction=direction, jobs=jobs, scheduler=scheduler,
                      output=str(target.path) if target.path is not None else None, fmt=target.fmt)
    warn(session.design_warnings)
    warn(session.notes)  # --jobs capped by the machine
    with SweepProgress(session.todo + session.done, session.done, enabled=not is_quiet()) as progress:
        rows = api.run_sweep(session, progress.advance)
    failed = sum(r.get("status") != "ok" for r in rows)
    if failed or not is_quiet():  # -q: silent unless points failed (an error is still said)
        drawn = session.spec.seed if randoms and seed is None else None  # a drawn seed: said, or lost on stdout
        click.echo(f"sweep: {len(rows)} points, {failed} failed" + (f", written to {visible(output)}" if output else "")
                   + (f"; samples drawn with --seed {drawn} (give it to draw them again)" if drawn is not None else ""),
                   err=True)
    if plots_dir:
        _write_sweep_plots(session, rows, plots_dir)
    if failed:
        sys.exit(EXIT_FAILED)



def _write_sweep_plots(session, rows, plots_dir: str) -> None:
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.sweep_plots import write_sweep_plots  # lazy: start-up time of --help

    write_figures(lambda: write_sweep_plots(session, rows, plots_dir, api.sweep_campbell(session)), plots_dir,
                   "the sweep")


# -------------------------------------------------------------------------------------------- life
@click.command(epilog="""\b
Examples:
  gearcli life mixer_duty.toml --static
  gearcli life mixer_duty.toml --format json -o life.json
  gearcli life mixer_duty.toml --series torque_history.csv --static
  gearcli life mixer_duty.toml --plots figures/
""")
@click.argument("file", type=str)
@io_options()
@click.option("--static", "static", is_flag=True,
              help="Rate each duty point's static forces with the rating's K_v (one load class per point) "
                   "instead of simulating it.")
@click.option("--series", "series", metavar="FILE.csv",
              help="A measured history (time_s,torque_Nm,speed_rpm) instead of the [[duty]] tables.")
@click.option("--classes", type=click.IntRange(1, 1000), default=10, show_default=True,
              help="Torque classes of a --series history.")
@click.option("--miner", type=click.Choice(("iso", "elementary", "modified")), default="iso", show_default=True,
              help="The S-N curve below the knee (ISO 6336-6 Miner variants, docs/life.md).")
@click.option("--plots", "plots_dir", type=click.Path(), metavar="DIR",
              help="Also write pitting.png and bending.png (spectra against the S-N curves) to DIR "
                   "(pip install 'gearcli[plot]').")
@csv_table_option("classes", "classes (a row per load class)")
@guarded
def life(file: str, overrides, fmt, output, static: bool, series, classes: int, miner: str, plots_dir,
         csv_table: str = "classes") -> None:
    """Duty cycle to life: load spectra, ISO 6336-6 Miner damage per member, ISO 281 bearing lives."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.life_out import life_bearings_csv, life_csv, life_dict  # lazy: start-up time of --help

    if series is None and click.get_current_context().get_parameter_source("classes") is not ParameterSource.DEFAULT:
        raise click.UsageError("--classes classes a --series history; without --series the [[duty]] tables are the "
                               "points: give --series FILE.csv or drop --classes")
    target = check_target(fmt, output)
    if plots_dir:
        check_plots_dir(plots_dir, ("pitting.png", "bending.png"), target)
    session = api.prepare_life(file, overrides, series=series, classes=classes)
    bearings = wants_bearing_csv(csv_table, "classes", target.fmt, session.loaded)
    warn(session.design.warnings)
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("life", enabled=not is_quiet()) as progress:
        result = api.life(session, static=static, variant=miner, progress=progress)
    emit_as(target.fmt, target, result, sha256=session.loaded.sha256, json_doc=lambda: life_dict(result, session.design),
            csv_text=lambda: life_bearings_csv(result) if bearings else life_csv(result),
            table_builder="life_tables")
    warn(w for w in result.warnings if w not in session.design.warnings)
    if plots_dir:
        _write_life_plots(result, plots_dir)


def _write_life_plots(result, plots_dir: str) -> None:
    from gearcli.io.life_plots import write_life_plots  # lazy: start-up time of --help

    write_figures(lambda: write_life_plots(result, plots_dir), plots_dir, "the life calculation")

