"""The design file's default tables (``[contact]``, ``[simulation]``, a stage's ``basic_rack``) are made without
validation at import (``model_construct``: no validator built before a file is read); they are what validating an
empty table gives, field for field and in the fields a file set (none), and a file without them gets them."""

from __future__ import annotations

import pytest

from gearcli.config.schema import Contact, DesignFile, Simulation
from gearcli.config.stage_tables import BasicRack, PlanetaryStage, Stage


@pytest.mark.parametrize(("owner", "field", "table"), [(DesignFile, "contact", Contact),
                                                       (DesignFile, "simulation", Simulation),
                                                       (Stage, "basic_rack", BasicRack),
                                                       (PlanetaryStage, "basic_rack", BasicRack)])
def test_a_default_table_is_the_validated_empty_table(owner, field, table):
    default = owner.model_fields[field].default
    validated = table.model_validate({})
    assert type(default) is table
    assert default == validated
    assert default.model_dump() == validated.model_dump()
    assert default.model_fields_set == validated.model_fields_set == set()


def test_a_file_without_them_gets_the_defaults():
    from pathlib import Path

    from gearcli.config.load import load_design

    path = Path(__file__).resolve().parents[2] / "configs" / "wind_turbine_allowances.toml"  # no such table
    text = path.read_text()
    assert "[simulation]" not in text and "[contact]" not in text and "basic_rack" not in text
    cfg = load_design(str(path)).design
    # the schema's defaults, as docs/design-file.md lists them
    assert (cfg.simulation.method, cfg.simulation.steps, cfg.simulation.duration_s) == ("auto", 2000, 0.5)
    assert (cfg.contact.stiffness, cfg.contact.exponent, cfg.contact.damping_Ns_mm) == ("iso6336", 1.5, 50.0)
    rack = cfg.stage[0].basic_rack
    assert (rack.addendum, rack.dedendum, rack.root_radius) == (1.0, 1.25, 0.38)
