"""``--random`` on a key that takes no real number is refused before any point runs (exit 2, naming ``--random`` and
the key), with words true of the key: a count, a choice, a text and a flag alike (a text or a flag was told it "is a
whole number or a choice")."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


@pytest.mark.parametrize("key", ["stage.0.pinion.teeth", "load.speed_exponent", "title", "contact.time_varying",
                                 "simulation.method"])
def test_a_key_without_real_numbers_is_refused_in_words_true_of_it(key, tmp_path):
    out = tmp_path / "rows.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SEED), "--random", f"{key}=uniform(1, 2)", "--samples", "3",
                                   "--jobs", "1", "-o", str(out)])
    assert res.exit_code == 2, res.output
    text = res.output + (res.stderr if res.stderr_bytes is not None else "")
    assert "--random" in text and key in text and "takes no real number" in text, text
    assert "Traceback" not in text and not out.exists()
