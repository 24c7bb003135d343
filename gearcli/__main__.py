"""``python -m gearcli`` and the ``gearcli`` console script.

The command-line module is imported inside :func:`main` so that a Ctrl-C during the start-up imports
(click, pydantic, rich; scipy later for simulate) also ends with exit code 130 and one line, never a
traceback. Once running, :func:`gearcli.cli.guarded` maps interrupts the same way.
"""

import os
import sys

INTERRUPTED = (129, 130, 143)  # SIGHUP, SIGINT, SIGTERM: gearcli has said so and removed its temporary files


def _freeze_heap() -> None:
    """The command is done: move every live object out of the collector's reach, so that the interpreter's
    shutdown does not walk numpy's, scipy's and numba's module graphs in its final collections (measured:
    ~0.2 s of a report's exit, with numba loaded; ~0.05 s of a one-shot simulate). Shutdown itself still
    runs: atexit handlers, module teardown, output flushing."""
    import gc

    gc.freeze()


def _leave_now(code: int) -> bool:
    """End the process now with ``code``, without the interpreter's teardown of the modules (numpy's, scipy's
    and pydantic's: ~0.02 s of a one-shot `simulate` on the 2-core reference machine, measured side by side),
    after what the teardown would do for the user: the standard streams flushed, the atexit handlers run. Only
    when nothing else runs (one Python thread) and the streams flush; else False, and the usual exit follows."""
    import atexit
    import threading

    run_exitfuncs = getattr(atexit, "_run_exitfuncs", None)
    if run_exitfuncs is None or threading.active_count() != 1:
        return False
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (OSError, ValueError):  # a closed pipe or stream: the usual exit reports it as it always did
        return False
    run_exitfuncs()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (OSError, ValueError):
        pass
    os._exit(code)


def main() -> None:
    import gc

    from gearcli.io import streams

    streams.guard()  # stdout or stderr closed (>&-): hold their descriptors before anything opens a file
    # the start-up imports (click, pydantic, numpy, scipy, numba: a million objects, no garbage) run without the
    # cyclic collector walking them again and again; a command turns it back on with
    # gearcli.cli.collector_on() once its heavy imports are in, before any work that could make garbage
    gc.disable()
    # pydantic looks for third-party plugins (entry points of every installed package) before it builds the first
    # model: ~6 ms of a one-shot command, ~25 ms of `gearcli design` (where nothing else loads importlib.metadata).
    # No plugin has a part in validating a design file; a user who sets the variable keeps their value.
    os.environ.setdefault("PYDANTIC_DISABLE_PLUGINS", "__all__")
    try:
        from gearcli.simulate import background

        background.console()  # `simulate` may run its check pass on a second core (background's doc)
        from gearcli.cli import main as run
    except KeyboardInterrupt:
        sys.stderr.write("gearcli: interrupted\n")
        sys.exit(130)
    try:
        run()
    except SystemExit as exc:
        _freeze_heap()
        if exc.code in (0, None, 1, 2) and _leave_now(exc.code or 0):  # pragma: no cover - the process is gone
            return
        if exc.code in INTERRUPTED:
            # CPython remembers a KeyboardInterrupt that passed through an interrupted import or exec even
            # when gearcli caught it, and at shutdown re-kills itself with SIGINT (exit status -2 instead of
            # 130: seen for a Ctrl-C ~0.2 s into `simulate`, while scipy loads). The interrupt is handled:
            # leave now with the code gearcli chose.
            # The atexit handlers run first: multiprocessing's joins a sweep's (already stopped) workers and
            # unlinks the pool's named semaphores, so its resource tracker has nothing to warn about.
            import atexit

            run_exitfuncs = getattr(atexit, "_run_exitfuncs", None)
            if run_exitfuncs is not None:
                run_exitfuncs()
            try:
                sys.stdout.flush()
                sys.stderr.flush()
            except (OSError, ValueError):
                pass
            os._exit(exc.code)
        raise


if __name__ == "__main__":  # pragma: no cover
    main()
