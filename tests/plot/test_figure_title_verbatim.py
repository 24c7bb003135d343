"""A figure's title holds the design file's ``title`` as written (trial tr29c, 2026-12-01). matplotlib reads a text
with two unescaped ``$`` as mathtext: the title "Pump drive: costs $12 per_unit^2 and $3" was drawn "costs
12per_unit² and3" in italics, and "Mill $\\frac{1}{$ drive" ended ``gearcli modes --plots`` with an internal error
(ValueError from the mathtext parser, exit 1) after the table was printed. The title is plain text: the drawn string
is the file's, character for character, and its width is that of the plain characters."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

pytest.importorskip("matplotlib")

ROOT = Path(__file__).resolve().parents[2]
TITLES = ["Pump drive: costs $12 per_unit^2 and $3", "Mill $\\frac{1}{$ drive", "Ölmühle $x$ Ø 200 mm"]


def _with_title(tmp_path: Path, title: str) -> Path:
    text = (ROOT / "configs" / "conveyor.toml").read_text(encoding="utf-8")
    text = re.sub(r'(?m)^title = ".*"$', lambda _m: 'title = "' + title.replace("\\", "\\\\") + '"', text, count=1)
    path = tmp_path / "titled.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("title", TITLES, ids=["two-dollars", "broken-math", "non-ascii"])
def test_modes_plots_draw_the_title_as_written(tmp_path, title):
    design = _with_title(tmp_path, title)
    res = CliRunner().invoke(cli, ["modes", str(design), "--plots", str(tmp_path / "figs"), "--format", "json",
                                   "-o", str(tmp_path / "modes.json"), "-q"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "figs" / "campbell.png").stat().st_size > 0 and (tmp_path / "modes.json").exists()


@pytest.mark.parametrize("title", TITLES, ids=["two-dollars", "broken-math", "non-ascii"])
def test_the_drawn_title_is_the_files_characters_in_plain_text(title):
    from matplotlib.textpath import TextToPath

    from gearcli.io.figures import figure, suptitle

    fig, _ = figure(1, 1, width=11.0)
    text = f"Campbell diagram — {title}"
    suptitle(fig, text)
    fig.canvas.draw()
    drawn = fig._suptitle
    assert drawn.get_text() == text  # fits on one line: no wrap
    width = drawn.get_window_extent(fig.canvas.get_renderer()).width
    # the width of the characters laid out as plain text, by matplotlib's own text-to-path of the same font
    plain, _, _ = TextToPath().get_text_width_height_descent(text, drawn.get_fontproperties(), ismath=False)
    assert width == pytest.approx(plain * fig.dpi / 72.0, rel=0.02)
