"""Hygrothermal degradation of the matrix and free hygrothermal strain.

Chamis (1983) NASA TM-83320, hygrothermal degradation equations, as reproduced
in Singh & Sanyal (2017) eqs. 9-11 and Table 10, and Singh & Sanyal (2016) eqs. 4-10.

The papers are cited in full in :mod:`fickcam.materials`.
"""
from __future__ import annotations

import numpy as np

KELVIN_OFFSET = 273.15

#: Temperature scale in which Tgw = f(M) Tgd is evaluated. The relation is a
#: multiplicative fit, so the scale matters: Singh & Sanyal (2016, 2017) apply it in degC
#: (Singh & Sanyal 2017, Table 10 step 4: 157 degC -> 148 degC), Chamis' report in degF.
TG_SCALES = ("celsius", "fahrenheit", "kelvin")


def _to_scale(kelvin, scale: str):
    kelvin = np.asarray(kelvin, float)
    if scale == "celsius":
        return kelvin - KELVIN_OFFSET
    if scale == "fahrenheit":
        return (kelvin - KELVIN_OFFSET) * 1.8 + 32.0
    if scale == "kelvin":
        return kelvin
    raise ValueError(f"unknown temperature scale {scale!r} (known: {', '.join(TG_SCALES)})")


def _from_scale(value, scale: str):
    value = np.asarray(value, float)
    if scale == "celsius":
        return value + KELVIN_OFFSET
    if scale == "fahrenheit":
        return (value - 32.0) / 1.8 + KELVIN_OFFSET
    return value


def wet_tg_factor(matrix_moisture):
    """0.005 M^2 - 0.1 M + 1, M = matrix moisture in weight % (Chamis 1983; Singh & Sanyal
    2017 eq. 11,
    stated for M < 10 %).

    Parameters
    ----------
    matrix_moisture : float or array_like
        The matrix moisture M [weight %].

    Returns
    -------
    numpy.ndarray
        Tgw / Tgd [-].

    References
    ----------
    C. C. Chamis, "Simplified composite micromechanics equations for hygral, thermal
    and mechanical properties", NASA TM-83320, 1983.
    """
    m = np.asarray(matrix_moisture, float)
    return 0.005 * m ** 2 - 0.1 * m + 1.0


def wet_glass_transition_temperature(dry_tg, matrix_moisture, scale: str = "celsius"):
    """Tgw = (0.005 M^2 - 0.1 M + 1) Tgd, evaluated in ``scale`` (K in, K out).
    Chamis 1983; Singh & Sanyal 2017 eq. 11 and Table 10 step 4 (degC).

    Parameters
    ----------
    dry_tg : float or array_like
        The dry glass transition temperature Tgd [K].
    matrix_moisture : float or array_like
        The matrix moisture M [weight %].
    scale : {"celsius", "fahrenheit", "kelvin"}
        The temperature scale in which the multiplicative fit is applied.

    Returns
    -------
    numpy.ndarray
        The wet glass transition temperature Tgw [K].

    Raises
    ------
    ValueError
        When the scale is unknown.

    References
    ----------
    C. C. Chamis, "Simplified composite micromechanics equations for hygral, thermal
    and mechanical properties", NASA TM-83320, 1983.

    S. Singh and S. Sanyal, "Kinematic and dynamic variations in cam and follower made of
    composite material under hygrothermal environment", *International Journal of
    Innovative Research in Science, Engineering and Technology* 6(3), 2017.
    """
    return _from_scale(wet_tg_factor(matrix_moisture) * _to_scale(dry_tg, scale), scale)


def property_retention(wet_tg, temperature, dry_tg, reference_temperature):
    """P/P0 = sqrt((Tgw - T) / (Tgd - T0)) for mechanical matrix properties (Chamis 1983;
    Singh & Sanyal 2017 Table 10 step 5; Singh & Sanyal 2016 eq. 9). Temperature
    differences, so any scale. NaN where T >= Tgw (outside the model's domain).

    Parameters
    ----------
    wet_tg : float or array_like
        The wet glass transition temperature Tgw [K].
    temperature : float or array_like
        The service temperature T [K].
    dry_tg : float
        The dry glass transition temperature Tgd [K].
    reference_temperature : float
        The temperature T0 at which the dry properties are given [K].

    Returns
    -------
    numpy.ndarray
        The retention P/P0 [-] of the matrix's mechanical properties; NaN where T >= Tgw.

    References
    ----------
    C. C. Chamis, "Simplified composite micromechanics equations for hygral, thermal
    and mechanical properties", NASA TM-83320, 1983.

    S. Singh and S. Sanyal, "Variations in geometry, volume, mass and moment of inertia of
    link of a four bar mechanism made of neat resin under hygrothermal environment",
    *International Journal of Innovative Research in Science, Engineering and
    Technology* 5(12), 2016.
    """
    ratio = (np.asarray(wet_tg, float) - temperature) / (dry_tg - reference_temperature)
    with np.errstate(invalid="ignore"):
        return np.where(ratio > 0.0, np.sqrt(np.where(ratio > 0.0, ratio, 1.0)), np.nan)


def thermal_property_factor(retention):
    """Thermal matrix properties scale by the reciprocal, P0/P (Chamis 1983: 'the effects on
    the thermal properties are the reciprocal'; Singh & Sanyal 2017 eq. 10).

    Parameters
    ----------
    retention : float or array_like
        The mechanical retention P/P0 [-] (:func:`property_retention`).

    Returns
    -------
    numpy.ndarray
        P0/P [-].
    """
    return 1.0 / np.asarray(retention, float)


def secant_thermal_factor(wet_tg, temperature, dry_tg, reference_temperature):
    """Mean of P0/P over [T0, T] at fixed moisture: the factor on the matrix expansion
    coefficient that makes alpha_sec (T - T0) the integral of the instantaneous
    alpha_m P0/P (Chamis' reciprocal rule) from T0 to T:
    (1/(T - T0)) int dT'/sqrt((Tgw - T')/(Tgd - T0))
    = 2 sqrt(Tgd - T0) (sqrt(Tgw - T0) - sqrt(Tgw - T)) / (T - T0),
    -> sqrt((Tgd - T0)/(Tgw - T0)) as T -> T0; finite up to T = Tgw (where the
    instantaneous factor diverges). NaN for T >= Tgw (outside the domain).

    Parameters
    ----------
    wet_tg, temperature, dry_tg, reference_temperature
        Tgw, T, Tgd and T0 [K], as in :func:`property_retention`.

    Returns
    -------
    numpy.ndarray
        The secant factor [-] on the matrix expansion coefficient; NaN where T >= Tgw.

    """
    tgw = np.asarray(wet_tg, float)
    t = np.asarray(temperature, float) + 0.0 * tgw
    span = dry_tg - reference_temperature
    below = (tgw - t) > 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        a = np.sqrt(np.where(below, tgw - reference_temperature, 1.0))
        b = np.sqrt(np.where(below, tgw - t, 1.0))
        dt = t - reference_temperature
        near = np.abs(dt) < 1e-9 * max(span, 1.0)
        secant = 2.0 * np.sqrt(span) * (a - b) / np.where(near, 1.0, dt)
        limit = np.sqrt(span) / a
    return np.where(below, np.where(near, limit, secant), np.nan)


def free_strain(alpha, beta, temperature, reference_temperature, moisture, initial_moisture):
    """eps = alpha (T - T0) + beta (M - M0) (Singh & Sanyal 2017 eqs. 4, 7,
    8; Singh & Sanyal 2016 eq. 13).
    For a non-uniform field, M is the volume mean: the volume average of beta M (exact
    for the outer radius of an axisymmetric disc and for a symmetric sheet).

    Parameters
    ----------
    alpha : float or array_like
        The thermal expansion coefficient [1/K].
    beta : float or array_like
        The moisture expansion coefficient [1/weight %] (strain per weight % of moisture).
    temperature : float or array_like
        The temperature T [K].
    reference_temperature : float
        The strain-free temperature T0 [K].
    moisture : float or array_like
        The moisture content M [weight %].
    initial_moisture : float
        The strain-free moisture M0 [weight %].

    Returns
    -------
    numpy.ndarray
        The free strain [-].

    References
    ----------
    S. Singh and S. Sanyal, "Kinematic and dynamic variations in cam and follower made of
    composite material under hygrothermal environment", *International Journal of
    Innovative Research in Science, Engineering and Technology* 6(3), 2017.
    """
    return alpha * (np.asarray(temperature, float) - reference_temperature) + beta * (
        np.asarray(moisture, float) - initial_moisture)


def wet_mass(dry_mass, moisture):
    """m = m_dry (1 + M/100), M in weight % of dry mass (definition; Singh & Sanyal
    2017 eq. 3).

    Parameters
    ----------
    dry_mass : float or array_like
        The dry mass [kg] (or any mass unit; the result is in the same one).
    moisture : float or array_like
        The moisture content M [weight %].

    Returns
    -------
    numpy.ndarray
        The wet mass, in the unit of ``dry_mass``.
    """
    return dry_mass * (1.0 + np.asarray(moisture, float) / 100.0)


def wet_density(dry_density, moisture, strain_x, strain_y, strain_z):
    """rho = rho_dry (1 + M/100) / ((1 + eps_x)(1 + eps_y)(1 + eps_z)): wet mass over
    swollen volume.

    Parameters
    ----------
    dry_density : float or array_like
        The dry density [kg/m^3].
    moisture : float or array_like
        The moisture content M [weight %].
    strain_x, strain_y, strain_z : float or array_like
        The free strains along the part axes [-].

    Returns
    -------
    numpy.ndarray
        The wet density [kg/m^3].
    """
    return wet_mass(dry_density, moisture) / ((1.0 + strain_x) * (1.0 + strain_y) * (1.0 + strain_z))
