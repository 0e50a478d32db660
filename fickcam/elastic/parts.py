"""The swelling-stress variables over (time, part) of the parts that get an elastic
analysis (``cam.elastic``, ``linkage.elastic``: each mechanism's ``elastic_parts``), for
:mod:`fickcam.simulation.simulate`."""
from __future__ import annotations

import numpy as np

from ..diffusion import Diffusivity, Sheet, solve
from .thickness import SheetProfile

DEPTH_STRIDE = 2   # every other cell of the exact sheet field (40 cells) between face and mid-plane
SWELLING = ("swelling_stress_tensile", "swelling_stress_compressive", "failure_index")


def sheet_profile(part, exposure, times) -> SheetProfile | None:
    """``exact_sheet`` of the part's thickness under its exposure, with its
    through-thickness diffusivity; None for a part without a diffusion geometry.

    Parameters
    ----------
    part : Part
        The part (thickness [m], material).
    exposure : fickcam.diffusion.Exposure
        Its surface moisture [weight %] and temperature [K] over time.
    times : array_like
        Ageing times [s].

    Returns
    -------
    SheetProfile or None
        The sheet's moisture [weight %] through the thickness.
    """
    if part.geometry is None:
        return None
    d = part.material.diffusivity_for(part.geometry)
    dz = float(d.pre_exponential[2])
    return exact_sheet(part.geometry.thickness, Diffusivity((dz, dz, dz), d.activation_energy),
                       exposure, times, part.name)


def exact_sheet(thickness, diffusivity, exposure, times, name: str = "") -> SheetProfile:
    """The exact moisture of an infinite sheet under an exposure (the engine's series,
    Crank 1975 eq. 4.17, superposed over the history).

    Parameters
    ----------
    thickness : float
        Sheet thickness [m].
    diffusivity : fickcam.diffusion.Diffusivity
        Its diffusivity (the through-thickness value is used) [m^2/s].
    exposure : fickcam.diffusion.Exposure
        Surface value and temperature over time.
    times : array_like
        Ageing times [s].
    name : str
        The part's name for messages.

    Returns
    -------
    SheetProfile
        From a face (the surface value; at t = 0 still the initial moisture) to the
        mid-plane at every ``DEPTH_STRIDE``-th cell of the series' field, and the mean.
    """
    result = solve(Sheet(thickness), diffusivity, exposure, times, model="analytic",
                   store_fields=True, part=name)
    z = np.asarray(result.cell_coordinates["z"])
    fields = np.asarray(result.fields)
    half = z <= 0.5 * thickness
    order = np.argsort(z[half])
    inside = fields[:, half][:, order]
    mid = 0.5 * (inside[:, -1] + fields[:, ~half][:, np.argmin(z[~half])])
    times = np.asarray(times, float)
    face = np.where(times > 0, exposure.surface_moisture(times), exposure.initial_moisture)
    depths = np.concatenate([[0.0], z[half][order][::DEPTH_STRIDE], [0.5 * thickness]])
    return SheetProfile(depths, np.column_stack([face, inside[:, ::DEPTH_STRIDE], mid]),
                        np.asarray(result.mean, float))


def swelling_variables(histories, names: set[str], seen) -> tuple[dict[str, np.ndarray], dict]:
    """(values, coords): (time, part) arrays of the swelling variables (NaN for parts not
    asked for) and each part's face stress field at its worst time over (part,
    stress_point), padded with NaN.

    Parameters
    ----------
    histories : list of PartHistory
        The parts' ageing.
    names : set of str
        The parts asked for (the scene's ``elastic_parts``).
    seen : fickcam.climate.environment.ClimateSeen
        The climate at the ageing times [s]: temperature [K], the parts' exposures, and
        the history's reference temperature [K] and initial moisture [weight %].

    Returns
    -------
    values : dict
        swelling_stress_tensile/compressive [Pa] and failure_index [-] over (time, part).
    coords : dict
        The face stress fields [Pa] and their points [m] over (part, stress_point).
    """
    from .swelling import swelling_history  # scikit-fem: only a scene that asks for stress

    temperature, environment = seen.temperature, seen.environment
    out = {name: np.full((len(temperature), len(histories)), np.nan) for name in SWELLING}
    fields = {}
    for column, history in enumerate(histories):
        if history.part.name not in names:
            continue
        result = swelling_history(history.part.geometry, history.part.material, history.diffusion,
                                  history.state, temperature, environment.reference_temperature,
                                  environment.initial_moisture, history.valid,
                                  _sheet_of(history, seen))
        for name in SWELLING:
            out[name][:, column] = result[name]
        if "field" in result:
            fields[column] = (result["field"], result["points"])
    if not fields:
        return out, {}
    count = max(len(field) for field, _ in fields.values())
    stored = {name: np.full((len(histories), count), np.nan) for name in
              ("swelling_stress_field", "stress_point_x", "stress_point_y")}
    for column, (field, points) in fields.items():
        stored["swelling_stress_field"][column, :len(field)] = field
        stored["stress_point_x"][column, :len(field)] = points[:, 0]
        stored["stress_point_y"][column, :len(field)] = points[:, 1]
    return out | stored, {"stress_point": np.arange(count)}


def _sheet_of(history, seen) -> SheetProfile | None:
    """The history's exact sheet, else the one of its part's thickness under its exposure."""
    if history.sheet is not None or history.part.geometry is None:
        return history.sheet
    return sheet_profile(history.part, seen.exposures[history.part.name], seen.times)
