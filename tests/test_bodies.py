"""Volume, mass and inertia of links, discs and cam plates; Singh & Sanyal (2016) Table 6."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.materials.bodies import (
    aged_disc_body,
    aged_link_body,
    aged_plate_body,
    disc_body,
    link_body,
    link_section,
    plate_body,
    polygon_section,
)
from fickcam.materials.library import entry


def raster_link(L, W, ro, ri, n=1600):
    """Brute-force area and polar moment of the link outline on a grid."""
    xs = np.linspace(-L / 2 - ro, L / 2 + ro, n)
    ys = np.linspace(-ro, ro, n // 2)
    X, Y = np.meshgrid(xs, ys)
    dA = (xs[1] - xs[0]) * (ys[1] - ys[0])
    boss = lambda r: ((X - L / 2) ** 2 + Y ** 2 < r ** 2) | ((X + L / 2) ** 2 + Y ** 2 < r ** 2)
    inside = (((np.abs(X) <= L / 2) & (np.abs(Y) <= W / 2)) | boss(ro)) & ~boss(ri)
    return inside.sum() * dA, ((X ** 2 + Y ** 2) * inside).sum() * dA


@pytest.mark.parametrize("W, ro", [(0.03, 0.02), (0.03, 0.015), (0.01, 0.02)])
def test_link_section_matches_a_raster_of_its_outline(W, ro):
    area, polar = link_section(0.1, W, ro, 0.006)
    ref_area, ref_polar = raster_link(0.1, W, ro, 0.006)
    assert area == pytest.approx(ref_area, rel=3e-3)
    assert polar == pytest.approx(ref_polar, rel=3e-3)


def test_link_body_parallel_axis_against_composite_body_without_overlap():
    # a thin bar (W -> 0) leaves two annuli at +-L/2 plus the bar: parallel axis explicit
    L, ro, ri, t, rho = 0.2, 0.02, 0.01, 0.01, 1000.0
    v, m, inertia = link_body(L, 1e-9, t, ro, ri, rho)
    m_boss = rho * np.pi * (ro ** 2 - ri ** 2) * t
    assert m == pytest.approx(2 * m_boss, rel=1e-6)
    assert inertia == pytest.approx(2 * (m_boss * (ro ** 2 + ri ** 2) / 2 + m_boss * (L / 2) ** 2), rel=1e-6)


def test_link_outline_that_is_not_a_link_is_nan():
    assert np.isnan(link_section(0.1, 0.05, 0.02, 0.01)[0])  # wider than the boss


def test_disc_and_polygon_shoelace_agree_for_a_fine_polygon():
    t = np.linspace(0, 2 * np.pi, 4000, endpoint=False)
    v, m, i = plate_body(0.05 * np.cos(t), 0.05 * np.sin(t), 0.01, bore_radius=0.01, density=1500.0)
    vd, md, idisc = disc_body(0.05, 0.01, 0.01, 1500.0)
    assert v == pytest.approx(vd, rel=1e-5) and m == pytest.approx(md, rel=1e-5)
    assert i == pytest.approx(idisc, rel=1e-5)


def test_polygon_section_of_an_offset_rectangle():
    x = np.array([1.0, 3.0, 3.0, 1.0])
    y = np.array([0.0, 0.0, 1.0, 1.0])
    area, cx, cy, polar = polygon_section(x, y)
    assert (area, cx, cy) == pytest.approx((2.0, 2.0, 0.5))
    # about its centroid 2 (4 + 1)/12, plus area x distance^2 (parallel axis)
    assert polar == pytest.approx(2 * 5 / 12 + 2 * (4 + 0.25))


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 10.0), st.floats(0.0, 10.0))
def test_aged_link_mass_is_dry_mass_times_one_plus_moisture_and_monotone(m1, m2):
    dims = (0.1, 0.03, 0.01, 0.015, 0.005)
    _, dry, _ = link_body(*dims, 1290.0)
    low, high = sorted((m1, m2))
    out = [aged_link_body(*dims, 1290.0, m, 3e-3 * m, 3e-3 * m, 3e-3 * m) for m in (low, high)]
    assert out[0][1] == pytest.approx(dry * (1 + low / 100))
    assert out[0][1] <= out[1][1] and out[0][2] <= out[1][2]


# --------------------------------------------------------------------------------------
# Singh & Sanyal (2016) Table 6 under the paper's own convention (Table 5):
# V = W T L + 2 pi (Ro^2 - Ri^2) T (the bar runs centre to centre, overlap counted twice),
# wet dimensions x (1 + alpha_wet dT + beta dm) with dT = 95 degC and dm = the Table 4
# equilibrium moisture, wet mass = wet density x wet volume.
# Inferred link cross-section: W = 30 mm, T = 20 mm (W T = 600 mm^2 from the volume
# differences between the three lengths; W^2 + T^2 = 1300 mm^2 from the inertia's linear
# term m_bar (W^2 + T^2)/12), bosses 2 pi (Ro^2 - Ri^2) T = 13699 mm^3, i.e.
# Ro^2 - Ri^2 = 109.0 mm^2 (Ro = 15 mm = W/2 gives Ri = 10.77 mm), density 2.0 g/cm3
# (mass / volume of every dry row).

W, T, RO = 30.0, 20.0, 15.0
RI = np.sqrt(RO ** 2 - 13699.0 / (2 * np.pi * T))
RHO = 2.0e-3  # g/mm^3
TABLE6 = [  # length, resin, V dry, V wet, m dry, m wet (mm^3, g)
    (100, "R914", 73699, 79991, 147, 158), (100, "3502", 73699, 77938, 147, 154),
    (100, "8551-7", 73699, 76577, 147, 150), (1000, "R914", 613699, 667456, 1227, 1313),
    (1000, "3502", 613699, 649004, 1227, 1289), (1000, "8551-7", 613699, 637662, 1227, 1252),
    (1200, "R914", 733699, 796339, 1467, 1570), (1200, "3502", 733699, 775908, 1467, 1540),
    (1200, "8551-7", 733699, 762348, 1467, 1496),
]


def paper_volume(L, W, T, ro, ri):
    return W * T * L + 2 * np.pi * (ro ** 2 - ri ** 2) * T


@pytest.mark.parametrize("L, resin, v_dry, v_wet, m_dry, m_wet", TABLE6)
def test_singh2016_table6_volume_and_mass(L, resin, v_dry, v_wet, m_dry, m_wet):
    values = entry("matrices", resin)
    strain = values["thermal_expansion_wet"] * 95.0 + values["moisture_expansion"] * values["saturation"]["coefficient"]
    scale = 1.0 + strain
    assert paper_volume(L, W, T, RO, RI) == pytest.approx(v_dry, rel=0.02)
    assert paper_volume(L * scale, W * scale, T * scale, RO * scale, RI * scale) == pytest.approx(v_wet, rel=0.02)
    assert RHO * paper_volume(L, W, T, RO, RI) == pytest.approx(m_dry, rel=0.02)
    # fickcam's mass m_dry (1 + M/100) vs the paper's wet density x wet volume: the paper's
    # wet masses are not reproducible from a stated wet density, but agree with m_dry (1 + M/100)
    assert RHO * paper_volume(L, W, T, RO, RI) * (1 + values["saturation"]["coefficient"] / 100) == \
        pytest.approx(m_wet, rel=0.02)


def test_singh2016_table6_dry_inertia_has_the_inferred_bar_term_and_no_bar_length_term():
    # The dry inertias of the three lengths fit I = A + B L + C L^2 exactly with
    # B = rho W T (W^2 + T^2)/12 of the inferred section; a correct centroidal bar term
    # m_bar L^2/12 would add rho W T L^3/12 (paper slip: Table 5 uses the bar's long axis).
    lengths = np.array([100.0, 1000.0, 1200.0])
    inertia = np.array([7132765.0, 710755166.0, 1023450234.0])
    a, b, c = np.linalg.solve(np.vstack([np.ones(3), lengths, lengths ** 2]).T, inertia)
    assert b == pytest.approx(RHO * W * T * (W ** 2 + T ** 2) / 12, rel=5e-3)
    cubic = np.linalg.solve(np.vstack([lengths, lengths ** 2, lengths ** 3]).T, inertia)[2]
    assert abs(cubic) < 1e-2 * RHO * W * T / 12


def test_aged_disc_and_plate_agree_and_scale_with_strain():
    t = np.linspace(0, 2 * np.pi, 3000, endpoint=False)
    strains = np.array([0.0, 0.01, 0.02])
    moisture = np.array([0.0, 1.0, 2.0])
    v, m, i = aged_plate_body(0.05 * np.cos(t), 0.05 * np.sin(t), 0.01, 0.01, 1500.0, moisture,
                              strains, strains, strains)
    vd, md, idisc = aged_disc_body(0.05, 0.01, 0.01, 1500.0, moisture, strains, strains)
    assert v.shape == (3,)
    assert np.allclose(v, vd, rtol=1e-5) and np.allclose(m, md) and np.allclose(i, idisc, rtol=1e-5)
    assert np.allclose(vd, vd[0] * (1 + strains) ** 3)
    # uniform swelling: I = m_wet k^2 (1 + eps)^2
    assert np.allclose(idisc, idisc[0] * (1 + moisture / 100) * (1 + strains) ** 2)


def test_singh2016_table6_inertia_growth_is_per_material_except_a_copied_row():
    # Every link dimension scales by the same free strain, so under any one
    # convention the wet/dry inertia ratio depends on the material, not on the
    # link length. Rows 1-6 of Singh & Sanyal (2016) Table 6 obey this
    # (R914 1.209 / 1.211, 3502 1.144 / 1.144, 8551-7 1.067 / 1.067); row 7
    # (R914, 1200 mm) carries the 3502 ratio (1.1449): a copying slip in the paper,
    # which is why that column is not used to validate fickcam's inertia.
    dry = {100: 7132765.0, 1000: 710755166.0, 1200: 1023450234.0}
    wet = {("R914", 100): 8622622.0, ("R914", 1000): 860584074.0, ("R914", 1200): 1171745656.0,
           ("3502", 100): 8161202.0, ("3502", 1000): 813372280.0, ("3502", 1200): 1171215532.0,
           ("8551-7", 100): 7612314.0, ("8551-7", 1000): 758593142.0, ("8551-7", 1200): 1092335194.0}
    ratio = {key: value / dry[key[1]] for key, value in wet.items()}
    for resin in ("R914", "3502", "8551-7"):
        assert ratio[(resin, 100)] == pytest.approx(ratio[(resin, 1000)], rel=2e-3)
    for resin in ("3502", "8551-7"):
        assert ratio[(resin, 1200)] == pytest.approx(ratio[(resin, 1000)], rel=2e-3)
    assert ratio[("R914", 1200)] == pytest.approx(ratio[("3502", 1000)], rel=1e-3)
    assert abs(ratio[("R914", 1200)] / ratio[("R914", 1000)] - 1) > 0.05
