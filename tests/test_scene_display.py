"""How a loaded scene shows itself, in a terminal (``repr``) and in a notebook (HTML): each
value as its user wrote it, never the validated model's SI floats; one line per section,
cut to the width with an ellipsis; the HTML escaped."""
import re

import pytest
import yaml

import fickcam
from fickcam.scene import examples
from fickcam.scene.display import WIDTH, climate, scene_html, scene_text, segment, short


@pytest.fixture(scope="module")
def cam():
    return fickcam.load_scene(examples.path("singh2017_cam"))


def test_the_text_shows_each_section_as_written(cam):
    lines = repr(cam).splitlines()
    assert lines[0] == f"<fickcam Scene 'singh2017-cam' from {examples.path('singh2017_cam')}>"
    headings = [line.split(":")[0].strip() for line in lines[1:]]
    assert headings == ["cam", "follower", "materials", "climate", "outputs", "limits"]
    assert "  climate:   60 d at 113 degC, 80 % RH" in lines
    assert "base_circle_radius: 1.94 in" in repr(cam)  # inches as written, not 0.049276 m
    assert not re.search(r"386\.15|0\.0492", repr(cam))


def test_a_long_section_is_cut_to_the_width_with_an_ellipsis(cam):
    for line in repr(cam).splitlines()[1:]:
        assert len(line) <= 2 + 11 + WIDTH
    assert short("x" * (WIDTH + 5)) == "x" * (WIDTH - 1) + "…"
    assert short("short") == "short"


def test_a_four_bar_shows_its_linkage_and_no_cam():
    lines = repr(fickcam.load_scene(examples.path("fourbar_r914_humid"))).splitlines()
    assert lines[1].startswith("  linkage:   material: resin,")
    assert not any(line.startswith(("  cam:", "  follower:")) for line in lines)


def test_a_weather_file_climate_is_shown_as_written():
    scene = fickcam.load_scene(examples.path("eccentric_cam_greensboro"))
    assert "  climate:   reference_temperature: 23 degC, history_file: pvlib:723170TYA.CSV" in repr(scene)


@pytest.mark.parametrize("step, said", [
    ({"duration": "60 d", "temperature": "113 degC", "relative_humidity": "80 %"},
     "60 d at 113 degC, 80 % RH"),
    ({"duration": "2 h", "temperature": "40 degC", "relative_humidity": "90 %", "ramp": True},
     "ramp over 2 h at 40 degC, 90 % RH"),
    ({"duration": "1 d", "temperature": "40 degC", "relative_humidity": "90 %", "note": "x"},
     "{duration: 1 d, temperature: 40 degC, relative_humidity: 90 %, note: x}"),
])
def test_a_climate_segment_in_words(step, said):
    assert segment(step) == said


def test_segments_follow_one_another():
    data = {"environment": {"history": [
        {"duration": "30 d", "temperature": "60 degC", "relative_humidity": "85 %"},
        {"duration": "30 d", "temperature": "23 degC", "relative_humidity": "0 %"}]}}
    assert climate(data) == "30 d at 60 degC, 85 % RH; then 30 d at 23 degC, 0 % RH"


def test_the_html_is_escaped_and_holds_one_row_per_section(cam):
    page = cam._repr_html_()
    assert page.count("<tr>") == 6 and "<code>60 d at 113 degC, 80 % RH</code>" in page
    data = yaml.safe_load(examples.path("singh2017_cam").read_text())
    data["description"] = "a <b>bold</b> & risky cam"
    page = scene_html("x<y", "<dict>", data)
    assert "a &lt;b&gt;bold&lt;/b&gt; &amp; risky cam" in page
    assert "<code>x&lt;y</code> from <code>&lt;dict&gt;</code>" in page
    assert "<b>bold</b>" not in page


def test_a_scene_given_as_a_dict_says_so():
    data = yaml.safe_load(examples.path("singh2017_cam").read_text())
    assert scene_text("mine", "<dict>", data).splitlines()[0] == "<fickcam Scene 'mine' from <dict>>"
