"""A re-run against a sweep's own -o file computes only what the file does not hold, and leaves the file an
uninterrupted run leaves (docs/sweeps.md, "-o FILE is resumable"), also where the file holds a point otherwise than
``--vary`` gave it, and where the file is another version's.

- A text value is written to a CSV cell with its formula escape and without ``#`` (``=b`` as ``'=b``, ``#1`` as
  ``No.1``): the resume read such a cell as another value than the point's, so every such point was computed again
  on every re-run (a 4-point sweep of texts ran 3 of its points again, each time).
- A file whose rows lack a column this version writes (a file of an earlier gearcli, or a header edited by hand)
  lent those rows as done: the resumed file held empty cells in that column. Its points are computed again.

The reference is the uninterrupted run: the same rows, cell for cell (``wall_s`` aside), and which points ran.
"""

from __future__ import annotations

import csv
import io
import json

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep import worker
from tests.sweep.test_sweep_resonance import SCENE

TITLES = ["#1 run", "=b", "-c", "plain"]
ARGS = ["--vary", "title=" + ",".join(TITLES), "--set", "simulation.duration_s=0.1", "--jobs", "1"]
REAL = worker._evaluate


def _rows(path):
    text = path.read_text()
    if path.suffix == ".json":
        return json.loads(text)["rows"]
    return list(csv.DictReader(io.StringIO(text.partition("\n")[2])))


def _plain(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


@pytest.fixture
def counted(monkeypatch):
    """The indices of the points evaluated (the real evaluation, counted)."""
    calls: list[int] = []

    def evaluate(evaluator, scene_, point, prev, check=False):
        calls.append(point.index)
        return REAL(evaluator, scene_, point, prev, check)

    monkeypatch.setattr(worker, "_evaluate", evaluate)
    return calls


def _sweep(scene, out):
    return CliRunner().invoke(cli, ["sweep", str(scene), *ARGS, "-o", str(out)])


@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_a_complete_file_of_text_values_runs_no_point_again(tmp_path, counted, suffix):
    scene, out = tmp_path / "scene.toml", tmp_path / f"texts{suffix}"
    scene.write_text(SCENE)
    assert _sweep(scene, out).exit_code == 0
    assert counted == [0, 1, 2, 3]
    before = _rows(out)
    written = [r["title"] for r in before]
    assert written == (["No.1 run", "'=b", "'-c", "plain"] if suffix == ".csv" else TITLES)
    counted.clear()
    res = _sweep(scene, out)
    assert res.exit_code == 0, res.output
    assert counted == []  # every point is in the file: none computed again
    assert _rows(out) == before  # wall_s too: the rows are the file's own


def test_rows_without_a_column_of_this_version_are_computed_again(tmp_path, counted):
    scene, full, old = tmp_path / "scene.toml", tmp_path / "full.csv", tmp_path / "old.csv"
    scene.write_text(SCENE)
    assert _sweep(scene, full).exit_code == 0
    reference = _plain(_rows(full))
    assert all(r["stage1_runup_factor"] not in ("", None) for r in reference)
    head, _, body = full.read_text().partition("\n")
    table = list(csv.reader(io.StringIO(body)))
    gone = table[0].index("stage1_runup_factor")  # the file an earlier version wrote, without that column
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows([r[:gone] + r[gone + 1:] for r in table])
    old.write_text(head + "\n" + buf.getvalue())
    counted.clear()
    res = _sweep(scene, old)
    assert res.exit_code == 0, res.output
    assert counted == [0, 1, 2, 3]
    assert _plain(_rows(old)) == reference
