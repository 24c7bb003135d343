"""An interrupted pool whose worker was ending mid-way through sending its rows: the sweep ends, it does not hang.

A Ctrl-C or SIGTERM while a worker writes its task's rows (a message larger than the pipe holds, written in parts)
ended that worker with half the message in the result pipe. The pool's manager thread, reading it, waited for the
rest for ever; ``shutdown(wait=True)`` joined that thread, so the sweep hung with its finished rows unwritten (seen:
a SIGTERM'd sweep of 241 points still there 11 minutes later, 0 % CPU). The scenario runs in a child process, so
that a regression fails instead of hanging the test run; the half message is written on the pipe by the test
(the same state as a worker ended mid-send, which a real interrupt hits only now and then).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forkserver, POSIX pipes")

CHILD = textwrap.dedent("""
    import multiprocessing, os, struct, threading, time
    from concurrent.futures import ProcessPoolExecutor

    from gearcli.sweep.execute import _stop_workers


    def square(i):
        return i * i


    if __name__ == "__main__":
        pool = ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context("forkserver"))
        assert pool.submit(square, 3).result() == 9  # the workers and the pool's manager thread are running
        # what a worker ended mid-send leaves: a message's length header and part of its body (deterministic here:
        # written on the pipe's write end, which the parent holds as every worker does)
        writer = pool._result_queue._writer
        os.write(writer.fileno(), struct.pack("!i", 100_000) + b"half a message")
        time.sleep(0.5)  # the manager thread reads the header and waits for the rest
        _stop_workers(pool)
        joiner = threading.Thread(target=pool.shutdown, kwargs={"wait": True, "cancel_futures": True}, daemon=True)
        joiner.start()
        joiner.join(20)
        print("joined" if not joiner.is_alive() else "hung", flush=True)
        if joiner.is_alive():
            os._exit(3)  # the interpreter's exit would join the stuck thread for ever
""")



def test_stopped_workers_leave_no_pool_thread_waiting_for_the_rest_of_a_message(tmp_path):
    script = tmp_path / "child.py"
    script.write_text(CHILD, encoding="utf-8")
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=90)
    assert done.stdout.strip() == "joined", (done.stdout, done.stderr[-2000:])
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-2000:]
