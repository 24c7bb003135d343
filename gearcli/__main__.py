"""``python -m gearcli`` and the ``gearcli`` console script.

The command-line module is imported inside :func:`main` so that a Ctrl-C during the start-up imports
(numpy and scipy first where the command uses them, below; then click, pydantic, rich) also ends with exit code 130
and one line, never a traceback. numpy's and scipy's imports run with signals held back
(:func:`gearcli.core.signals.deferred`; a signal is acted on once they return, within a second): a KeyboardInterrupt
raised inside a C extension's initialisation is that extension's to handle, and scipy's pybind11 modules (HiGHS,
imported by scipy.integrate through scipy.optimize) turned it into "ImportError: initialization failed" (exit 1, a
traceback) or aborted the process ("terminate called after throwing an instance of 'pybind11::error_already_set'",
exit 134), 1.4 s into a compiled ``simulate`` under load. Once running, :func:`gearcli.cli.guarded` maps interrupts the same way. The
process then ends the ordinary way (``SystemExit``): no forked helpers, no collector switches, no early exit.

A command that integrates (:data:`INTEGRATING`) imports numpy and scipy.integrate right after that guard, before
gearcli's own modules, and one that computes with numpy alone (:data:`NUMERIC`) numpy: modules it would import
anyway, from a frame next to the entry point instead of from inside gearcli's import tree and the command's body
(25-50 frames deeper). Python 3.11 keeps frames in 16 KiB chunks and frees a chunk whenever the frame at its start
returns, so an import-time loop whose calls straddle a chunk's end maps and unmaps a chunk per call
(docs/performance.md, "The one-shot commands, session 13"); the shallower the imports, the fewer such loops. The
seed's ``simulate`` over 19 caller depths: 129-3,144 unmapped chunks (median 1,041) against 1,658-14,300 (median
4,805) from inside gearcli; ``python -m gearcli design`` 54 against 990 (docs/performance.md, "The one-shot
simulate, session 15").
"""

import sys

INTERRUPTED = (129, 130, 143)  # SIGHUP, SIGINT, SIGTERM: gearcli has said so and removed its temporary files
#: the commands whose runs step scipy's solvers, and those that compute with numpy alone (module doc)
INTEGRATING = frozenset({"simulate", "report", "sweep", "life"})
NUMERIC = INTEGRATING | {"design", "modes", "schema"}


def command_word(argv: list[str]) -> str | None:
    """The command a command line names: its first argument that is not an option (gearcli's own options take no
    value), or None."""
    return next((a for a in argv if not a.startswith("-")), None)


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
        argv = sys.argv[1:]
        word = command_word(argv) if "--help" not in argv and "-h" not in argv else None
        if word in NUMERIC:
            from gearcli.core import signals  # lazy: inside main (docstring)

            with signals.deferred():  # a signal is acted on once they are imported (module doc)
                import numpy  # noqa: F401  # lazy: a command's own, imported first from here (module doc)

                if word in INTEGRATING:
                    import scipy.integrate  # noqa: F401  # lazy: a command's own, imported first from here
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
