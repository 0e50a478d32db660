"""Al-Shamma & Yousuf (2011): where its analytical plate solution fails, and its box cam
through fickcam's plane-stress model.

References
----------
Al-Shamma, F. & Yousuf, L. S. (2011). Predictive model of orthotropic un-symmetric
    box cam based on deflection and countered by segments of circular-arc contact
    profiles. Global Journal of Researches in Engineering (A) 11(7).
"""
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam

# plate rigidities of a T300/epoxy ply at kf 0.3 (fickcam's library, Chamis), t = 10 mm;
# the paper's D = E t^3 / (12 (nu_rt nu_tr)) drops the "1 -" of D = E t^3 / (12 (1 - nu nu))
E_R, E_T, NU_RT, G_RT, T = 68.4e9, 5.0e9, 0.32, 1.9e9, 0.01
NU_TR = NU_RT * E_T / E_R
D_R = E_R * T ** 3 / (12 * (1 - NU_RT * NU_TR))
D_T = E_T * T ** 3 / (12 * (1 - NU_RT * NU_TR))
D_1 = NU_RT * D_T
D_RT = G_RT * T ** 3 / 12
H = D_1 + 2 * D_RT


def plate_operator(d):
    """Left side of the paper's eq. (3) (the orthotropic plate in polar coordinates,
    Ventsel & Krauthammer 2001 eq. 10.x / Lekhnitskii) from the derivatives d[name]."""
    r = d["r"]
    return (D_R * d["rrrr"] + 2 * D_R / r * d["rrr"] - D_T / r ** 2 * d["rr"] + D_T / r ** 3 * d["r1"]
            + 2 * H / r ** 2 * d["rrtt"] - 2 * H / r ** 3 * d["rtt"]
            + 2 * (D_1 + D_T + 2 * D_RT) / r ** 4 * d["tt"] + D_T / r ** 4 * d["tttt"])


def sine_derivatives(r, t):
    """Exact derivatives of w = sin(r theta) (the paper's eq. 4 with A = 1, B = 0)."""
    s, c = np.sin(r * t), np.cos(r * t)
    return {"r": r, "w": s, "r1": t * c, "rr": -t ** 2 * s, "rrr": -t ** 3 * c, "rrrr": t ** 4 * s,
            "tt": -r ** 2 * s, "tttt": r ** 4 * s, "rtt": -2 * r * s - t * r ** 2 * c,
            "rrtt": -2 * s - 4 * r * t * c + t ** 2 * r ** 2 * s}


def test_sine_derivatives_agree_with_finite_differences():
    """The derivatives used below, checked independently (central differences)."""
    r, t, h = 0.03, 0.7, 1e-3

    def w(rr, tt):
        return np.sin(rr * tt)
    d = sine_derivatives(r, t)
    assert (w(r + h, t) - w(r - h, t)) / (2 * h) == pytest.approx(d["r1"], rel=1e-6)
    assert (w(r, t + h) - 2 * w(r, t) + w(r, t - h)) / h ** 2 == pytest.approx(d["tt"], rel=1e-5)
    def along_r(tt):
        return (w(r + h, tt) - w(r - h, tt)) / (2 * h)
    assert (along_r(t + h) - 2 * along_r(t) + along_r(t - h)) / h ** 2 == pytest.approx(d["rtt"], rel=1e-3)
    hh = 1e-2  # fourth derivative in r: sin(r t) varies on 1/t, so a coarse step is accurate
    fourth = (w(r + 2 * hh, t) - 4 * w(r + hh, t) + 6 * w(r, t) - 4 * w(r - hh, t) + w(r - 2 * hh, t)) / hh ** 4
    assert fourth == pytest.approx(d["rrrr"], rel=1e-3)


@pytest.mark.parametrize("r, theta", [(0.025, 0.5), (0.025, 2.0), (0.04, 1.0), (0.06, 3.0)])
def test_alshamma2011_homogeneous_solution_does_not_satisfy_its_plate_equation(r, theta):
    """w_H = A sin(r theta) + B cos(r theta) (eq. 4) is not a solution of eq. (3) with
    q = 0: the residual L[w_H] is of the size of its largest term, not zero. (The paper's
    eq. 5 then 'solves' for w_H in terms of itself; eqs. 5-9 inherit the error.)"""
    d = sine_derivatives(r, theta)
    residual = plate_operator(d)
    terms = [D_R * d["rrrr"], D_T / r ** 4 * d["tttt"], 2 * H / r ** 2 * d["rrtt"],
             2 * (D_1 + D_T + 2 * D_RT) / r ** 4 * d["tt"]]
    assert abs(residual) > 0.1 * max(abs(x) for x in terms)


def test_alshamma2011_particular_solution_is_not_one():
    """w_P = C r theta with C = q r^3 / (theta D_theta) (eqs. 6-7): C is not a constant,
    and w_P = q r^4 / D_theta gives L[w_P] = q (72 D_r - 8 D_theta) / D_theta, which is q
    only if D_r / D_theta = 1/8; here the residual is 100x q."""
    q, r = 1.0, 0.03
    d = {"r": r, "r1": 4 * r ** 3, "rr": 12 * r ** 2, "rrr": 24 * r, "rrrr": 24.0,
         "tt": 0.0, "tttt": 0.0, "rtt": 0.0, "rrtt": 0.0}
    residual = q / D_T * plate_operator(d) - q
    assert residual == pytest.approx(q * (72 * D_R / D_T - 9), rel=1e-9)
    assert abs(residual) > 10 * q


#: the paper's ANSYS deflections (Tables 1-3; units not stated, read as mm)
ANSYS_RANGE = (0.0031101e-3, 0.047361e-3)


@pytest.mark.slow
def test_alshamma2011_box_cam_deflection_against_the_ansys_magnitudes():
    """The Al-Shamma & Yousuf 2011 scene (its clamped radius, fibre fraction, harmonic
    motion; the rest fickcam's assumptions, see the scene) deflects in its plane by
    micrometres, the order of the paper's ANSYS tables read as mm; the paper's load cannot
    be evaluated (sigma_y, L and L1 of its eq. 10 are not given), so only the order is
    compared. Moisture softens the matrix, so the aged cam deflects more."""
    doc = yaml.safe_load((Path(__file__).resolve().parents[1] / "configs" /
                          "alshamma2011_box_cam.yaml").read_text())
    doc["outputs"] = {"ageing_times": ["0 d", "60 d"], "angle_step": "15 deg"}
    ds = fickcam.run(doc)
    deflection = ds.elastic_deflection.values
    low, high = ANSYS_RANGE
    assert 0.1 * low < np.nanmax(deflection[0]) < 10 * high
    assert np.nanmax(deflection[1]) > np.nanmax(deflection[0])
    assert np.all(np.isfinite(ds.swelling_stress_compressive.sel(part="cam").values))
