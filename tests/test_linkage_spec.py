"""The scene's linkage section: units, defaults, refusals; and the linkage over
ageing as the run assembles it (class change warnings, assembly gaps, link growth)."""
from types import SimpleNamespace

import numpy as np
import pytest
from pydantic import ValidationError

from fickcam.linkage import JOINTS, LinkageSection
from fickcam.linkage.mechanism import LINKS, linkage_response

SECTION = {
    "material": "resin", "frame_material": "steel",
    "crank": "115 mm", "coupler": "120 mm", "rocker": "120 mm", "frame": "120 mm",
    "coupler_point": {"distance": "60 mm", "angle": "30 deg"},
    "section": {"width": "20 mm", "thickness": "10 mm", "boss_outer_radius": "12 mm",
                "boss_inner_radius": "4 mm"},
    "crank_speed": "100 rpm", "assembly": "open",
}


def section(**changes):
    data = {**SECTION, **changes}
    return LinkageSection.model_validate(data)


def reason(**changes) -> str:
    with pytest.raises(ValidationError) as info:
        section(**changes)
    return str(info.value)


def test_section_parses_units_to_si_with_documented_defaults():
    s = section()
    assert s.crank == pytest.approx(0.115) and s.crank_speed == pytest.approx(100 * 2 * np.pi / 60)
    assert s.coupler_point.angle == pytest.approx(np.radians(30))
    assert (s.gravity, s.crank_angular_acceleration, s.rocker_load_torque) == (False, 0.0, 0.0)
    assert s.centre_of_mass == (0.5, 0.5, 0.5)
    assert section(rocker_load_torque="2 N*m", crank_angular_acceleration="3 rad/s^2").rocker_load_torque == 2.0


@pytest.mark.parametrize("changes, fragment", [
    ({"frame": "1000 mm"}, "cannot assemble at any crank angle"),
    ({"crank": "-5 mm"}, "positive"),
    ({"assembly": "sideways"}, "open"),
    ({"colour": "red"}, "Extra inputs"),
    ({"crank": "20 mm"}, "bosses would overlap"),
    ({"section": {**SECTION["section"], "boss_inner_radius": "12 mm"}}, "smaller than boss_outer"),
    ({"section": {**SECTION["section"], "width": "30 mm"}}, "wider than its bosses"),
    ({"rocker_load_torque": "2 kg"}, "torque"),
    ({"centre_of_mass": [0.5, 1.5, 0.5]}, "between 0 and 1"),
])
def test_section_refuses_what_cannot_be_a_four_bar_with_a_reason(changes, fragment):
    assert fragment in reason(**changes)


def history(strain, moisture=0.0, density=1290.0):
    n = len(strain)
    return SimpleNamespace(
        part=SimpleNamespace(material=SimpleNamespace(dry_density=density)),
        state={"strain_longitudinal": np.asarray(strain, float),
               "strain_transverse": np.asarray(strain, float),
               "strain_through_thickness": np.asarray(strain, float),
               "moisture_content": np.broadcast_to(np.asarray(moisture, float), (n,))})


def test_ageing_that_lengthens_the_crank_removes_full_rotation_and_is_warned():
    """Singh & Sanyal 2016 case 2 (a = 115, b = c = d = 120 mm) is 5 mm from its Grashof
    limit: a crank grown by 6 % makes it non-Grashof, so the crank cannot turn through
    ~180 deg."""
    times = np.array([0.0, 86400.0, 10 * 86400.0])
    histories = {"crank": history([0.0, 0.01, 0.06], [0.0, 1.0, 2.0]), "coupler": history([0, 0, 0]),
                 "rocker": history([0, 0, 0]), "frame": history([0, 0, 0], density=7850.0)}
    angles = np.radians(np.arange(0, 360, 2.0))
    result = linkage_response(section(), histories, times, angles, np.ones(3, bool))
    v = result.variables
    assert list(v["grashof_class"]) == ["crank-rocker", "crank-rocker", "non-Grashof"]
    assert v["coupler_angle"].shape == (3, angles.size)
    assert v["joint_force_x"].shape == (3, len(JOINTS), angles.size)
    assert v["link_length"].shape == (3, len(LINKS))
    assert v["link_length"][2, 0] == pytest.approx(0.115 * 1.06)
    assert v["link_mass"][1, 0] > v["link_mass"][0, 0] and v["link_inertia"][2, 0] > v["link_inertia"][0, 0]
    assert np.isfinite(v["rocker_angle"][:2]).all() and np.isnan(v["rocker_angle"][2]).any()
    text = "\n".join(result.notices)
    assert "no longer make a full revolution" in text
    assert "changed from crank-rocker to non-Grashof" in text
    assert "cannot assemble for crank angles" in text and "at t = 10" in text
    assert "toggle" in text


def test_invalid_ageing_times_stay_nan():
    times = np.array([0.0, 86400.0])
    histories = {name: history([0.0, 0.01]) for name in LINKS}
    result = linkage_response(section(), histories, times, np.radians(np.arange(0, 360, 10.0)),
                              np.array([True, False]))
    assert np.isnan(result.variables["input_torque"][1]).all()
    assert result.variables["grashof_class"][1] == ""


def test_fourbar_response_returns_exactly_the_schema_linkage_variables():
    from fickcam.linkage import FourBarDesign, FourBarState, fourbar_response
    from fickcam.schema import VARIABLES

    v = fourbar_response(FourBarDesign(0.1, 0.16, 0.16, 0.2), FourBarState((0.1, 0.16, 0.16, 0.2)),
                         np.radians(np.arange(0, 360, 30.0))).variables
    per_state = {"link_length", "link_mass", "link_inertia"}  # added by the ageing loop
    linkage = {n for n, var in VARIABLES.items()
               if var.section == "linkage" and "time" in var.dims} - per_state  # not the design rows
    assert set(v) == linkage
    sizes = {"crank_angle": 12, "link": 4, "joint": 4}
    for name in linkage:
        assert np.shape(v[name]) == tuple(sizes[d] for d in VARIABLES[name].dims[1:]), name
