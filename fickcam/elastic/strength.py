r"""Wet ply strengths and the Tsai-Wu failure index.

Ply strengths from the constituents (Chamis 1984, NASA TM-83696, "Simplified composite
micromechanics equations for strength ..."):

.. math::

    S_{11T} = k_f S_{fT}, \qquad S_{11C} = k_f S_{fC},

    S_{22T} = \Big[1 - (\sqrt{k_f} - k_f)\Big(1 - \frac{E_m}{E_{f22}}\Big)\Big] S_{mT},
    \qquad S_{22C} \text{ the same with } S_{mC},

    S_{12S} = \Big[1 - (\sqrt{k_f} - k_f)\Big(1 - \frac{G_m}{G_{f12}}\Big)\Big] S_{mS},

with the matrix strengths and moduli degraded by the same hygrothermal retention P/P0 as
the stiffness (Chamis 1984 eq. for environmental effects). A resin or plastic: its own
strengths times P/P0. Metals carry no strengths here (NaN index).

Failure index: the Tsai-Wu criterion (Tsai & Wu 1971, J. Composite Materials 5, 58;
Jones 1999 eq. 4.25) F1 s1 + F2 s2 + F11 s1^2 + F22 s2^2 + F66 s12^2 + 2 F12 s1 s2 = 1,
F1 = 1/Xt - 1/Xc, F11 = 1/(Xt Xc), F66 = 1/S^2, F12 = -sqrt(F11 F22)/2 (Tsai & Hahn 1980),
reported as 1/R, R the factor on the stress that reaches the criterion: with
a = quadratic terms, b = linear terms, 1/R = (b + sqrt(b^2 + 4 a)) / 2 (proportional to
the load; 1 = failure).
"""
from __future__ import annotations

import numpy as np


def ply_strengths(material, retention) -> dict[str, np.ndarray] | None:
    """Xt, Xc, Yt, Yc, S (Pa) of the ply (or the isotropic material) at retention P/P0;
    None when the library gives no strengths (metals).

    Parameters
    ----------
    material : fickcam.materials.Material
        The part's material.
    retention : float or array_like
        The hygrothermal retention P/P0 of the matrix [-].

    Returns
    -------
    dict of str to numpy.ndarray or None
        The strengths Xt, Xc, Yt, Yc, S [Pa] (compressive ones positive).

    References
    ----------
    C. C. Chamis, "Simplified composite micromechanics equations for strength,
    fracture toughness and environmental effects", NASA TM-83696, 1984.
    """
    m = material.matrix
    if material.kind == "metal" or "tensile_strength" not in m:
        return None
    r = np.asarray(retention, float)
    smt, smc, sms = (m[key] * r for key in ("tensile_strength", "compressive_strength", "shear_strength"))
    if material.fiber is None:
        return {"Xt": smt, "Xc": smc, "Yt": smt, "Yc": smc, "S": sms}
    f, kf = material.fiber, material.fiber_ratio
    em = m["youngs_modulus"] * r
    gm = em / (2.0 * (1.0 + m["poisson_ratio"]))
    factor = np.sqrt(kf) - kf
    transverse = 1.0 - factor * (1.0 - em / f["transverse_modulus"])
    shear = 1.0 - factor * (1.0 - gm / f["shear_modulus"])
    return {"Xt": kf * f["tensile_strength"] + 0.0 * r, "Xc": kf * f["compressive_strength"] + 0.0 * r,
            "Yt": transverse * smt, "Yc": transverse * smc, "S": shear * sms}


def tsai_wu_index(s1, s2, s12, strengths: dict) -> np.ndarray:
    """1/R of the Tsai-Wu criterion for ply-axis stresses (arrays broadcast with the
    strengths).

    Parameters
    ----------
    s1, s2 : float or array_like
        The normal stresses along and across the fibres [Pa].
    s12 : float or array_like
        The in-plane shear stress [Pa].
    strengths : dict of str to float or array_like
        Xt, Xc, Yt, Yc, S [Pa] (:func:`ply_strengths`).

    Returns
    -------
    numpy.ndarray
        The failure index 1/R [-]: 1 at failure, proportional to the load.

    References
    ----------
    S. W. Tsai and E. M. Wu, "A general theory of strength for anisotropic materials",
    *Journal of Composite Materials* 5(1), 58-80, 1971, doi:10.1177/002199837100500106.
    """
    xt, xc, yt, yc, s = (strengths[k] for k in ("Xt", "Xc", "Yt", "Yc", "S"))
    f11, f22 = 1.0 / (xt * xc), 1.0 / (yt * yc)
    f12 = -0.5 * np.sqrt(f11 * f22)
    a = f11 * s1 ** 2 + f22 * s2 ** 2 + s12 ** 2 / s ** 2 + 2.0 * f12 * s1 * s2
    b = (1.0 / xt - 1.0 / xc) * s1 + (1.0 / yt - 1.0 / yc) * s2
    return 0.5 * (b + np.sqrt(b ** 2 + 4.0 * a))
