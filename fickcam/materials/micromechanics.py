"""Ply properties from constituent properties: Chamis' simplified micromechanics.

Chamis, C. C. (1983) "Simplified composite micromechanics equations for hygral,
thermal and mechanical properties", NASA TM-83320 (tables of geometric,
mechanical, thermal and hygral equations), as reproduced in
Singh & Sanyal (2017) Tables 2-5. That paper typesets the transverse
and shear moduli as Em / ((1 - Em/Ef22)(1 - sqrt(kf))); the published form
Em / (1 - sqrt(kf) (1 - Em/Ef22)) is used here (it reproduces the paper's own
8.29 GPa, Table 9). Notation: kf, km, kv fibre, matrix, void volume ratios.
All functions are vectorised over numpy arrays.

The papers are cited in full in :mod:`fickcam.materials`.
"""
from __future__ import annotations

import numpy as np


def fiber_volume_ratio(fiber_weight_fraction, fiber_density, matrix_density, void_ratio=0.0):
    """kf = (1 - kv) / (1 + (rho_f/rho_m)(1/lambda_f - 1)) (Chamis 1983; Singh & Sanyal
    2017 Table 2).

    Parameters
    ----------
    fiber_weight_fraction : float or array_like
        The fibre weight fraction lambda_f [-].
    fiber_density, matrix_density : float
        The densities rho_f and rho_m [kg/m^3].
    void_ratio : float
        The void volume ratio kv [-].

    Returns
    -------
    numpy.ndarray
        The fibre volume ratio kf [-].
    """
    lam = np.asarray(fiber_weight_fraction, float)
    return (1.0 - void_ratio) / (1.0 + (fiber_density / matrix_density) * (1.0 / lam - 1.0))


def matrix_volume_ratio(fiber_ratio, void_ratio=0.0):
    """km = 1 - kf - kv (partial volumes, Singh & Sanyal 2017 Table 2).

    Parameters
    ----------
    fiber_ratio : float or array_like
        kf [-].
    void_ratio : float
        kv [-].

    Returns
    -------
    numpy.ndarray
        km [-].
    """
    return 1.0 - np.asarray(fiber_ratio, float) - void_ratio


def ply_density(kf, km, fiber_density, matrix_density):
    """rho_l = kf rho_f + km rho_m (Singh & Sanyal 2017 Table 2; voids weightless).

    Parameters
    ----------
    kf, km : float or array_like
        The fibre and matrix volume ratios [-].
    fiber_density, matrix_density : float
        rho_f and rho_m [kg/m^3].

    Returns
    -------
    numpy.ndarray
        The ply density rho_l [kg/m^3].
    """
    return kf * fiber_density + km * matrix_density


def rule_of_mixtures(kf, km, fiber_value, matrix_value):
    """P_l11 = kf P_f11 + km P_m: E11, nu12, K11 (Chamis 1983; Singh & Sanyal 2017 Tables
    3-4).

    Parameters
    ----------
    kf, km : float or array_like
        Volume ratios of fibre and matrix [-].
    fiber_value, matrix_value : float or array_like
        The property along the fibre and of the matrix, in one unit (Pa for moduli,
        W/(m K) for conductivities, - for Poisson's ratios).

    Returns
    -------
    numpy.ndarray
        The ply's property along the fibres, in that unit.
    """
    return kf * fiber_value + km * matrix_value


def transverse_inverse_mixture(kf, matrix_value, fiber_value):
    """P_l22 = P_m / (1 - sqrt(kf)(1 - P_m/P_f22)): E22, G12, G23 (Chamis 1983, published form).

    Parameters
    ----------
    kf : float or array_like
        The fibre volume ratio [-].
    matrix_value, fiber_value : float or array_like
        The matrix's modulus and the fibre's transverse (or shear) modulus [Pa].

    Returns
    -------
    numpy.ndarray
        The ply's transverse (or shear) modulus [Pa].
    """
    root = np.sqrt(kf)
    return matrix_value / (1.0 - root * (1.0 - matrix_value / fiber_value))


def matrix_shear_modulus(youngs_modulus, poisson_ratio):
    """Gm = Em / (2 (1 + nu_m)) (isotropic matrix, Singh & Sanyal 2017 section IV).

    Parameters
    ----------
    youngs_modulus : float or array_like
        Em [Pa].
    poisson_ratio : float
        nu_m [-].

    Returns
    -------
    numpy.ndarray
        Gm [Pa].
    """
    return youngs_modulus / (2.0 * (1.0 + poisson_ratio))


def transverse_poisson_ratio(transverse_modulus, transverse_shear_modulus):
    """nu23 = E22 / (2 G23) - 1 (Chamis 1983; Singh & Sanyal 2017
    Table 3 typesets Em for E22).

    Parameters
    ----------
    transverse_modulus : float or array_like
        E22 [Pa].
    transverse_shear_modulus : float or array_like
        G23 [Pa].

    Returns
    -------
    numpy.ndarray
        nu23 [-].
    """
    return transverse_modulus / (2.0 * transverse_shear_modulus) - 1.0


def longitudinal_expansion(kf, km, fiber_alpha11, fiber_e11, matrix_alpha, matrix_e, ply_e11):
    """alpha_l11 = (kf alpha_f11 Ef11 + km alpha_m Em) / E_l11 (Chamis 1983; Singh & Sanyal
    2017 Table 4).

    Parameters
    ----------
    kf, km : float or array_like
        The fibre and matrix volume ratios [-].
    fiber_alpha11, matrix_alpha : float or array_like
        alpha_f11 and alpha_m [1/K].
    fiber_e11, matrix_e, ply_e11 : float or array_like
        Ef11, Em and E_l11 [Pa].

    Returns
    -------
    numpy.ndarray
        alpha_l11 [1/K].
    """
    return (kf * fiber_alpha11 * fiber_e11 + km * matrix_alpha * matrix_e) / ply_e11


def transverse_expansion(kf, fiber_alpha22, matrix_alpha, matrix_nu, fiber_e11, ply_e11):
    """alpha_l22 = alpha_f22 sqrt(kf) + (1 - sqrt(kf))(1 + kf nu_m Ef11/E_l11) alpha_m
    (Chamis 1983; Singh & Sanyal 2017 Table 4).

    Parameters
    ----------
    kf : float or array_like
        The fibre volume ratio [-].
    fiber_alpha22, matrix_alpha : float or array_like
        alpha_f22 and alpha_m [1/K].
    matrix_nu : float
        nu_m [-].
    fiber_e11, ply_e11 : float or array_like
        Ef11 and E_l11 [Pa].

    Returns
    -------
    numpy.ndarray
        alpha_l22 [1/K].
    """
    root = np.sqrt(kf)
    return fiber_alpha22 * root + (1.0 - root) * (1.0 + kf * matrix_nu * fiber_e11 / ply_e11) * matrix_alpha


def transverse_conductivity(kf, fiber_k22, matrix_k):
    """K_l22 = (1 - sqrt(kf)) K_m + K_m sqrt(kf) / (1 - sqrt(kf)(1 - K_m/K_f22))
    (Chamis 1983; Singh & Sanyal 2017 Table 4 typesets the last factor as (1 - k_m/k_f)).

    Parameters
    ----------
    kf : float or array_like
        The fibre volume ratio [-].
    fiber_k22, matrix_k : float or array_like
        K_f22 and K_m [W/(m K)].

    Returns
    -------
    numpy.ndarray
        K_l22 [W/(m K)].
    """
    root = np.sqrt(kf)
    return (1.0 - root) * matrix_k + matrix_k * root / (1.0 - root * (1.0 - matrix_k / fiber_k22))


def longitudinal_moisture_expansion(km, matrix_beta, matrix_e, ply_e11):
    """beta_l11 = beta_m km Em / E_l11 (Chamis 1983, fibres do not swell; Singh & Sanyal
    2017 Table 5).

    Parameters
    ----------
    km : float or array_like
        The matrix volume ratio [-].
    matrix_beta : float or array_like
        beta_m [1/weight %].
    matrix_e, ply_e11 : float or array_like
        Em and E_l11 [Pa].

    Returns
    -------
    numpy.ndarray
        beta_l11 [1/weight %].
    """
    return matrix_beta * km * matrix_e / ply_e11


def transverse_moisture_expansion(kf, matrix_beta, matrix_e, ply_e22):
    """beta_l22 = beta_m (1 - sqrt(kf)) [1 + Em (1 - sqrt(kf)) sqrt(kf) /
    (sqrt(kf) E_l22 + (1 - sqrt(kf)) Em)] (Chamis 1983; Singh & Sanyal 2017 Table 5).

    Parameters
    ----------
    kf : float or array_like
        Fibre volume ratio [-].
    matrix_beta : float or array_like
        The matrix moisture expansion beta_m [1/weight %].
    matrix_e, ply_e22 : float or array_like
        Em and E_l22 [Pa].

    Returns
    -------
    numpy.ndarray
        beta_l22, in the unit of ``matrix_beta``.
    """
    root = np.sqrt(kf)
    return matrix_beta * (1.0 - root) * (
        1.0 + matrix_e * (1.0 - root) * root / (root * ply_e22 + (1.0 - root) * matrix_e))


def longitudinal_diffusivity(kf, matrix_d):
    """D_l11 = (1 - kf) D_m (Chamis 1983; Singh & Sanyal 2017 Table 5).

    Parameters
    ----------
    kf : float or array_like
        The fibre volume ratio [-].
    matrix_d : float or array_like
        The matrix diffusivity D_m [m^2/s].

    Returns
    -------
    numpy.ndarray
        The ply diffusivity along the fibres [m^2/s].
    """
    return (1.0 - kf) * matrix_d


def transverse_diffusivity(kf, matrix_d, model: str = "chamis"):
    """D_l22 = (1 - sqrt(kf)) D_m (Chamis 1983; Singh & Sanyal 2017 Table 5), or
    ``model="shen_springer"``: (1 - 2 sqrt(kf/pi)) D_m (Shen & Springer 1976,
    J. Compos. Mater. 10:2-20, eq. 19, impermeable square-packed fibres).

    Parameters
    ----------
    kf, matrix_d
        As in :func:`longitudinal_diffusivity`: kf [-], D_m [m^2/s].
    model : {"chamis", "shen_springer"}

        Which relation.

    Returns
    -------
    numpy.ndarray
        The ply diffusivity across the fibres [m^2/s].

    References
    ----------
    C.-H. Shen and G. S. Springer, "Moisture absorption and desorption of composite
    materials", *Journal of Composite Materials* 10(1), 2-20, 1976,
    doi:10.1177/002199837601000101.
    """
    if model == "shen_springer":
        return (1.0 - 2.0 * np.sqrt(kf / np.pi)) * matrix_d
    return (1.0 - np.sqrt(kf)) * matrix_d


def ply_moisture(matrix_moisture, matrix_beta_per_fraction, km, kv, matrix_density, ply_density_):
    """M_l = M_m (3 beta_m km + kv) rho_m / rho_l (Chamis 1983; Singh & Sanyal
    2017 section IV and Table 10 step 2). beta_m here in strain per unit weight fraction (= 100 x per %);
    3 beta_m ~ 1 for epoxies, when M_l is the matrix weight share of M_m.

    Parameters
    ----------
    matrix_moisture : float or array_like
        The matrix moisture M_m [weight %].
    matrix_beta_per_fraction : float
        The matrix moisture expansion beta_m [-] (strain per unit weight fraction).
    km, kv : float
        The matrix and void volume ratios [-].
    matrix_density, ply_density_ : float
        The densities rho_m and rho_l [kg/m^3].

    Returns
    -------
    numpy.ndarray
        The ply moisture M_l [weight %].
    """
    return matrix_moisture * (3.0 * matrix_beta_per_fraction * km + kv) * matrix_density / ply_density_


def matrix_moisture(ply_moisture_, matrix_beta_per_fraction, km, kv, matrix_density, ply_density_):
    """Inverse of :func:`ply_moisture`: M_m from the ply (diffusion) moisture M_l.

    Parameters
    ----------
    ply_moisture_ : float or array_like
        The ply moisture M_l [weight %].
    matrix_beta_per_fraction, km, kv : float
        beta_m and the volume ratios, as in :func:`ply_moisture` [-].
    matrix_density, ply_density_ : float
        rho_m and rho_l [kg/m^3].

    Returns

    -------
    numpy.ndarray
        The matrix moisture M_m [weight %].
    """
    return ply_moisture_ * ply_density_ / ((3.0 * matrix_beta_per_fraction * km + kv) * matrix_density)


# --- laminate averaging for quasi-isotropic in-plane layups ----------------------------


def reduced_stiffness(e11, e22, g12, nu12):
    """Plane-stress reduced stiffnesses Q11, Q22, Q12, Q66 (Jones 1999, Mechanics of
    Composite Materials, eq. 2.61).

    Parameters
    ----------
    e11, e22 : float or array_like
        The ply's moduli along and across the fibres [Pa].
    g12 : float or array_like
        G12, the in-plane shear modulus [Pa].
    nu12 : float or array_like
        nu12, the strain across over the strain along the fibres under a load along
        them [-].

    Returns
    -------
    tuple
        Q11, Q22, Q12, Q66 [Pa].

    References
    ----------
    Jones, R. M. (1999). Mechanics of Composite Materials, 2nd ed. Philadelphia: Taylor &
    Francis.
    """
    nu21 = nu12 * e22 / e11
    denom = 1.0 - nu12 * nu21
    return e11 / denom, e22 / denom, nu12 * e22 / denom, g12


def _quasi_isotropic_invariants(q11, q22, q12, q66):
    """U1, U4, U5 (Tsai & Hahn 1980, Introduction to Composite Materials, ch. 7;
    Jones 1999 eq. 4.93): a quasi-isotropic laminate has A/h = [[U1, U4], [U4, U1]],
    A66/h = U5."""
    u1 = (3.0 * q11 + 3.0 * q22 + 2.0 * q12 + 4.0 * q66) / 8.0
    u4 = (q11 + q22 + 6.0 * q12 - 4.0 * q66) / 8.0
    u5 = (q11 + q22 - 2.0 * q12 + 4.0 * q66) / 8.0
    return u1, u4, u5


def quasi_isotropic_elastic(e11, e22, g12, nu12):
    """In-plane E, G, nu of a quasi-isotropic laminate: E = (U1^2 - U4^2)/U1,
    G = U5, nu = U4/U1 (Tsai & Hahn 1980 ch. 7).

    Parameters
    ----------
    e11, e22 : float or array_like
        The ply's moduli along and across the fibres [Pa].
    g12 : float or array_like
        The ply's in-plane shear modulus [Pa].
    nu12 : float or array_like
        The ply's major Poisson's ratio [-].

    Returns
    -------
    tuple
        The laminate's E [Pa], G [Pa] and nu [-].

    References
    ----------
    Tsai, S. W. & Hahn, H. T. (1980). Introduction to Composite Materials. Westport, CT:
    Technomic.
    """
    u1, u4, u5 = _quasi_isotropic_invariants(*reduced_stiffness(e11, e22, g12, nu12))
    return (u1 ** 2 - u4 ** 2) / u1, u5, u4 / u1


def quasi_isotropic_expansion(e11, e22, g12, nu12, coefficient11, coefficient22):
    """In-plane expansion coefficient (thermal or moisture) of a quasi-isotropic laminate:
    rotational average of the ply's Q.alpha over (A11 + A12)/h =
    (Q11 a1 + Q12 (a1 + a2) + Q22 a2) / (Q11 + Q22 + 2 Q12) (Tsai & Hahn 1980 ch. 7,
    laminate thermal forces; Jones 1999 section 4.8).

    Parameters
    ----------
    e11, e22, g12, nu12 : float or array_like
        The ply's elastic constants, as :func:`quasi_isotropic_elastic` takes them: moduli
        [Pa], Poisson's ratio [-].
    coefficient11, coefficient22 : float or array_like
        The ply's expansion coefficients along and across the fibres: thermal [1/K] or
        moisture [1/weight %].

    Returns
    -------
    float or numpy.ndarray
        The laminate's in-plane coefficient [unit of the coefficients].

    References
    ----------
    Tsai & Hahn (1980), ch. 7; Jones (1999), sec. 4.8 (in full in
    :func:`quasi_isotropic_elastic` and :func:`reduced_stiffness`).
    """
    q11, q22, q12, _ = reduced_stiffness(e11, e22, g12, nu12)
    return (q11 * coefficient11 + q12 * (coefficient11 + coefficient22) + q22 * coefficient22) / (
        q11 + q22 + 2.0 * q12)
