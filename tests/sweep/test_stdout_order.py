"""A sweep without -o streams its CSV rows to stdout in point order, whatever order its workers finish them in
(a pipe reads what `-o FILE` holds: the field test's 29-point speed sweep on 2 workers printed 2500, 2525, 2550,
2575, 2700, ... 2600 rpm)."""

from __future__ import annotations

import csv
import io

from gearcli.io.sweep_file import CsvStdout

COLUMNS = ["input.speed_rpm", "status"]


def _row(i: int) -> dict:
    return {"_index": i, "input.speed_rpm": 100 * (i + 1), "status": "ok"}


def _speeds(text: str) -> list[int]:
    return [int(r["input.speed_rpm"]) for r in csv.DictReader(io.StringIO(text))]


def test_rows_finished_out_of_order_are_written_in_point_order_as_soon_as_their_turn_comes():
    out = io.StringIO()
    sink = CsvStdout(COLUMNS, {}, stream=out)
    arrival = [2, 3, 0, 5, 1, 4]  # two workers' batches, finishing crosswise
    written_after = []
    for i in arrival:
        sink.add(_row(i))
        written_after.append(len(_speeds(out.getvalue())))
    # streaming, not buffered to the end: point 0 goes out when it arrives (third), 1 pulls 2 and 3 with it
    assert written_after == [0, 0, 1, 1, 4, 6]
    sink.finish(sorted(sink.rows, key=lambda r: r["_index"]))
    assert _speeds(out.getvalue()) == [100, 200, 300, 400, 500, 600]  # point order, each row once


def test_an_interrupted_sweep_writes_the_rows_done_in_point_order():
    out = io.StringIO()
    sink = CsvStdout(COLUMNS, {}, stream=out)
    for i in (4, 1, 0):  # 2 and 3 never finished
        sink.add(_row(i))
    sink.close()
    assert _speeds(out.getvalue()) == [100, 200, 500]
