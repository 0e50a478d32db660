"""Monte Carlo draws of a material's fitted parameters with their covariance.

A sweep's ``random:`` entry ``materials.NAME.fit: {draw: covariance}`` draws, per
case, (ln D0, Ea) and (a, b) of material NAME as bivariate normals centred on the
values the base scene holds, with the covariances ``fickcam fit`` recorded under
``materials.NAME.fit.covariance`` (SI 2x2 matrices of (ln pre_exponential,
activation_energy [J/mol]) and (coefficient [%], exponent); the user guide's page
"Materials and fickcam fit"). ln D0 and Ea of a fit across temperatures are strongly correlated (about
+0.99): drawing them independently would spread D at the test temperatures far
more than the data allow, so they are drawn jointly (numpy's
``Generator.multivariate_normal``). D0 is log-normal: it stays positive.
"""
from __future__ import annotations

import math

import numpy as np

from ..quantities.parsing import to_si

#: group -> (key, fickcam.quantities.types dimension or None, unit written into the scene, drawn as log)
GROUPS = {
    "diffusivity": (("pre_exponential", "diffusivity", "m^2/s", True),
                    ("activation_energy", "molar_energy", "J/mol", False)),
    "saturation": (("coefficient", "percent", "%", False), ("exponent", None, "", False)),
}


def _material(path: str, base_data: dict) -> tuple[str, dict]:
    keys = path.split(".")
    if len(keys) != 3 or keys[0] != "materials" or keys[2] != "fit":
        raise ValueError("covariance: true goes with a path materials.NAME.fit")
    material = (base_data.get("materials") or {}).get(keys[1])
    if not isinstance(material, dict):
        raise ValueError(f"no material {keys[1]!r} in the base scene")
    return keys[1], material


def _covariances(name: str, material: dict) -> dict:
    covariance = ((material.get("fit") or {}).get("covariance")) or {}
    groups = {group: matrix for group, matrix in covariance.items() if matrix is not None}
    if not groups:
        raise ValueError(f"materials.{name} has no fit.covariance to draw from (fickcam fit "
                         "writes it)")
    return groups


def fitted_parameters(path: str, base_data: dict) -> list[tuple[str, str | None]]:
    """(dotted path, dimension) of every value a covariance draw of ``path`` sets.

    Parameters
    ----------
    path : str
        ``materials.NAME.fit``.
    base_data : dict
        The base scene as read from YAML.

    Returns
    -------
    list of tuple of (str, str or None)
        The dotted paths of the fitted values and their dimensions (None for a bare number).

    Raises
    ------
    ValueError
        When ``path`` is not ``materials.NAME.fit``, the material or its ``fit.covariance``
        is absent, or a fitted value is not in the base scene.
    """
    name, material = _material(path, base_data)
    out = []
    for group in _covariances(name, material):
        for key, dimension, _, _ in GROUPS[group]:
            if key not in (material.get(group) or {}):
                raise ValueError(f"materials.{name}.{group}.{key} is not in the base scene: the "
                                 "fitted values are drawn around it")
            out.append((f"materials.{name}.{group}.{key}", dimension))
    return out


def draw_fitted(path: str, base_data: dict, rng: np.random.Generator, count: int) -> dict[str, list]:
    """``count`` joint draws of each fitted value, by dotted path.

    (ln D0, Ea) and (a, b) are drawn as bivariate normals centred on the base scene's values
    with the recorded covariances (``numpy.random.Generator.multivariate_normal``); D0 is
    log-normal, so it stays positive.

    Parameters
    ----------
    path, base_data
        As for :func:`fitted_parameters`.
    rng : numpy.random.Generator
        The sweep's generator.
    count : int
        The number of draws [1].

    Returns
    -------
    dict of str to list
        Dotted path -> the draws, as strings with units (``m^2/s``, ``J/mol``, ``%``) or bare
        floats (the exponent).

    Raises
    ------
    ValueError
        As :func:`fitted_parameters`.
    """
    name, material = _material(path, base_data)
    out: dict[str, list] = {}
    for group, covariance in _covariances(name, material).items():
        specs = GROUPS[group]
        mean = []
        for key, dimension, _, log in specs:
            value = material[group][key]
            value = to_si(value, dimension) if dimension else float(value)
            mean.append(math.log(value) if log else value)
        draws = rng.multivariate_normal(mean, np.asarray(covariance, float), count)
        for column, (key, _, unit, log) in enumerate(specs):
            values = np.exp(draws[:, column]) if log else draws[:, column]
            out[f"materials.{name}.{group}.{key}"] = [f"{v:.12g} {unit}" if unit else float(v)
                                                      for v in values]
    return out
