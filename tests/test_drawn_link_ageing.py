"""A drawn link's aged length from its moisture field (the example dog-bone crank, acetal,
a web 8 mm wide between bosses of 14 mm radius): its displaced pins' distance is the mean
strain's L (1 + eps) plus the shift of the field's unevenness, which converges with the
mesh, parts the pins further while the thin web is wetter than the mean, and vanishes at
saturation."""
import numpy as np
import pytest
import yaml

pytest.importorskip("ezdxf")

import fickcam  # noqa: E402
from fickcam.elastic.displacement import field_pin_shifts  # noqa: E402
from fickcam.elastic.nodal import NodalField  # noqa: E402
from fickcam.elastic.parts import sheet_profile  # noqa: E402
from fickcam.elastic.swelling import plane_nodal_moisture  # noqa: E402
from fickcam.scene import examples  # noqa: E402
from fickcam.simulation.ageing import age_part  # noqa: E402
from fickcam.simulation.options import RunOptions  # noqa: E402
from fickcam.simulation.planning import climate_seen  # noqa: E402
from fickcam.simulation.times import ageing_times  # noqa: E402

DAY = 86400.0


@pytest.fixture(scope="module")
def dogbone():
    return fickcam.load_scene(examples.path("fourbar_acetal_dogbone"))


def test_a_drawn_link_s_field_is_kept_unless_the_scene_asks_for_the_mean_strain(dogbone, tmp_path):
    assert dogbone.field_parts == {"crank"} and not dogbone.elastic_parts
    copied = examples.copy_to(tmp_path, ["fourbar_acetal_dogbone"])
    path = next(p for p in copied if p.suffix == ".yaml")
    data = yaml.safe_load(path.read_text())
    data["linkage"]["aged_length"] = "mean_strain"
    path.write_text(yaml.safe_dump(data))
    assert fickcam.load_scene(path).field_parts == frozenset()


@pytest.fixture(scope="module")
def crank(dogbone):
    """(link, moisture at the nodes of the plane model's mesh, expansion, the ageing times
    [s]) of the crank."""
    times = ageing_times(dogbone, dogbone.environment)
    part = next(p for p in dogbone.parts if p.name == "crank")
    seen = climate_seen(dogbone, times, [part])
    history = age_part(part, seen, RunOptions.for_scene(dogbone), [], store_fields=True)
    link = dogbone.mechanisms[0].drawn["crank"]
    field = plane_nodal_moisture(history.diffusion, part.geometry.thickness,
                                 sheet_profile(part, seen.exposures["crank"], times))
    expansion = np.column_stack([history.state["moisture_expansion_longitudinal"],
                                 history.state["moisture_expansion_transverse"]])
    return link, field, expansion, times


def test_the_plane_model_s_field_is_the_same_function_on_its_own_mesh(crank):
    """The nodal field lives on the plane model's own mesh, which covers the drawing to its
    chords, and rises with age from the uniform dry start."""
    link, field, _, times = crank
    corners = field.points[field.triangles]
    (ax, ay), (bx, by) = ((corners[:, k] - corners[:, 0]).T for k in (1, 2))
    area = 0.5 * np.abs(ax * by - ay * bx)
    mean = np.einsum("tmk,m->t", field.values[:, field.triangles], area) / (3 * area.sum())
    assert area.sum() == pytest.approx(link.planform.area, rel=1e-3)  # chords cut the arcs
    assert np.all(np.diff(mean) > 0) and mean[0] == pytest.approx(field.values[0].mean())


def test_a_linear_field_parts_the_pins_by_nothing_to_first_order(crank):
    """A moisture linear in x and y makes a compatible free strain (no stress), whose
    displacement u = e0 x + (g.x) x - |x|^2 g / 2 (e = e0 + g.x) P2 elements hold exactly.
    Along the link it parts the pins by L (e(A) + e(B)) / 2, which is zero where the
    field's mean is its value at the planform's centre, midway between the pins, as on this
    symmetric crank: what remains is the displaced holes' second-order geometry, and it
    falls as the strain's square (a first-order error would fall only as the strain)."""
    link, field, _, _ = crank
    x, y = field.points.T
    values = np.stack([0.4 + 3.0 * x - 20.0 * y] * 2)
    linear = NodalField(field.points, field.triangles, values)
    betas = np.array([[2e-3, 2e-3], [1e-3, 1e-3]])  # one factorisation for both
    shifts = field_pin_shifts(linear, link.planform, link.pins, betas)[:, 0]
    growth = 2e-3 * link.length * np.ptp(values[0]) / 2  # the pins' own displacements' scale
    assert abs(shifts[0]) < growth ** 2 / link.length
    # shift = a beta + b beta^2: the first-order part at beta = 2e-3 is 4 s(1e-3) - s(2e-3)
    assert abs(4 * shifts[1] - shifts[0]) < 1e-5 * growth


@pytest.mark.slow  # P1 on three meshes up to 0.35 million unknowns, P2 on two (about 60 s)
def test_the_dogbone_s_pin_shift_converges_at_the_elements_order(crank):
    """On the plane model's own mesh graded toward the web's four re-entrant corners, the
    pins' shift converges at a functional's order O(h^(2p)): P1 observed 1.72 to 1.73 from
    the second to the third mesh (2 asymptotically); P2 3.6, 4.1 and 5.4 at 1, 3 and 7 d
    (measured 2026-11-29 with a third P2 mesh, 0.7 million unknowns, too slow to repeat
    here). Without the grading the corners' singularity (r^0.56, Williams 1952) held every
    order near 2 x 0.56. The run's mesh (P2, no refinement) is within 2e-4 um of the next."""
    link, field, expansion, times = crank
    aged = (times > 0) & (times <= 30 * DAY)  # at 91 d the field is uniform: no shift
    p1 = np.array([field_pin_shifts(field, link.planform, link.pins, expansion, r, order=1)[aged, 0]
                   for r in range(3)])
    differences = np.abs(np.diff(p1, axis=0))
    assert np.all(np.log2(differences[0] / differences[1]) > 1.6), differences
    p2 = np.array([field_pin_shifts(field, link.planform, link.pins, expansion, r)[aged, 0]
                   for r in range(2)])
    assert np.max(np.abs(p2[1] - p2[0])) < 2e-10
    assert np.all(np.abs(p2[1] - p2[0]) < 0.1 * differences[1])  # P2 past P1 two meshes finer


@pytest.mark.slow  # a run of the example four-bar (about 5 s)
def test_the_dogbone_s_pins_part_by_what_its_field_gives_and_by_the_mean_strain_at_saturation(
        dogbone):
    ds = fickcam.run(dogbone)
    length = dogbone.mechanisms[0].drawn["crank"].length
    aged = np.asarray(ds["link_length"].sel(link="crank"))
    eps = np.asarray(ds["strain_longitudinal"].sel(part="crank"))
    shift = aged - length * (1 + eps)
    days = np.asarray(ds["time"]) / DAY
    # measured (2026-11-29): -0.019, 0.217, 0.455, 0.078 um at 1, 3, 7, 30 d; the web fills first
    assert shift[0] == 0.0
    assert np.all((shift[(days >= 3) & (days <= 30)] > 0.05e-6))
    assert np.all(shift < 1e-6)  # under 0.4 % of the swelling (250 um at 7 d)
    assert abs(shift[-1]) < 1e-12  # 91 d: saturated, uniform, L (1 + eps)
