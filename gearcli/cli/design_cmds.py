"""The commands on one design file: ``design``, ``simulate``, ``modes``, and the file makers ``init``, ``schema``."""

from __future__ import annotations

import json
from pathlib import PurePath

import click

from gearcli.cli.common import (
    check_sweep_plots_dir,
    check_target,
    csv_table_option,
    emit,
    emit_as,
    emit_tables,
    fail,
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
from gearcli.errors import EXIT_USAGE, OutputError
from gearcli.io import output as outfiles


@click.command(epilog="""\b
Examples:
  gearcli design mixer.toml
  gearcli design mixer.toml --format json -o design.json
  gearcli design mixer.toml --set stage.0.pinion.teeth=22 --format csv
  gearcli init - | gearcli design -
""")
@click.argument("file", type=str)
@io_options()
@csv_table_option("stages", "stages (a row per stage)")
@guarded
def design(file: str, overrides, fmt, output, csv_table: str = "stages") -> None:
    """Ratios, speeds, torques, helical geometry, contact ratios, stiffness and static forces."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import serialize  # lazy: start-up time of --help

    target = check_target(fmt, output)
    loaded, result = load_and_design(file, overrides)
    bearings = wants_bearing_csv(csv_table, "stages", target.fmt, loaded)
    result = api.with_motor_start(loaded.design, api.with_resonances(loaded.design, result))
    emit_as(target.fmt, target, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.design_dict(result),
            csv_text=lambda: serialize.design_bearings_csv(result) if bearings else serialize.design_csv(result), table_builder="design_tables")
    warn(result.warnings)


@click.command(epilog="""\b
Examples:
  gearcli simulate mixer.toml
  gearcli simulate mixer.toml -o run.csv
  gearcli simulate mixer.toml --format json --series -o run.json
  gearcli simulate mixer.toml --set simulation.duration_s=2 --set simulation.steps=20000
""")
@click.argument("file", type=str)
@io_options()
@click.option("--series", is_flag=True, help="Include the time series in JSON output (CSV always has them).")
@click.option("--dump-model", is_flag=True, help="Print the scene's generated equations (Python source) and exit.")
@csv_table_option("series", "series (a row per output sample)")
@guarded
def simulate(file: str, overrides, fmt, output, series: bool, dump_model: bool = False,
             csv_table: str = "series") -> None:
    """Torsional lumped-parameter simulation with nonlinear Hertz meshes."""
    from gearcli import api  # lazy: start-up time of --help

    if dump_model:
        _dump_model(file, overrides, output)
        return
    target = check_target(fmt, output)
    if series and target.fmt != "json":  # as --dump-model's options: an option that cannot act says so
        warn([f"--series adds the time series to the JSON output; the {target.fmt} output "
              + ("always has them" if target.fmt == "csv" else "shows the statistics, never the series")
              + ": it has no effect"])
    loaded, design_result = load_and_design(file, overrides)  # bad input fails before scipy loads
    bearings = wants_bearing_csv(csv_table, "series", target.fmt, loaded)
    # the bearings' CSV holds no series: budgeted as the JSON summary
    api.check_budget(loaded, design_result, output_format="json" if bearings else target.fmt, series=series)
    warn(design_result.warnings)
    from gearcli.io import serialize  # lazy: start-up time of --help
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("simulate", enabled=not is_quiet()) as progress:  # a long run on a terminal
        result = api.simulate_file(loaded, design_result, progress=progress.fraction, overrides=overrides)
    emit_as(target.fmt, target, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.simulation_dict(result, series=series),
            csv_text=lambda: (serialize.simulation_bearings_csv(result) if bearings
                              else serialize.simulation_csv(result)), table_builder="simulation_tables")
    warn(w for w in result.warnings if w not in design_result.warnings)  # the design's went out first


def _dump_model(file: str, overrides, output) -> None:
    """``simulate --dump-model``: the generated equations, Python source, to stdout or ``-o`` (atomically). The
    options of the run's output (``--format``, ``--series``, ``--table``) have no effect: a warning each; an ``-o``
    whose suffix names a data format (``run.csv``, ``run.json``) would hold Python source under that name: exit 2."""
    from gearcli import api  # lazy: start-up time of --help

    ctx = click.get_current_context()
    given = {"fmt": "--format", "series": "--series", "csv_table": "--table"}
    warn(f"{option} chooses the run's output, which --dump-model does not write (it writes the equations, Python "
         "source): it has no effect" for name, option in given.items()
         if ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE)
    suffix = PurePath(output).suffix.lower() if output not in (None, outfiles.STDOUT) else ""
    said = outfiles.SUFFIX_FORMAT.get(suffix, "text")
    if said != "table" and said != "text":
        raise OutputError(f"--dump-model writes the equations as Python source, and the suffix {suffix} says {said}; "
                          "name the file .py (or .txt)", path=visible(str(output)))
    target = check_target(None, output, ("text", "table"), pipe_format="text")  # .txt: the table format's suffix
    loaded, design_result = load_and_design(file, overrides)
    emit(api.model_source(loaded.design, design_result), target)


@click.command(epilog="""\b
Examples:
  gearcli modes mixer.toml
  gearcli modes mixer.toml --format json -o modes.json
  gearcli modes mixer.toml --set stage.0.shaft.stiffness_Nm_rad=2e6
  gearcli modes mixer.toml --plots figures
""")
@click.argument("file", type=str)
@io_options()
@click.option("--plots", "plots_dir", type=click.Path(), metavar="DIR",
              help="Also write the Campbell diagram campbell.png to DIR (pip install 'gearcli[plot]').")
@guarded
def modes(file: str, overrides, fmt, output, plots_dir=None) -> None:
    """Natural frequencies (clamped input and free), mode shapes, modal strain-energy shares, crossings of the mesh, shaft, torque-ripple and load-fluctuation orders."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import modes_out, serialize  # lazy: start-up time of --help

    target = check_target(fmt, output)
    if plots_dir:
        check_sweep_plots_dir(plots_dir, file, target, ())
    loaded, design_result = load_and_design(file, overrides)
    design_result = api.with_resonances(loaded.design, design_result)  # as design and simulate warn
    warn(design_result.warnings)
    analyses = api.modes(loaded.design, design_result)
    if target.fmt == "json":
        emit(serialize.to_json(serialize.with_meta(modes_out.modes_document(analyses, design_result), loaded.sha256)),
             target)
    elif target.fmt == "csv":
        emit(modes_out.modes_csv(analyses), target)
    else:
        from gearcli.io import units  # lazy: start-up time of --help

        emit_tables(modes_out.modes_tables(analyses, units.of_design_file(loaded.design)), target)
    if plots_dir:
        _write_campbell(loaded, api.campbell(loaded.design, design_result), plots_dir)



def _write_campbell(loaded, data, plots_dir: str) -> None:
    """``modes --plots``: the Campbell diagram at the drive's boundary."""
    from gearcli.io import units  # lazy: start-up time of --help
    from gearcli.io.campbell import write_campbell  # lazy: start-up time of --help

    write_figures(lambda: [write_campbell(data, units.of_design_file(loaded.design), plots_dir, loaded.design.title)],
                   plots_dir, "the modes output")


@click.command(epilog="""\b
Examples:
  gearcli init mixer.toml
  gearcli init - > mixer.toml
""")
@click.argument("file", required=False, type=str)
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def init(file: str | None, force: bool) -> None:
    """Write a commented starter design file (the seed reducer) to FILE, or to stdout ('-' or none)."""
    from gearcli import api  # lazy: start-up time of --help

    target = outfiles.check_output(file, formats=("toml",), stdout_as="'-'")
    if target.path is not None and target.path.exists() and not force:
        fail(f"{visible(file or '')}: exists; use --force to overwrite", EXIT_USAGE)
    emit(api.starter_toml(), target)
    if target.path is not None and not is_quiet():
        click.echo(f"wrote {visible(target.shown)}; try: gearcli design {visible(target.shown)}", err=True)


@click.command(epilog="""\b
Examples:
  gearcli schema -o gearcli.schema.json
  gearcli schema | python -m json.tool
""")
@outfiles.output_option("Write to FILE atomically ('-' is stdout).")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def schema(output: str | None) -> None:
    """Print the JSON Schema of the design file."""
    from gearcli import api  # lazy: start-up time of --help

    target = outfiles.check_output(output, formats=("json",))
    emit(json.dumps(api.design_file_schema(), indent=2) + "\n", target)
    # a plug-in that failed to load gave the schema none of its tables: an editor validating against it would refuse
    # the plug-in's stage type with no word why
    warn(f"plug-in {f}; the schema has none of its stage tables" for f in api.plugin_failures())

