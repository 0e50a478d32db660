"""Unit parsing at the edges: SI out, dimension checked, one-line reasons."""
import math

import pytest

from fickcam.quantities.parsing import parse_duration, to_si


@pytest.mark.parametrize("text, dimension, expected", [
    ("1.5 in", "length", 0.0381),
    ("113 degC", "temperature", 386.15),
    ("1376.7 N/in", "stiffness", 1376.7 / 0.0254),
    ("600 rpm", "angular_speed", 20 * math.pi),
    ("60 d", "time", 60 * 86400),
    ("75 deg", "angle", math.radians(75)),
    ("80 %", "percent", 80.0),
    ("60 %", "fraction", 0.6),
    ("1e-3", "fraction", 1e-3),
    (0.5, "length", 0.5),
    ("40 kJ/mol", "molar_energy", 40e3),
])
def test_values_convert_to_si(text, dimension, expected):
    assert to_si(text, dimension) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text, dimension, fragment", [
    ("3 kg", "length", "wrong dimension"),
    ("3 furlongz", "length", "unknown unit"),
    ("abc", "length", "cannot read"),
    (True, "length", "expected"),
    ([1, 2], "length", "expected a number"),
    ("nan m", "length", "cannot read"),
    (float("inf"), "length", "finite"),
])
def test_bad_values_give_one_line_reasons(text, dimension, fragment):
    with pytest.raises(ValueError, match=fragment) as info:
        to_si(text, dimension)
    assert "\n" not in str(info.value)


def test_durations_accept_compact_and_calendar_units():
    assert parse_duration("30d") == 30 * 86400
    assert parse_duration("6 months") == pytest.approx(0.5 * 365.25 * 86400)
