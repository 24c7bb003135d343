"""A tolerance study run without --seed says the seed it drew (stderr, stdout stays the rows): a CSV to stdout has no
comment line to record it in, so the study could not be repeated. Reference: the draws themselves, made here with
scipy from that seed as docs/sweeps.md states them (a Latin hypercube, `qmc.LatinHypercube(d, seed=default_rng(S))`,
mapped through the normal distribution's inverse CDF)."""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import numpy as np
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.stats import norm, qmc

from gearcli.cli import cli

SEED_FILE = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")
ARGS = ["sweep", SEED_FILE, "--samples", "3", "--random", "load.torque_Nm=normal(5310,200)", "--jobs", "1",
        "--set", "simulation.duration_s=0.3"]


def test_a_drawn_seed_is_said_and_repeats_the_draws():
    res = CliRunner().invoke(cli, [*ARGS, "-o", "-"])
    assert res.exit_code == 0, res.output
    found = re.search(r"--seed (\d+)", res.stderr)
    assert found, res.stderr
    assert "--seed" not in res.stdout  # the pipe gets the rows only
    seed = int(found.group(1))
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    u = qmc.LatinHypercube(d=1, seed=np.random.default_rng(seed)).random(3)[:, 0]
    assert_allclose([float(r["load.torque_Nm"]) for r in rows], norm.ppf(u, loc=5310.0, scale=200.0), rtol=1e-12)
    again = CliRunner().invoke(cli, [*ARGS, "--seed", str(seed), "-o", "-"])
    assert again.exit_code == 0 and "--seed" not in again.stderr  # given, not drawn: nothing to say
    assert [r["load.torque_Nm"] for r in csv.DictReader(io.StringIO(again.stdout))] == \
        [r["load.torque_Nm"] for r in rows]
