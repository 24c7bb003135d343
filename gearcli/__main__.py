"""``python -m gearcli`` and the ``gearcli`` console script.

The command-line module is imported inside :func:`main` so that a Ctrl-C during the start-up imports
(click, pydantic, rich; scipy later for simulate) also ends with exit code 130 and one line, never a
traceback. Once running, :func:`gearcli.cli.guarded` maps interrupts the same way. The process then ends
the ordinary way (``SystemExit``): no forked helpers, no collector switches, no early exit.
"""

import sys

INTERRUPTED = (129, 130, 143)  # SIGHUP, SIGINT, SIGTERM: gearcli has said so and removed its temporary files


def _forget_handled_interrupt() -> None:
    """CPython remembers a KeyboardInterrupt that escaped the evaluation of a source string (``exec`` of a string,
    as dataclasses and some start-up imports do), even when gearcli caught it further up, and at the end of
    ``python -m`` kills itself with SIGINT instead of exiting with gearcli's code (seen: status -2 instead of 130
    for a Ctrl-C ~0.2 s into ``simulate``, while scipy loads). Evaluating a string resets that memory (CPython's
    ``run_eval_code_obj``); the interrupt is handled, so the code gearcli chose is the process's."""
    exec("pass", {})  # noqa: S102 - a constant string: resets the interpreter's unhandled-interrupt flag


def main() -> None:
    try:
        from gearcli.io import streams  # lazy: inside main, so a Ctrl-C during the start-up imports exits 130

        streams.guard()  # stdout or stderr closed (>&-): hold their descriptors before anything opens a file
        # lazy: inside main, so a Ctrl-C during the start-up imports exits 130 (docstring)
        from gearcli.cli import main as run
    except KeyboardInterrupt:
        sys.stderr.write("gearcli: interrupted\n")
        _forget_handled_interrupt()
        sys.exit(130)
    try:
        run()
    except SystemExit as exc:
        if exc.code in INTERRUPTED:
            _forget_handled_interrupt()
        raise


if __name__ == "__main__":  # pragma: no cover
    main()
