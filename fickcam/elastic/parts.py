"""Which parts get an elastic analysis (``cam.elastic``, ``linkage.elastic``) and their
swelling-stress variables over (time, part), for :mod:`fickcam.simulate`."""
from __future__ import annotations

import numpy as np

SWELLING = ("swelling_stress_tensile", "swelling_stress_compressive", "failure_index")


def elastic_parts(model) -> set[str]:
    """Names of the parts whose swelling stress the scene asks for."""
    names: set[str] = set()
    if model.cam is not None and model.cam.elastic:
        names.add("cam")
    if model.linkage is not None and model.linkage.elastic:
        names.update(("crank", "coupler", "rocker", "frame"))
    return names


def swelling_variables(histories, names: set[str], temperature, reference, initial_moisture
                       ) -> dict[str, np.ndarray]:
    """(time, part) arrays of the swelling variables; NaN for parts not asked for."""
    from .swelling import swelling_history

    out = {name: np.full((len(temperature), len(histories)), np.nan) for name in SWELLING}
    for column, history in enumerate(histories):
        if history.part.name not in names:
            continue
        result = swelling_history(history.part.geometry, history.part.material, history.diffusion,
                                  history.state, temperature, reference, initial_moisture,
                                  history.valid)
        for name in SWELLING:
            out[name][:, column] = result[name]
    return out
