"""report --plots: spectrum.png and speeds.png show the run, checked against the simulate CSV of the same file.

The spectrum is recomputed here from the CSV's F_t series over the JSON's steady window (least-squares line
removed, numpy's Hann window, |rfft| * 2 / sum(w), the textbook single-sided amplitude) and compared with the
figure's curve; its mesh line lies at z n / 60 from the teeth (stage 1: 23 x 1200 / 60 = 460 Hz; stage 2:
19 x 1200 x 23/67 / 60 = 130.45 Hz) and its largest line at a mesh harmonic. speeds.png's curves are the CSV's
shaft speeds in the file's unit (rpm), its dashed design lines the kinematic speeds 1200 x (23/67)^k.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

from gearcli.cli import cli  # noqa: E402

SCENE = Path(__file__).parent / "data" / "two_stage_duty.toml"
SHORT = ("--set", "simulation.duration_s=0.25", "--set", "simulation.steps=2500")
MESH_HZ = {1: 23 * 1200 / 60, 2: 19 * 1200 * 23 / 67 / 60}
SHAFT_RPM = (1200.0, 1200 * 23 / 67, 1200 * 23 / 67 * 19 / 61)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("report")
    runner = CliRunner()
    res = runner.invoke(cli, ["simulate", str(SCENE), *SHORT, "-q", "-o", str(tmp / "run.csv")])
    assert res.exit_code == 0, res.output
    with (tmp / "run.csv").open() as f:
        table = list(csv.DictReader(line for line in f if not line.startswith("#")))
    series = {k: np.array([float(r[k]) for r in table]) for k in table[0]}
    from gearcli.io import plots

    figs: dict = {}
    real = plots._save
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(plots, "_save", lambda fig, path: figs.setdefault(path.name, fig) and real(fig, path))
        res = runner.invoke(cli, ["report", str(SCENE), *SHORT, "--quick", "-q", "--format", "json",
                                  "--plots", str(tmp / "p")])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp / "p").iterdir()) == ["campbell.png", "mesh_forces.png", "spectrum.png",
                                                             "speeds.png"]
    return series, json.loads(res.stdout), figs


def test_spectrum_is_the_fft_of_the_simulated_force(run):
    series, doc, figs = run
    t = series["time_s"]
    for ax, dyn in zip(figs["spectrum.png"].axes, doc["dynamics"], strict=True):
        k = dyn["stage"]
        lo, hi = dyn["spectrum"]["window_s"]
        keep = (t >= lo - 1e-9) & (t <= hi + 1e-9)
        tt, x = t[keep], series[f"stage{k}_tangential_N"][keep]
        x = x - np.polyval(np.polyfit(tt - tt[0], x, 1), tt - tt[0])
        w = np.hanning(x.size)
        amp = np.abs(np.fft.rfft(w * x)) * 2 / w.sum()
        f = np.fft.rfftfreq(x.size, (tt[-1] - tt[0]) / (x.size - 1))
        (curve,) = [ln for ln in ax.get_lines() if ln.get_label() == "|F_t| amplitude"]
        assert np.asarray(curve.get_xdata()) == pytest.approx(f[1:], rel=1e-9)
        drawn = np.nan_to_num(np.asarray(curve.get_ydata(), float))
        assert drawn == pytest.approx(amp[1:], abs=1e-6 * amp.max())  # the CSV's 10 digits
        (mesh,) = [ln for ln in ax.get_lines() if ln.get_label().startswith("mesh ")]
        assert mesh.get_xdata()[0] == pytest.approx(MESH_HZ[k], rel=1e-12)
        top = f[1 + np.argmax(amp[1:])]
        harmonics = [h * m for m in MESH_HZ.values() for h in (1, 2, 3)]
        assert min(abs(top - h) for h in harmonics) <= f[1]  # the largest line is a mesh harmonic, within a bin


def test_speeds_are_the_simulated_shaft_speeds_and_the_kinematic_design(run):
    series, _, figs = run
    fig = figs["speeds.png"]
    for i, design in enumerate(SHAFT_RPM, start=1):
        ax = next(a for a in fig.axes if a.get_title(loc="left").startswith(f"shaft {i} ("))
        assert ax.get_ylabel() == f"shaft {i}\n[rpm]"
        (sim,) = [ln for ln in ax.get_lines() if ln.get_label() == "simulated"]
        assert np.asarray(sim.get_ydata()) == pytest.approx(series[f"shaft{i}_speed_rpm"], rel=1e-8, abs=1e-6)
        (line,) = [ln for ln in ax.get_lines() if ln.get_label().startswith("design ")]
        assert line.get_ydata()[0] == pytest.approx(design, rel=1e-12)


def test_mesh_forces_static_lines_are_torque_over_radius(run):
    """The dashed static F_t of mesh_forces.png, by hand: stage 1 the input torque 1500 N·m / i over the pinion's
    pitch radius m_n z / (2 cos β) = 4 x 23 / (2 cos 15°) mm; stage 2 the output torque over the gear's 6 x 61 /
    (2 cos 13°) mm (no losses in this file). The simulated trace is the CSV's F_t."""
    series, _, figs = run
    i = (67 / 23) * (61 / 19)
    hand = {1: 1500.0 / i / (4 * 23 / (2 * np.cos(np.radians(15.0))) * 1e-3),
            2: 1500.0 / (6 * 61 / (2 * np.cos(np.radians(13.0))) * 1e-3)}
    fig = figs["mesh_forces.png"]
    for k, force in hand.items():
        ax = next(a for a in fig.axes if a.get_title(loc="left") == f"stage {k}: tangential mesh force")
        (static,) = [ln for ln in ax.get_lines() if ln.get_label().startswith("static F_t")]
        assert static.get_ydata()[0] == pytest.approx(force, rel=1e-9)
        (sim,) = [ln for ln in ax.get_lines() if ln.get_label() == "F_t simulated"]
        assert np.asarray(sim.get_ydata()) == pytest.approx(series[f"stage{k}_tangential_N"], rel=1e-8, abs=1e-6)
