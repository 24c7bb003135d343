"""An option that cannot act in the command it is given to says so (a warning, exit 0), as `life --classes`
without `--series` is refused: `report --quick` skips the accuracy study that `--rtols` and `--accuracy` set, and a
sweep without `--random` draws no samples for `--seed` and `--sampling` to shape. Before, they were silently
ignored."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")


def _warnings(res) -> list[str]:
    return [line for line in res.stderr.splitlines() if "no effect" in line]


@pytest.mark.parametrize(("extra", "named"), [
    (["--rtols", "1e-4,1e-6"], ["--rtols"]),
    (["--accuracy", "1e-3", "--rtols", "1e-5"], ["--accuracy", "--rtols"]),
    ([], []),
    (["--accuracy", "1e-4"], ["--accuracy"]),  # given, though equal to the default: the user asked for it
])
def test_report_quick_says_the_study_options_do_nothing(extra, named):
    res = CliRunner().invoke(cli, ["report", SEED, "--quick", "--format", "json", *extra])
    assert res.exit_code == 0, res.stderr
    said = _warnings(res)
    assert [w.split()[1] for w in said] == named, said
    assert all(w.startswith("warning: ") and "--quick" in w for w in said)


def test_report_without_quick_says_nothing_of_them(monkeypatch):
    """The options act there (the ladder runs): no warning. The study itself is replaced by a stub here."""
    from gearcli import api

    seen = {}

    def report_file(loaded, design, **kw):
        seen.update(kw)
        raise SystemExit(0)

    monkeypatch.setattr(api, "report_file", report_file)
    res = CliRunner().invoke(cli, ["report", SEED, "--rtols", "1e-4,1e-6", "--format", "json"])
    assert res.exit_code == 0 and not _warnings(res) and seen["rtols"] == (1e-4, 1e-6)


@pytest.mark.parametrize(("extra", "named"), [
    (["--seed", "3"], ["--seed"]),
    (["--sampling", "mc", "--seed", "1"], ["--seed", "--sampling"]),
    ([], []),
])
def test_sweep_without_random_says_seed_and_sampling_do_nothing(extra, named):
    res = CliRunner().invoke(cli, ["sweep", SEED, "--vary", "input.speed_rpm=600", "--jobs", "1", *extra])
    assert res.exit_code == 0, res.stderr
    said = _warnings(res)
    assert sorted(w.split()[1] for w in said) == sorted(named), said
    assert res.stdout.count("\n") == 2  # the header and the one row: the sweep ran as before


def test_sweep_with_random_takes_them_silently():
    res = CliRunner().invoke(cli, ["sweep", SEED, "--random", "stage.0.backlash_mm=uniform(0.1,0.2)", "--samples", "1",
                                   "--seed", "3", "--sampling", "mc", "--jobs", "1"])
    assert res.exit_code == 0, res.stderr
    assert not _warnings(res)


@pytest.mark.parametrize(("fmt", "why"), [("csv", "always has them"),
                                         ("table", "shows the statistics, never the series"), ("json", None)])
def test_simulate_series_outside_json_says_it_does_nothing(fmt, why):
    """``--series`` adds the series to the JSON output only (its help says so): with CSV (which always has them) or
    a table it was silently ignored."""
    scene = str(Path(__file__).resolve().parents[2] / "configs" / "extreme" / "one_stage.toml")
    res = CliRunner().invoke(cli, ["simulate", scene, "--series", "--format", fmt,
                                   "--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50"])
    assert res.exit_code == 0, res.stderr
    if why is None:
        assert _warnings(res) == [] and '"series"' in res.stdout
    else:
        assert _warnings(res) == [f"warning: --series adds the time series to the JSON output; the {fmt} output "
                                  f"{why}: it has no effect"]
