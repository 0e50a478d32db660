"""Material state over ageing time: wet Tg, retention, moduli, strains, density.

Order per time (Chamis 1983 NASA TM-83320; Singh & Sanyal 2017, Table 10):
ply moisture (diffusion) -> matrix moisture (Chamis M_l relation, inverted) -> wet Tg
-> retention P/P0 -> degraded matrix -> micromechanics -> ply properties -> free strain.
Expansion coefficients are reported as Chamis' instantaneous values (alpha_m P0/P); the
free thermal strain uses the secant value that integrates them from T0 to T
(hygrothermal.secant_thermal_factor), which stays finite as T approaches the wet Tg.
"""
from __future__ import annotations

import logging

import numpy as np

from ..errors import PhysicsDomainError
from ..messages import warn
from .micromechanics import quasi_isotropic_elastic
from .hygrothermal import (
    KELVIN_OFFSET,
    free_strain,
    property_retention,
    secant_thermal_factor,
    wet_density,
    wet_glass_transition_temperature,
)

log = logging.getLogger(__name__)

#: ply-property key -> result name (SI)
_MODULI = {"e11": "longitudinal_modulus", "e22": "transverse_modulus", "g12": "shear_modulus",
           "g23": "transverse_shear_modulus", "nu12": "poisson_ratio",
           "nu23": "transverse_poisson_ratio"}
_SURFACE = ("e11", "e22", "g12", "nu12")


def moisture_modulus_retention(table, moisture):
    """E(M)/E_dry of a thermoplastic from its moisture-modulus table (library
    ``moisture_modulus: {moisture: [...] %, retention: [...]}``, sourced per material):
    piecewise linear in the moisture content, held beyond the last entry.

    Parameters
    ----------
    table : dict
        ``moisture`` [weight %] and ``retention`` [-] columns, moisture increasing.
    moisture : float or array_like
        The moisture content [weight %].

    Returns
    -------
    numpy.ndarray
        E(M)/E_dry [-].
    """
    return np.interp(moisture, table["moisture"], table["retention"])


def wet_tg_and_retention(material, ply_moisture, temperature, reference_temperature):
    """(matrix moisture %, wet Tg K, retention) at the given ply moisture. A thermoset takes
    Chamis' wet Tg and retention; a thermoplastic with a moisture-modulus table takes its
    retention from the table (water plasticises it, Tg NaN); metals and materials with
    neither have Tg NaN and retention 1.

    Parameters
    ----------
    material : Material
        The part's material.
    ply_moisture : array_like
        The ply (diffusion) moisture [weight %].
    temperature : array_like
        The service temperature [K].
    reference_temperature : float
        The temperature T0 of the dry properties [K].

    Returns
    -------
    tuple of numpy.ndarray
        The matrix moisture [weight %], the wet Tg [K] and the retention P/P0 [-].
    """
    temperature = np.asarray(temperature, float)
    matrix_m = np.asarray(material.matrix_moisture(ply_moisture), float) + 0.0 * temperature
    tgd = material.dry_glass_transition_temperature
    table = material.matrix.get("moisture_modulus")
    if material.kind != "metal" and tgd is None and table:
        return (matrix_m, np.full_like(matrix_m, np.nan),
                moisture_modulus_retention(table, matrix_m))
    if tgd is None or material.kind == "metal":
        return matrix_m, np.full_like(matrix_m, np.nan), np.ones_like(matrix_m)
    tgw = wet_glass_transition_temperature(tgd, matrix_m, material.wet_tg_scale)
    return matrix_m, tgw, property_retention(tgw, temperature, tgd, reference_temperature)


def _secant_factor(material, wet_tg, temperature, reference_temperature):
    """Secant thermal factor (see hygrothermal.secant_thermal_factor); 1 without a Tg."""
    tgd = material.dry_glass_transition_temperature
    if tgd is None or material.kind == "metal":
        return np.ones_like(np.asarray(temperature, float))
    return secant_thermal_factor(wet_tg, temperature, tgd, reference_temperature)


def surface_in_plane_modulus(material, props):
    """One in-plane modulus of the contact layer: the rotational (laminate-invariant) average
    (U1^2 - U4^2)/U1 of the ply for a UD composite, whose contact direction turns around a
    cam profile (Tsai & Hahn 1980 ch. 7); the modulus itself for isotropic and QI.

    Parameters
    ----------
    material : Material
        The cam's material.
    props : dict of str to array_like
        Its ply properties (:meth:`fickcam.materials.material.Material.ply_properties`), moduli [Pa].

    Returns
    -------
    numpy.ndarray
        The in-plane modulus [Pa].

    References
    ----------
    S. W. Tsai and H. T. Hahn, *Introduction to Composite Materials*, Technomic, 1980,
    ch. 7.
    """
    if material.fiber is None or material.layup == "quasi_isotropic":
        return np.asarray(props["e11"], float)
    return quasi_isotropic_elastic(props["e11"], props["e22"], props["g12"], props["nu12"])[0]


def first_invalid_index(temperature, *wet_tgs) -> int | None:
    """Index of the first time at which T >= any of the given wet Tg arrays, else None.

    Parameters
    ----------
    temperature : array_like
        The service temperature at each time [K].
    *wet_tgs : array_like
        Wet glass transition temperatures at each time [K] (NaN: none).

    Returns
    -------
    int or None
        The first index reached, or None.
    """
    temperature = np.asarray(temperature, float)
    reached = np.zeros(temperature.shape, bool)
    for tg in wet_tgs:
        reached |= temperature >= np.asarray(tg, float)  # NaN Tg compares False
    hits = np.nonzero(reached)[0]
    return int(hits[0]) if hits.size else None


def wet_tg_error(part, times, index, temperature, state) -> PhysicsDomainError:
    """The error for T reaching the wet Tg at ``index``; carries ``index`` and ``state``
    (every variable truncated to the valid times before ``index``).

    Parameters
    ----------
    part : str
        The part's name.
    times : numpy.ndarray
        Ageing times [s].
    index : int
        The first time at which T reaches the wet Tg.
    temperature : numpy.ndarray
        Service temperature at the ageing times [K].
    state : dict
        The material state over the ageing times (temperatures [K], moisture [weight %]).

    Returns
    -------
    PhysicsDomainError
        The error, with ``index`` and the truncated ``state``.
    """
    tg = min(state["glass_transition_temperature"][index], state["surface_glass_transition_temperature"][index])
    message = (f"service temperature {temperature[index] - KELVIN_OFFSET:.1f} degC reached the wet Tg "
               f"{tg - KELVIN_OFFSET:.1f} degC (mean moisture {state['moisture_content'][index]:.3g} %, "
               f"surface {state['surface_moisture_content'][index]:.3g} %); the part is not computed "
               f"from then on, earlier results are kept")
    error = PhysicsDomainError(part, float(times[index]), message, span=float(np.max(times)))
    error.index = index
    error.state = {k: v[:index] for k, v in state.items()}
    return error


def _free_strains(material, bulk, secant, temperature, reference_temperature, mean,
                  initial_moisture) -> tuple:
    """The free strains along the part's x, y and z [-] (``hygrothermal.free_strain``): the
    secant thermal and the bulk moisture expansion of the ply axes (y in-plane: 11 for a
    quasi-isotropic layup, else 22); a metal's thermal alone."""
    dT_args = (temperature, reference_temperature)
    if material.kind == "metal":
        strain = free_strain(bulk["alpha11"], 0.0, *dT_args, 0.0, 0.0)
        return strain, strain, strain
    in_plane = "11" if material.layup == "quasi_isotropic" else "22"
    strain_x = free_strain(secant["alpha11"], bulk["beta11"], *dT_args, mean, initial_moisture)
    strain_y = free_strain(secant["alpha" + in_plane], bulk["beta" + in_plane], *dT_args, mean,
                           initial_moisture)
    strain_z = free_strain(secant["alpha22"], bulk["beta22"], *dT_args, mean, initial_moisture)
    return strain_x, strain_y, strain_z


def _moduli(material, bulk, skin, temperature) -> dict:
    """The bulk and surface moduli of the state, each as long as ``temperature`` [Pa]."""
    moduli = {name: np.asarray(bulk[key], float) + 0.0 * temperature
              for key, name in _MODULI.items()}
    moduli.update({f"surface_{_MODULI[key]}": np.asarray(skin[key], float) + 0.0 * temperature
                   for key in _SURFACE})
    moduli["surface_modulus"] = surface_in_plane_modulus(material, skin) + 0.0 * temperature
    return moduli


def material_state(material, temperature, moisture, surface_moisture, reference_temperature,
                   initial_moisture, part: str = "", times=None, raise_on_wet_tg: bool = False):
    """State of one part at each ageing time: SI arrays (moisture in weight %) named as in
    :mod:`fickcam.schema`, of the length of ``temperature``; times with T >= wet Tg (bulk or
    surface) hold NaN and ``within_wet_tg`` False (Chamis 1983).

    Parameters
    ----------
    material : Material
    temperature, moisture, surface_moisture : array_like
        Service temperature [K], volume-mean and contact-layer ply moisture [weight %].
    reference_temperature, initial_moisture : float
        T0 [K] and M0 [weight %] of the dry, strain-free design.
    part, times, raise_on_wet_tg
        With ``raise_on_wet_tg`` (needs the ageing ``times`` [s]) a PhysicsDomainError naming
        ``part`` is raised at the first such time, carrying ``.index`` and ``.state`` (results
        before it).

    Returns
    -------
    dict of str to numpy.ndarray

    Raises
    ------
    fickcam.errors.PhysicsDomainError
        With ``raise_on_wet_tg``, where the service temperature reaches the wet glass
        transition temperature (:func:`wet_tg_error`).
    """
    temperature = np.asarray(temperature, float)
    mean = np.asarray(moisture, float) + 0.0 * temperature
    surface = np.asarray(surface_moisture, float) + 0.0 * temperature
    matrix_m, tgw, retention = wet_tg_and_retention(material, mean, temperature, reference_temperature)
    matrix_s, tgw_s, retention_s = wet_tg_and_retention(material, surface, temperature,
                                                        reference_temperature)
    if np.nanmax(matrix_s, initial=0.0) > 10.0:
        warn("%s: matrix moisture %.3g %% exceeds 10 %%, the range of Chamis' wet-Tg fit",
             part or material.name, np.nanmax(matrix_s))
    bulk = material.ply_properties(retention)
    skin = material.ply_properties(retention_s)
    secant = material.ply_properties(retention, _secant_factor(material, tgw, temperature,
                                                               reference_temperature))
    strain_x, strain_y, strain_z = _free_strains(material, bulk, secant, temperature,
                                                 reference_temperature, mean, initial_moisture)
    state = {
        "moisture_content": mean,
        "surface_moisture_content": surface,
        "matrix_moisture_content": matrix_m,
        "surface_matrix_moisture_content": matrix_s,
        "glass_transition_temperature": tgw,
        "surface_glass_transition_temperature": tgw_s,
        "property_retention": retention,
        "surface_property_retention": retention_s,
        "mass_ratio": 1.0 + mean / 100.0,
        "density": wet_density(material.dry_density, mean, strain_x, strain_y, strain_z),
        "strain_longitudinal": strain_x,
        "strain_transverse": strain_y,
        "strain_through_thickness": strain_z,
        "hygrothermal_strain": strain_x,
        "secant_thermal_expansion_longitudinal": secant["alpha11"],
        "secant_thermal_expansion_transverse": secant["alpha22"],
        "thermal_expansion_longitudinal": bulk["alpha11"],
        "thermal_expansion_transverse": bulk["alpha22"],
        "moisture_expansion_longitudinal": bulk["beta11"],
        "moisture_expansion_transverse": bulk["beta22"],
        "thermal_conductivity_longitudinal": bulk["k11"],
        "thermal_conductivity_transverse": bulk["k22"],
        **_moduli(material, bulk, skin, temperature),
    }
    index = first_invalid_index(temperature, tgw, tgw_s)
    state["within_wet_tg"] = np.arange(temperature.size) < (temperature.size if index is None else index)
    if index is not None:
        error = wet_tg_error(part, times if times is not None else np.arange(temperature.size),
                             index, temperature, state)
        log.debug("%s", error)
        if raise_on_wet_tg:
            raise error
    return state

