"""``python -m gearcli`` and the ``gearcli`` console script.

The command-line module is imported inside :func:`main` so that a Ctrl-C during the start-up imports
(numpy, scipy and pydantic first where the command uses them, below; then click, rich) also ends with exit code 130
and one line, never a traceback. Those first imports run with signals held back
(:func:`gearcli.core.signals.deferred`; a signal is acted on once they return, within a second): a KeyboardInterrupt
raised inside a C extension's initialisation is that extension's to handle, and scipy's pybind11 modules (HiGHS,
imported by scipy.integrate through scipy.optimize) turned it into "ImportError: initialization failed" (exit 1, a
traceback) or aborted the process ("terminate called after throwing an instance of 'pybind11::error_already_set'",
exit 134), 1.4 s into a compiled ``simulate`` under load. Once running, :func:`gearcli.cli.guarded` maps interrupts
the same way. The process then ends the ordinary way (``SystemExit``): no forked helpers, no collector switches, no early exit.

A command that reads a design file (:data:`NUMERIC`) imports the libraries it loads anyway right after that guard,
before gearcli's own modules: numpy; for one that integrates (:data:`INTEGRATING`) numpy's ``f2py`` and ``ma`` and
scipy.integrate next (scipy's array-API layer star-imports numpy, which loads numpy's lazy submodules: ``f2py``'s
crackfortran compiles ~70 regular expressions at import, ``ma.core`` builds ~100 function wrappers); then pydantic's
model machinery (``pydantic.main``, ``pydantic.types`` with annotated_types), last because the typing_extensions it
imports makes every later generic alias dearer. They load from a frame next to the entry point (5-27 frames deep)
instead of from inside gearcli's import tree and scipy's (55-85). Python 3.11 keeps frames in 16 KiB chunks and
frees a chunk whenever the frame at its start returns, so an import-time loop whose calls straddle a chunk's end
maps and unmaps a chunk per call, a page fault each (docs/performance.md, "The one-shot commands, session 13"); the
shallower such loops run, the fewer straddle one. The seed's ``simulate`` over 19 caller depths: 82-2,180 unmapped
chunks (median 319) against 585-8,937 (median 1,623) with numpy and scipy.integrate alone imported here and
1,658-14,300 from inside gearcli (docs/performance.md, "The one-shot simulate, session 17").
"""

import os
import sys

INTERRUPTED = (129, 130, 143)  # SIGHUP, SIGINT, SIGTERM: gearcli has said so and removed its temporary files
#: the commands whose runs step scipy's solvers, and those that compute with numpy alone (module doc)
INTEGRATING = frozenset({"simulate", "report", "sweep", "life"})
NUMERIC = INTEGRATING | {"design", "modes", "schema"}
#: the libraries those commands load anyway, imported first from the entry point (module doc); pydantic's last:
#: typing_extensions, which it imports, replaces ``typing._collect_parameters`` with a slower one for every generic
#: alias numpy and scipy would make after it
NUMERIC_FIRST = ("numpy",)
INTEGRATING_FIRST = ("numpy.f2py", "numpy.ma", "scipy.integrate")
MODELS_FIRST = ("pydantic.main", "pydantic.types")


def command_word(argv: list[str]) -> str | None:
    """The command a command line names: its first argument that is not an option (gearcli's own options take no
    value), or None."""
    return next((a for a in argv if not a.startswith("-")), None)


def first_imports(word: str | None) -> tuple[str, ...]:
    """The modules a command imports first, in order: its libraries' heaviest import-time loops, run next to the
    entry point (module doc); none for another command or a request for help."""
    if word not in NUMERIC:
        return ()
    return NUMERIC_FIRST + (INTEGRATING_FIRST if word in INTEGRATING else ()) + MODELS_FIRST


def _forget_handled_interrupt() -> None:
    """CPython remembers a KeyboardInterrupt that escaped the evaluation of a source string (``exec`` of a string,
    as dataclasses and some start-up imports do), even when gearcli caught it further up, and at the end of
    ``python -m`` kills itself with SIGINT instead of exiting with gearcli's code (seen: status -2 instead of 130
    for a Ctrl-C ~0.2 s into ``simulate``, while scipy loads). Evaluating a string resets that memory (CPython's
    ``run_eval_code_obj``); the interrupt is handled, so the code gearcli chose is the process's."""
    exec("pass", {})  # noqa: S102 - a constant string: resets the interpreter's unhandled-interrupt flag


#: the BLAS thread counts a Dask worker's nanny sets to 1 before it starts (distributed's ``pre-spawn-environ``):
#: scipy's Radau factorises through OpenBLAS, whose results depend on its thread count (a Python-engine Radau run
#: of configs/planetary_stage.toml: 6,561 evaluations on 1 thread, 6,433 on 2, its mean F_t 8e-8 apart), so a sweep's
#: rows on a cluster would differ from ``--jobs``' (docs/sweeps.md). Set before numpy loads; a value the user set wins.
BLAS_THREADS = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")


def one_blas_thread() -> None:
    """Run BLAS on one thread, as a Dask worker does (:data:`BLAS_THREADS`), unless the user chose a count."""
    for name in BLAS_THREADS:
        os.environ.setdefault(name, "1")


def main() -> None:
    one_blas_thread()  # before any import of numpy (the process's BLAS reads it once, when it loads)
    try:
        from gearcli.io import streams  # lazy: inside main, so a Ctrl-C during the start-up imports exits 130

        streams.guard()  # stdout or stderr closed (>&-): hold their descriptors before anything opens a file
        argv = sys.argv[1:]
        word = command_word(argv) if "--help" not in argv and "-h" not in argv else None
        first = first_imports(word)
        if first:
            from gearcli.core import signals  # lazy: inside main (docstring)

            with signals.deferred():  # a signal is acted on once they are imported (module doc)
                for name in first:
                    __import__(name)  # lazy: a command's own libraries, imported first from here (module doc)
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
