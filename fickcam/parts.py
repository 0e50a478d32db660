"""The bodies a scene ages, and their per-part results gathered into arrays.

A :class:`Part` is one body (cam, follower, a link) with its material and
diffusion geometry; a :class:`PartHistory` is what diffusion and the material
state give for it over the ageing times (or, for the as-designed state, at one
time). :func:`part_values` stacks the histories into ``(time, part)`` arrays
named after the schema (:mod:`fickcam.schema`); :func:`field_values` does the
same for the moisture fields.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np


@dataclass
class Part:
    """One body that ages: its name, material, diffusion geometry and dry mass."""

    name: str
    material_name: str
    material: object
    geometry: object | None  # diffusion geometry (None: the part does not absorb)
    dry_mass: float | None = None


@dataclass
class PartHistory:
    """What diffusion and the material state give for one part over ageing."""

    part: Part
    diffusion: object | None
    state: dict = field(default_factory=dict)
    valid: np.ndarray | None = None  # bool over ageing times

    def at_rows(self, rows: np.ndarray) -> "PartHistory":
        """The history at the ageing times ``rows`` (indices) only: every array over time
        (state, validity, moisture and fields) taken at those rows."""
        n = len(self.valid)

        def take(value):
            return value[rows] if np.ndim(value) >= 1 and np.shape(value)[0] == n else value

        result = self.diffusion
        if result is not None:
            result = replace(result, times=result.times[rows], mean=result.mean[rows],
                                         surface=result.surface[rows],
                                         fields=None if result.fields is None
                                         else result.fields[rows])
        return PartHistory(self.part, result, {k: take(v) for k, v in self.state.items()},
                           self.valid[rows])


def build_parts(scene) -> list[Part]:
    """The parts a scene models, in a fixed order (cam, follower, links)."""
    parts: list[Part] = []
    model = scene.model
    if model.cam is not None:
        from .cam import scene_parts as cam_parts

        parts += [Part(name, mat, scene.materials[mat], geometry, mass)
                  for name, mat, geometry, mass in cam_parts(model.cam, scene.materials)]
    if model.linkage is not None:
        from .linkage import scene_parts as linkage_parts

        parts += [Part(name, mat, scene.materials[mat], geometry, mass)
                  for name, mat, geometry, mass in linkage_parts(model.linkage, scene.materials)]
    for part in parts:
        if not getattr(part.material, "absorbs", False):
            part.geometry = None
    return parts


def part_mass(history: PartHistory) -> np.ndarray:
    """m = m_dry (1 + M/100) (Singh & Sanyal 2017 eq. 3 inverted), NaN where not given."""
    dry = history.part.dry_mass
    moisture = np.asarray(history.state["moisture_content"], float)
    return np.full_like(moisture, np.nan) if dry is None else dry * (1 + moisture / 100.0)


def part_values(histories: list[PartHistory]) -> dict[str, np.ndarray]:
    """Every state variable of the parts as a (time, part) array (the schema names them;
    an unknown name fails when the Dataset is built). Numbers are NaN at the times a
    part is not computed; flags (bool) are kept as they are."""
    states = [dict(h.state, mass=part_mass(h)) for h in histories]
    names = list(dict.fromkeys(name for state in states for name in state))
    values = {}
    for name in names:
        columns = []
        for history, state in zip(histories, states):
            value = np.asarray(state.get(name, np.nan))
            value = np.broadcast_to(value, history.valid.shape)
            columns.append(value if value.dtype == bool else np.where(history.valid, value, np.nan))
        values[name] = np.stack(columns, axis=1)
    return values


def diffusion_attrs(history: PartHistory) -> dict:
    """The diffusion plan and error a part's result records in the dataset attributes."""
    result = history.diffusion
    if result is None and history.part.geometry is not None:
        return {"model": "state", "error_estimate": 0.0, "cells": 0, "steps": 0,
                "reason": "uniform moisture given by the environment's state (no diffusion)"}
    if result is None:
        return {"model": "none", "error_estimate": 0.0, "cells": 0, "steps": 0,
                "reason": "material does not absorb moisture"}
    return {"model": result.model, "error_estimate": float(result.error_estimate),
            "cells": int(result.cells), "steps": int(result.steps), "reason": result.reason}


def field_values(histories: list[PartHistory], times) -> tuple[dict, dict]:
    """(values, coords): moisture fields of every absorbing part, padded with NaN to a
    common cell count; empty when no part stored fields."""
    with_fields = [h for h in histories if h.diffusion is not None and
                   getattr(h.diffusion, "fields", None) is not None]
    if not with_fields:
        return {}, {}
    n_cells = max(h.diffusion.fields.shape[1] for h in with_fields)
    n_parts = len(histories)
    moisture = np.full((len(times), n_parts, n_cells), np.nan)
    cell = {axis: np.full((n_parts, n_cells), np.nan) for axis in ("x", "y", "z")}
    for index, history in enumerate(histories):
        result = history.diffusion
        if result is None or getattr(result, "fields", None) is None:
            continue
        n = result.fields.shape[1]
        moisture[:, index, :n] = result.fields
        for axis, array in cell.items():
            if axis in result.cell_coordinates:
                array[index, :n] = result.cell_coordinates[axis]
    values = {"moisture": moisture} | {f"cell_{axis}": array for axis, array in cell.items()}
    return values, {"cell": np.arange(n_cells)}
