"""docs/design-file.md's type column for nested arrays (trial tr15c): a motor's `torque_speed = [[rpm, N·m], …]` read
"array of array of numberss" and "each 2 to 2 entries"; it is an array of arrays of numbers, each of 2 entries."""

from __future__ import annotations

from gearcli.config.reference import _kind, design_file_reference


def test_nested_and_fixed_length_arrays_read_as_english():
    pair = {"type": "array", "minItems": 2, "maxItems": 2, "items": {"type": "number"}}
    assert _kind(pair, {}) == ("array of numbers", "2 entries")
    table = {"type": "array", "minItems": 2, "maxItems": 32, "items": pair}
    assert _kind(table, {})[0] == "array of arrays of numbers"
    assert _kind(table, {})[1].startswith("2 to 32 entries; each 2 entries")
    text = design_file_reference()
    assert "numberss" not in text and "2 to 2 entries" not in text
    assert "| `torque_speed` | array of arrays of numbers | 2 to 32 entries; each 2 entries;" in text
