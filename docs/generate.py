"""Generate the reference pages that are derived from the code: ``docs/cli.md`` from every command's ``--help``
and ``docs/api.md`` from the facade ``gearcli.api`` (signatures and docstrings).

Run ``python docs/generate.py`` after changing a command's options or help text, or the facade; the test
``tests/unit/test_docs_generated.py`` fails while a committed page differs from what this script writes.
"""

from __future__ import annotations

import inspect
import re
import sys
from pathlib import Path

import click

WIDTH = 100  # the help text's wrapping width, fixed so the page does not depend on the terminal


def _help(command: click.Command, name: str, parent: click.Context | None) -> str:
    settings = {**command.context_settings, "terminal_width": WIDTH, "max_content_width": WIDTH}
    ctx = click.Context(command, info_name=name, parent=parent, **settings)
    return command.get_help(ctx)


def cli_reference() -> str:
    """Every command's ``--help``, the group's first, in the order ``gearcli --help`` lists them."""
    from gearcli.cli import cli

    root = click.Context(cli, info_name="gearcli", **{**cli.context_settings, "terminal_width": WIDTH})
    out = ["# Command-line reference", "",
           "Generated from each command's `--help` by `python docs/generate.py`; a test keeps it fresh.", "",
           "## gearcli", "", "```text", _help(cli, "gearcli", None), "```", ""]
    group = cli if isinstance(cli, click.Group) else None
    names = group.list_commands(root) if group else []
    for name in names:
        command = group.get_command(root, name) if group else None
        if command is None or command.hidden:
            continue
        out += [f"## gearcli {name}", "", "```text", _help(command, name, root), "```", ""]
        if isinstance(command, click.Group):
            sub_ctx = click.Context(command, info_name=name, parent=root, terminal_width=WIDTH)
            for sub in command.list_commands(sub_ctx):
                subcommand = command.get_command(sub_ctx, sub)
                if subcommand is not None and not subcommand.hidden:
                    out += [f"### gearcli {name} {sub}", "", "```text", _help(subcommand, sub, sub_ctx), "```", ""]
    return "\n".join(out).rstrip("\n") + "\n"


def api_reference() -> str:
    """The facade's public functions and types (``gearcli.api.__all__``): signature and docstring each."""
    from gearcli import api

    out = ["# Python API: `gearcli.api`", "",
           "The facade the command line calls; a script gets the same numbers the commands print. Generated",
           "from the module by `python docs/generate.py`; a test keeps it fresh.", "",
           "```python", "from gearcli import api", "",
           'loaded, design = api.load_and_design("configs/concrete_mixer.toml", ["simulation.duration_s=0.3"])',
           "result = api.simulate(loaded.design, design)",
           "print(result.stages[0].tangential_N.mean)   # N, the steady window's mean", "```", ""]
    doc = inspect.getdoc(api)
    if doc:
        out += [doc, ""]
    functions = [n for n in api.__all__ if inspect.isfunction(getattr(api, n))]
    types = [n for n in api.__all__ if not inspect.isfunction(getattr(api, n))]
    out += ["## Functions", ""]
    for name in functions:
        obj = getattr(api, name)
        signature = re.sub(r" at 0x[0-9a-f]+", "", str(inspect.signature(obj)))  # a default lambda's address
        out += [f"### `{name}`", "", "```python", f"def {name}{signature}", "```", "",
                inspect.getdoc(obj) or "(no docstring)", ""]
    out += ["## Types", ""]
    for name in types:
        obj = getattr(api, name)
        module = getattr(obj, "__module__", "")
        first = (inspect.getdoc(obj) or "").split("\n\n")[0].replace("\n", " ")
        out += [f"- `{name}` (`{module}`): {first}"]
    return "\n".join(out).rstrip("\n") + "\n"


PAGES = {"cli.md": cli_reference, "api.md": api_reference}


def main() -> None:
    here = Path(__file__).resolve().parent
    for page, make in PAGES.items():
        (here / page).write_text(make())
        print(f"wrote docs/{page}", file=sys.stderr)


if __name__ == "__main__":
    main()
