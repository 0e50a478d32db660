"""A drawn link's swelling stress (``linkage.elastic`` with a drawn link: the plane model's
moisture over its drawn planform, through the thickness with the exact sheet, on a mesh
of the drawn outline with every hole) and its size for the plausibility readings (its
planform's area over its perimeter, a thin web for what it is)."""
import numpy as np
import pytest
import yaml

import fickcam
from fickcam.linkage.drawn import in_plane_half_size
from fickcam.linkage.mechanism import LinkageMechanism
from test_drawing_links import PINS, bar_outline, mm, scene


def elastic(path):
    data = yaml.safe_load(path.read_text())
    data["linkage"]["elastic"] = True
    data["linkage"]["aged_length"] = "mean_strain"
    path.write_text(yaml.safe_dump(data, default_flow_style=None))
    return path


@pytest.mark.slow  # two elastic runs of a four-bar (about 25 s)
def test_a_drawn_bar_with_two_bosses_gives_the_parametric_link_s_swelling_stress(tmp_path):
    """R914 crank at 10 and 30 d (60 °C / 85 % RH). Measured (2026-11-29): the drawn bar's
    largest tension, compression and Tsai-Wu index within 0.22 % of the parametric link's;
    the parametric link's own change from its mesh (1/100 of its extent) to one twice as
    fine is up to 0.59 %: the tolerance is that mesh error, twice over. At 0 d, dry, both
    are stress-free to round-off."""
    drawn = fickcam.run(fickcam.load_scene(elastic(scene(tmp_path, outline=mm(bar_outline()),
                                                         holes=PINS))))
    made = fickcam.run(fickcam.load_scene(elastic(scene(tmp_path, "made"))))
    for name in ("swelling_stress_tensile", "swelling_stress_compressive", "failure_index"):
        a, b = (np.asarray(ds[name].sel(part="crank")) for ds in (drawn, made))
        assert np.all(np.abs(a[1:] - b[1:]) <= 1.2e-2 * np.abs(b[1:])), (name, a, b)
        assert abs(a[0]) <= 1e-9 * np.max(np.abs(b)), name
    assert np.all(np.isnan(np.asarray(drawn["failure_index"].sel(part="frame"))))  # steel


def test_a_drawn_link_s_size_is_its_web_not_the_section_s_width(tmp_path):
    """A strip 4 mm wide (pins of 1 mm radius) in a 10 mm thick plate, beside bars 20 mm
    wide: the drawn link is judged by its area over its perimeter, about 2 mm."""
    length, half, radius = 0.1, 0.002, 0.001
    outline = [(-0.005, -half), (length + 0.005, -half), (length + 0.005, half), (-0.005, half)]
    holes = [{"centre": ["0 mm", "0 mm"], "radius": "1 mm"},
             {"centre": ["100 mm", "0 mm"], "radius": "1 mm"}]
    loaded = fickcam.load_scene(scene(tmp_path, outline=mm(outline), holes=holes))
    linkage = loaded.mechanisms[0]
    sizes = LinkageMechanism.absorber_sizes(linkage.section, linkage.drawn)
    area = (length + 0.01) * 2 * half - 2 * np.pi * radius ** 2
    perimeter = 2 * (length + 0.01 + 2 * half) + 2 * 2 * np.pi * radius
    # the pins' polygons within the chord tolerance: their share of A and P by (2 pi^2/3)/n^2
    assert in_plane_half_size(linkage.drawn["crank"]) == pytest.approx(area / perimeter, rel=1e-4)
    assert sizes == [("links", "resin", 0.005),
                     ("crank", "resin", in_plane_half_size(linkage.drawn["crank"]))]
    assert LinkageMechanism.absorber_sizes(linkage.section) == [("links", "resin", 0.005)]
