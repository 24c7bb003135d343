"""Two registrants of one name (docs/plugins.md, "Names"): two installed plug-ins that register the same rating
standard or stage type, or a plug-in that registers a name built into gearcli, are refused with one line naming the
name and both registrants (exit 1, the plug-in guard's code, no traceback), where the last one used to win silently.
The rival plug-in (``plug_rival.py``) gives figures of its own (ISO 6336 at S_Hmin 2.0), so a silent replacement
would change the numbers; the registrant that keeps a name keeps its figures, checked against ISO's own rating of
the same file (sigma_HP = sigma_HG / S_Hmin, ISO 6336-2)."""

from __future__ import annotations

import json

import plug_extras as px
import plug_rival
import pytest
from numpy.testing import assert_allclose
from test_entry_points import MARINE, ONLY_FIXED, RATED, _install, _invoke, _json, _write

from gearcli.core import plugins
from gearcli.errors import EXIT_FAILED, PluginConflict, PluginError
from gearcli.rating import registry
from gearcli.stages import kinds

EXTRAS = "plug-in 'extras' (plug_extras:register)"


@pytest.fixture
def install(tmp_path, monkeypatch):
    """Install the extras and a rival beside them (one distribution, the extras' entry point first)."""
    def _with(rival: str) -> str:
        _install(tmp_path / "site", {"extras": "plug_extras:register", "rival": f"plug_rival:{rival}"})
        monkeypatch.syspath_prepend(str(tmp_path / "site"))
        plugins.reset()
        return f"plug-in 'rival' (plug_rival:{rival})"
    yield _with
    px.withdraw()
    registry.withdraw(plug_rival.ONLY)
    plugins.reset()


def _refused(r, *texts: str) -> str:
    """The run refused: exit 1, one line on stderr, nothing on stdout, no traceback; returns the line."""
    assert r.exit_code == EXIT_FAILED, r.output
    assert r.stdout == "" and "Traceback" not in r.output and "internal error" not in r.output
    (line,) = r.stderr.strip().splitlines()
    for text in texts:
        assert text in line, line
    return line


def test_two_plug_ins_of_one_standard_name_are_refused_naming_both(install):
    rival = install("same_standard")
    r = _invoke("design", RATED, *MARINE, "--format", "json")
    _refused(r, f'rating standard "{px.MARINE}" is registered twice, by {EXTRAS} and by {rival}')
    with pytest.raises(PluginConflict, match="registered twice"):  # the load ended there; asked again, it says so
        plugins.load()
    # the extras' standard was not replaced by the rival's S_Hmin 2.0 (the silent "last one wins" of before)
    held = registry._STANDARDS[px.MARINE]
    assert type(held.std) is px.Marine


def test_two_plug_ins_of_one_stage_type_are_refused_naming_both(install, tmp_path):
    rival = install("same_kind")
    r = _invoke("design", _write(tmp_path, ONLY_FIXED))
    _refused(r, f'stage type "{px.KIND}" (its table facet) is registered twice, by {EXTRAS} and by {rival}')
    assert kinds.facet(px.KIND, "table") is px.FixedRatioStage


def test_a_plug_in_cannot_take_the_built_in_standard_name(install):
    """A file of the built-in name never loads the plug-ins (ISO's numbers: sigma_HP = sigma_HG / 1.25, the file's
    S_Hmin); a file naming a plug-in's standard loads them, and the rival's "iso6336" is refused there."""
    rival = install("iso6336")
    iso = _json("design", RATED)["stages"][0]["rating"]["pinion"]
    assert_allclose(iso["sigma_HP_MPa"], iso["sigma_HG_MPa"] / 1.25, rtol=1e-13)
    r = _invoke("design", RATED, *MARINE, "--format", "json")
    _refused(r, f'{rival} registers rating standard "iso6336", a name built into gearcli: a plug-in cannot replace '
                "a built-in rating standard")
    from gearcli.design.iso6336 import ISO6336

    assert registry._STANDARDS["iso6336"] is ISO6336


def test_a_plug_in_cannot_provide_a_facet_of_a_built_in_stage_type(install, tmp_path):
    rival = install("planetary")
    r = _invoke("design", _write(tmp_path, ONLY_FIXED))
    _refused(r, f'{rival} registers stage type "planetary" (its model facet), a name built into gearcli')
    assert type(kinds.facet("planetary", "model")).__module__ == "gearcli.stages.model"


def test_a_registrant_may_register_its_own_name_again(install):
    """The extras loaded through their entry point, then registered again by a script importing the package: one
    registrant, no conflict, and the figures stay the extras' (sigma_HP = sigma_HG / 1.4)."""
    install("own_standard")
    first = _json("design", RATED, *MARINE)["stages"][0]["rating"]["pinion"]
    px.register()
    again = _json("design", RATED, *MARINE)["stages"][0]["rating"]["pinion"]
    assert_allclose([first["sigma_HP_MPa"], again["sigma_HP_MPa"]], [first["sigma_HG_MPa"] / 1.4] * 2, rtol=1e-13)
    rival = json.loads(_invoke("design", RATED, "--set", f"rating.standard={plug_rival.ONLY}", "--format",
                               "json").stdout)["stages"][0]["rating"]["pinion"]
    assert_allclose(rival["sigma_HP_MPa"], rival["sigma_HG_MPa"] / 2.0, rtol=1e-13)  # the rival's own name: its S_Hmin


def test_a_script_registering_a_taken_name_gets_the_error_itself():
    """Outside the entry points a registrant is its module's package: a second package's registration raises."""
    px.register()
    try:
        with pytest.raises(PluginConflict, match=f'rating standard "{px.MARINE}" is registered twice, by module '
                                                 "'plug_extras' and by module 'plug_rival'"):
            plug_rival.same_standard()
        assert type(registry._STANDARDS[px.MARINE].std) is px.Marine
    finally:
        px.withdraw()
    plug_rival.same_standard()  # withdrawn, the name is free for another registrant
    registry.withdraw(px.MARINE)


@pytest.mark.parametrize("rival, holder, title", [("iso_title", "iso6336", "ISO 6336:2006 method B"),
                                                  ("same_title", px.MARINE, px.TITLE)])
def test_a_standard_titled_as_another_is_refused(install, rival, holder, title):
    """A title names one standard: life and the rating tables find a rating's standard by it. A plug-in titled as
    gearcli's ISO 6336 (registered or not yet) had its ratings read by ISO's table rows ("internal error:
    AttributeError: ... no attribute 'K_A'"); one titled as another plug-in's, by whichever registered first."""
    who = install(rival)
    name = {"iso_title": plug_rival.RivalIsoTitle.name, "same_title": plug_rival.RivalSameTitle.name}[rival]
    r = _invoke("design", RATED, *MARINE, "--format", "table")
    _refused(r, f'rating standard "{name}" (plug_rival) is titled {title!r}, the title of rating standard "{holder}"')
    assert name not in registry._STANDARDS and who


def test_a_standard_without_a_title_is_refused_where_it_registers():
    class Untitled(plug_rival.RivalOnly):
        name, title = "test_untitled", None

    with pytest.raises(PluginError, match='rating standard "test_untitled" .*: its title is None, not a text'):
        registry.register(Untitled())
    assert "test_untitled" not in registry._STANDARDS
    registry.register(plug_rival.RivalOnly())  # the registry is left as it was: another registers freely
    registry.withdraw(plug_rival.ONLY)
