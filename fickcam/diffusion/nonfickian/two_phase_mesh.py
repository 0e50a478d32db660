r"""Two-phase (Langmuir) free and bound water on the direct FiPy finite-volume models
(slab, axisymmetric disc/annulus, solid bar and prisms of cam plates and links).

The coupled system (Carter & Kibler 1978 eqs. 1-2, ``sorption``) on a mesh with
FiPy's assembled operator (M = diag(volumes), K, f; ``fipy_backend.assemble``) is the
block system

.. math::

    \begin{bmatrix} M & 0 \\ 0 & M \end{bmatrix} \frac{d}{dt}
    \begin{bmatrix} n \\ N \end{bmatrix}
    = -\begin{bmatrix} K + \gamma M & -\beta M \\ -\gamma M & \beta M \end{bmatrix}
    \begin{bmatrix} n \\ N \end{bmatrix} + \begin{bmatrix} g f \\ 0 \end{bmatrix},

:math:`g = \beta/(\gamma + \beta)\, M_s` the free water held on the exposed faces. Backward
Euler on it (step h) eliminates the bound block exactly, because it is diagonal:

.. math::

    N_{new} = \frac{N_{old} + \gamma h\, n_{new}}{1 + \beta h}, \qquad
    \Big(M \big(\tfrac{1}{h} + \tfrac{\gamma}{1 + \beta h}\big) + K\Big)\, n_{new}
    = M \Big(\frac{n_{old}}{h} + \frac{\beta N_{old}}{1 + \beta h}\Big) + g f:

the Fickian step of ``march.ThetaStepper`` with 1/h_eff = 1/h + gamma/(1 + beta h), so
every step reuses its factorisations (one per distinct h_eff), banded solves and residual
checks. Backward Euler is L-stable and keeps n, N >= 0 for any gamma, beta (the
eliminated operator is still an M-matrix).

References
----------
- Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture diffusion
  in composite resins. Journal of Composite Materials 12(2):118-131.
  doi:10.1177/002199837801200201
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..stepping.march import ThetaStepper, rounded_steps
from ..stepping.step_plans import StepPlan


@dataclass
class TwoPhaseHistory:
    """What a two-phase march records at the outputs (``march.History`` plus ``bound``).

    Parameters
    ----------
    mean : numpy.ndarray
        The total (free + bound) mean moisture [weight %] at each output.
    layer : numpy.ndarray
        The total mean moisture of the surface layer [weight %].
    bound : numpy.ndarray
        The bound water's mean [weight %].
    fields : numpy.ndarray or None
        The total moisture per cell [weight %], shape (outputs, cells), on request.
    steps : int
        Steps taken.
    factorisations : int
        Sparse factorisations made.
    """

    mean: np.ndarray
    layer: np.ndarray
    bound: np.ndarray
    fields: np.ndarray | None
    steps: int
    factorisations: int


def two_phase_marcher(law, exposure):
    """A march taking ``march.march``'s arguments that solves the two-phase law instead.

    The surface values (total Ms) become the free share at the node's temperature; the
    exchange over a step is gamma(T) and beta(T) at its middle times its physical
    duration.

    Parameters
    ----------
    law : Langmuir
        The two-phase law (rates [1/s] of temperature [K]).
    exposure : Exposure
        The history (times [s], temperature [K]).

    Returns
    -------
    callable
        ``march(disc, steps, initial, keep_fields=..., part=...)`` returning a
        ``TwoPhaseHistory`` (moisture [weight %]).

    References
    ----------
    Carter & Kibler (1978), cited in the module docstring.
    """
    def march_two_phase(disc, steps: StepPlan, initial, *, keep_fields=False, part="", **_):
        times = np.asarray(steps.times, float)
        share = law.free_share(exposure.temperature(times))
        share_before = law.free_share(exposure.temperature(np.nextafter(times, -np.inf)))
        gamma, beta = law.rates(exposure.temperature(0.5 * (times[1:] + times[:-1])))
        duration = np.diff(times)
        return march_coupled(disc, steps, share_before * steps.surface_before,
                             Exchange(gamma * duration, beta * duration, share[0]), initial,
                             keep_fields=keep_fields, part=part)
    return march_two_phase


@dataclass(frozen=True)
class Exchange:
    """The free/bound water exchange of each step of a two-phase march.

    Parameters
    ----------
    binding : numpy.ndarray
        gamma h of each step [-] (h its physical duration).
    release : numpy.ndarray
        beta h of each step [-].
    initial_share : float
        The free share of the initial moisture [-].
    """

    binding: np.ndarray
    release: np.ndarray
    initial_share: float


def march_coupled(disc, steps: StepPlan, free_before, exchange: Exchange, initial, *,
                  keep_fields=False, part="") -> TwoPhaseHistory:
    """Backward Euler on the free/bound block system, the bound block eliminated.

    See the module docstring for the scheme.

    Parameters
    ----------
    disc : Discretisation
        The operator in scaled coordinates.
    steps : StepPlan
        The step boundaries in scaled time [-], their times [s] (labelling errors) and the
        node indices recorded; its surface values are not read.
    free_before : numpy.ndarray
        The free surface moisture [weight %] at the end of the step ending at each node
        (the left limit there).
    exchange : Exchange
        gamma h and beta h of each step [-] and the initial free share [-].
    initial : float
        The initial total moisture [weight %].
    keep_fields : bool
        Also return the cell values.
    part : str
        The part's name, for error messages.

    Returns
    -------
    TwoPhaseHistory
        Total, layer and bound means [weight %] at the outputs.

    Raises
    ------
    SolverError
        When a step's linear solve fails.
    """
    stepper = ThetaStepper(disc, part)
    nodes, outputs, labels = steps.nodes, steps.outputs, steps.times
    binding, release, initial_share = exchange.binding, exchange.release, exchange.initial_share
    n = np.full(disc.cells, initial_share * float(initial))
    bound = np.full(disc.cells, (1.0 - initial_share) * float(initial))
    want = set(int(k) for k in outputs)
    record = {}
    if 0 in want:
        record[0] = (n.copy(), bound.copy())
    sizes = rounded_steps(np.diff(nodes))
    for k, dt in enumerate(sizes, start=1):
        gdt, bdt = binding[k - 1], release[k - 1]
        effective = 1.0 / (1.0 / dt + gdt / dt / (1.0 + bdt))
        source = effective * (n / dt + bdt / dt * bound / (1.0 + bdt))
        n = stepper.step(source, effective, free_before[k], free_before[k], k, labels[k])
        bound = (bound + gdt * n) / (1.0 + bdt)
        if k in want:
            record[k] = (n.copy(), bound.copy())
    free = np.array([record[int(k)][0] for k in outputs])
    held = np.array([record[int(k)][1] for k in outputs])
    total = free + held
    return TwoPhaseHistory(total @ disc.mean_weights, total @ disc.layer_weights,
                           held @ disc.mean_weights, total if keep_fields else None,
                           int(sizes.size), stepper.factorisations)
