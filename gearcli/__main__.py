"""``python -m gearcli`` and the ``gearcli`` console script.

The command-line module is imported inside :func:`main` so that a Ctrl-C during the start-up imports
(click, pydantic, rich; scipy later for simulate) also ends with exit code 130 and one line, never a
traceback. Once running, :func:`gearcli.cli.guarded` maps interrupts the same way. The process then ends
the ordinary way (``SystemExit``): no forked helpers, no collector switches, no early exit.
"""

import sys


def main() -> None:
    from gearcli.io import streams

    streams.guard()  # stdout or stderr closed (>&-): hold their descriptors before anything opens a file
    try:
        from gearcli.cli import main as run
    except KeyboardInterrupt:
        sys.stderr.write("gearcli: interrupted\n")
        sys.exit(130)
    run()


if __name__ == "__main__":  # pragma: no cover
    main()
