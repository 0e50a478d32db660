"""The unit-step response of an operator in scaled time (Richardson-extrapolated backward
Euler on geometric steps), interpolated between its nodes, and its blend with a
short-time expansion (``short_time``) for the plane model."""
from __future__ import annotations

import logging
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..planform.short_time import weighted
from . import march as marching
from .pchip import Pchip
from .step_plans import StepPlan
from .step_plans import geometric_steps

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class StepResponse:
    """Unsaturated fraction u(tau*) of a unit surface step, on geometric nodes.

    Parameters
    ----------
    nodes : numpy.ndarray
        The scaled times tau* [-], ``nodes[0] = 0``.
    mean : numpy.ndarray
        The unsaturated fraction of the mean content [-] at each node, shape (n,).
    layer : numpy.ndarray
        The unsaturated fraction of the surface layer's content [-], shape (n,).
    fields : numpy.ndarray or None
        The unsaturated fraction in each cell [-], shape (n, cells), when kept.
    """

    nodes: np.ndarray        # scaled time, nodes[0] = 0
    mean: np.ndarray         # (n,)
    layer: np.ndarray        # (n,)
    fields: np.ndarray | None  # (n, cells)

    def at(self, tau: np.ndarray, values: np.ndarray) -> np.ndarray:
        """u at arbitrary tau* >= 0: PCHIP in log tau, u = 1 - (1 - u_1) sqrt(tau/tau_1) below
        the first step (Crank 1975 eq. 4.20: early uptake grows as sqrt(t))."""
        tau = np.asarray(tau, float)
        first = self.nodes[1]
        spline = (self._mean_spline if values is self.mean else
                  self._layer_spline if values is self.layer else self._spline(values))
        inside = np.clip(tau, first, self.nodes[-1])
        out = spline(np.log(inside))
        early = tau < first
        if early.any():
            ratio = np.sqrt(np.clip(tau[early], 0.0, None) / first)
            out[early] = 1.0 - (1.0 - values[1]) * (ratio[:, None] if values.ndim > 1 else ratio)
        return out


    def _spline(self, values: np.ndarray) -> Pchip:
        return Pchip.through(np.log(self.nodes[1:]), values[1:])

    @cached_property
    def _mean_spline(self):
        """The mean's interpolant, built once (the response is read at every solve's times)."""
        return self._spline(self.mean)

    @cached_property
    def _layer_spline(self):
        return self._spline(self.layer)


def step_response(disc, end: float, per_doubling: int, first_step: float, *,
                  keep_fields: bool = False, part: str = "") -> tuple[StepResponse, float]:
    """Backward-Euler unit-step response, Richardson-extrapolated in time.

    The march runs on geometric steps and on the steps halved; 2 fine - coarse is the
    response. The fields come from the operator with its mass lumped
    (``Discretisation.lumped``: the operator itself for finite volumes), whose fields
    are bounded.

    Parameters
    ----------
    disc : Discretisation
        The spatial operator in scaled coordinates.
    end : float
        The last scaled time tau* [-] to reach.
    per_doubling : int
        Steps of equal size before the step doubles.
    first_step : float
        The first step [-] (scaled time).
    keep_fields : bool
        Also keep the cell values.
    part : str
        The part's name, for progress messages.

    Returns
    -------
    StepResponse
        The extrapolated unsaturated fractions [-].
    float
        The largest coarse/fine difference of the mean [-] (the time-error indicator).
    """
    nodes = geometric_steps(0.0, end, first_step, per_doubling)
    fine = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    grids = [(grid, np.searchsorted(grid, nodes)) for grid in (nodes, fine)]
    monotone = disc.lumped()
    coarse, refined = (_unit_march(disc, grid, at, keep_fields and monotone is disc, part)
                       for grid, at in grids)
    with_fields = ((coarse, refined) if monotone is disc or not keep_fields else
                   [_unit_march(monotone, grid, at, True, part) for grid, at in grids])

    def unsaturated(a, b):
        return 1.0 - (2.0 * b - a)
    fields = unsaturated(with_fields[0].fields, with_fields[1].fields) if keep_fields else None
    pair = float(np.max(np.abs(refined.mean - coarse.mean)))
    return StepResponse(nodes, unsaturated(coarse.mean, refined.mean),
                        unsaturated(coarse.layer, refined.layer), fields), pair


def _unit_march(disc, grid: np.ndarray, outputs: np.ndarray, keep_fields: bool, part: str):
    """A unit step of the surface value at t = 0 from 0 (``march.march``)."""
    return marching.march(disc, StepPlan.without_jumps(grid, np.ones(grid.size), outputs), 0.0,
                          keep_fields=keep_fields, part=part)


def blend(response: StepResponse, values: np.ndarray, series, indicator, tolerance: float,
          weight):
    """Join a short-time expansion and the mesh's step response, with an error bound.

    The unsaturated fraction comes from the short-time expansion ``series`` up to a
    switch node and from the mesh after it; ``error_at`` bounds its error at any tau*.
    Errors are weighted by ``weight``, the sheet's unsaturated fraction that multiplies
    the planform's in the product.

    The expansion is kept while its ``indicator`` is below ``tolerance`` or below half
    the mesh-expansion mismatch at that time (then the mesh is the worse of the two; the
    mesh is graded for the times after the switch, so its early mismatch says nothing
    about later). At each node the mesh's relative uptake error is at most (mismatch +
    indicator) / uptake; by the error model of ``p1``, MESH_ERROR (h0 / sqrt(tau) +
    GROWTH_REACH g)^2, it only falls with time, so the least of these bounds over the
    octave before the switch holds after it, and the mesh's error there is that ratio
    times the uptake. Before the switch the error is the weighted indicator.

    Parameters
    ----------
    response : StepResponse
        The mesh's step response (its nodes in scaled time [-]).
    values : numpy.ndarray
        The mesh's unsaturated fraction [-] at the response's nodes.
    series : callable
        tau* [-] -> the expansion's uptake fraction [-].
    indicator : callable
        tau* [-] -> the expansion's error indicator [-].
    tolerance : float
        The error [-] below which the expansion is kept.
    weight : callable
        tau* [-] -> the weight [-] applied to errors.

    Returns
    -------
    fraction : callable
        tau* [-] -> the unsaturated fraction [-].
    error_at : callable or None
        tau* [-] -> the bound of its error [-]; None where the mesh alone serves (no
        switch).
    """
    nodes = response.nodes[1:]
    w = weight(nodes)
    expected = weighted(indicator(nodes), w)
    mismatch = np.abs(values[1:] - (1.0 - series(nodes))) * w
    trusted = expected <= np.maximum(tolerance, 0.5 * mismatch)
    last = int(np.argmin(trusted)) - 1 if not trusted.all() else nodes.size - 1
    if last < 0:
        return (lambda tau: response.at(tau, values)), None
    switch = float(nodes[last]) if last < nodes.size - 1 else np.inf  # inf: expansion only
    ratio = 0.0
    if last < nodes.size - 1:
        octave = (nodes >= 0.5 * switch) & (nodes <= switch)
        uptake = np.maximum(1.0 - values[1:], np.finfo(float).tiny)
        # |mesh error| <= mismatch + |expansion error| <= mismatch + indicator at every
        # node of the octave, and the mesh's relative error only falls: the least bound
        ratio = float(np.min((mismatch + expected)[octave] / (uptake[octave] * w[octave])))

    def fraction(tau):
        tau = np.asarray(tau, float)
        early = tau < switch
        out = response.at(tau, values)
        if early.any():
            out[early] = 1.0 - series(tau[early])
        return out

    def error_at(tau):
        tau = np.atleast_1d(np.asarray(tau, float))
        out = weighted(indicator(tau), weight(tau))
        late = tau >= switch
        if late.any():
            uptake = np.maximum(1.0 - response.at(tau[late], values), np.finfo(float).tiny)
            out[late] = ratio * uptake * weight(tau[late])
        return out
    log.debug("switch to mesh at tau*=%.3g, ratio %.2g", switch, ratio)
    return fraction, error_at
