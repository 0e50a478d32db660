"""What the run gives for the bodies a scene ages, gathered into arrays.

A :class:`~fickcam.mechanisms.part.Part` is one body (cam, follower, a link) with its
material and diffusion geometry, as its mechanism builds it; a :class:`PartHistory` is
what diffusion and the material state give for it over the ageing times (or, for the
as-designed state, at one time). :func:`part_values` stacks the histories into ``(time, part)`` arrays
named after the schema (:mod:`fickcam.schema`); :func:`field_values` does the
same for the moisture fields.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..mechanisms.part import Part


@dataclass
class PartHistory:
    """What diffusion and the material state give for one part over ageing.

    Parameters
    ----------
    part : Part
        The part.
    diffusion : fickcam.diffusion.DiffusionResult or None
        Its moisture uptake; None when it does not absorb or its state is given.
    state : dict
        Material state variables by schema name, each over the ageing times [schema units].
    valid : numpy.ndarray of bool, optional
        Over ageing times: where the part's state is in the model's domain.
    sheet : fickcam.elastic.thickness.SheetProfile, optional
        The exact sheet of its thickness under its exposure [weight %], for a part whose
        moisture field its mechanism reads (``field_parts``); None otherwise.
    """

    part: Part
    diffusion: object | None
    state: dict = field(default_factory=dict)
    valid: np.ndarray | None = None  # bool over ageing times
    sheet: object | None = None

    def at_rows(self, rows: np.ndarray) -> "PartHistory":
        """The history at the ageing times ``rows`` only.

        Every array over time (state, validity, moisture and fields) is taken at those rows.

        Parameters
        ----------
        rows : numpy.ndarray of int
            Indices along the ageing times.

        Returns
        -------
        PartHistory
            A new history.
        """
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


def part_mass(history: PartHistory) -> np.ndarray:
    """The part's mass with its moisture, m = m_dry (1 + M/100).

    This is the weight-gain definition of moisture content, M = 100 (m - m_dry)/m_dry,
    inverted (Singh & Sanyal 2017, eq. 3).

    Parameters
    ----------
    history : PartHistory
        The part's history, with ``moisture_content`` [wt %] in its state.

    Returns
    -------
    numpy.ndarray
        The mass over ageing times [kg]; NaN where the dry mass is not given.

    References
    ----------
    S. Singh and S. Sanyal, "Kinematic and dynamic variations in cam and follower made
    of composite material under hygrothermal environment", International Journal of
    Innovative Research in Science, Engineering and Technology 6 (3), 2017.
    """
    dry = history.part.dry_mass
    moisture = np.asarray(history.state["moisture_content"], float)
    return np.full_like(moisture, np.nan) if dry is None else dry * (1 + moisture / 100.0)


def part_values(histories: list[PartHistory], wanted=None) -> dict[str, np.ndarray]:
    """Every state variable of the parts as a (time, part) array.

    The schema names them (an unknown name fails when the Dataset is built). Numbers are
    NaN at the times a part is not computed; flags (bool) are kept as they are. ``mass``
    (:func:`part_mass`) is added.

    Parameters
    ----------
    histories : list of PartHistory
        One per part, in the parts' order.
    wanted : frozenset of str, optional
        Only these variables (those a caller reads); None: every one.

    Returns
    -------
    dict of str to numpy.ndarray
        Variable name -> (time, part) values [schema units].
    """
    states = [dict(h.state, mass=part_mass(h)) for h in histories]
    names = [name for name in dict.fromkeys(name for state in states for name in state)
             if wanted is None or name in wanted]
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
    """The diffusion plan and error a part's result records in the dataset attributes.

    Parameters
    ----------
    history : PartHistory
        The part's history.

    Returns
    -------
    dict
        ``model``, ``error_estimate`` [-], ``cells`` [1], ``steps`` [1] and ``reason``
        (``model`` is "state" for a state given directly, "none" for a part that does not
        absorb).
    """
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
    """(values, coords): the absorbing parts' moisture fields, NaN-padded to one cell count.

    Parameters
    ----------
    histories : list of PartHistory
        One per part.
    times : array_like
        The ageing times [s] (their count sizes the arrays).

    Returns
    -------
    values : dict of str to numpy.ndarray
        ``moisture`` (time, part, cell) [wt %] and ``cell_x``, ``cell_y``, ``cell_z``
        (part, cell), the cells' coordinates [m]; empty when no part stored fields.
    coords : dict of str to numpy.ndarray
        ``cell``: the cell index.
    """
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
