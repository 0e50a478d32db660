"""Measured error-model constants of the numerical models, and the planner's fixed
choices. Every constant says how it was measured; the measurements are repeated by
the tests named beside them.

Measured (upper ends of the measured ranges, so estimates err on the safe side):

- ``space_error(tau*_lo)``: error of the mean uptake of a uniform cell-centred grid
  after a unit step, relative to the step, largest over the outputs tau* >= tau*_lo,
  ~ space_error(tau*_lo) (dx / L)^2 / tau*_lo per axis. Measured on the sheet (FiPy
  Grid1D, exact in time by the generalised eigen-decomposition of (K, M)) against Crank
  1975 eq. 4.18, n = 12-96 cells (the table is the largest of them; n-independent to a
  few %): the factor rises from 0.0055 at tau*_lo = 1e-3 to 0.057 near 0.18 (the
  slowest mode's error peaks there) and falls as exp(-pi^2 tau*) after. The old single
  constant 1.4e-2 (its value near 1e-2) made late first outputs miss the accuracy by
  2-2.6x. (tests/test_diffusion_convergence.py.)
- ``TIME_ERROR``: Richardson-extrapolated backward Euler on geometric steps with m steps
  per doubling: error of the mean ~ TIME_ERROR / m^2, the largest over one output at
  tau* = 1e-3-2 with no other output among the steps (outputs add nodes and only shrink
  the steps), m = 4-16, against Crank eq. 4.18: m^2 e = 0.0088-0.0125, worst at
  tau* = 0.18-0.25 (the extrapolated error ~ (dt pi^2)^2 exp(-pi^2 tau*) peaks there).
- ``PAIR_TO_EXTRAPOLATED``: the extrapolated error against the coarse/fine difference
  d of the Richardson pair where the error is largest: 7.9-8.2 d^2 over the same runs.
- ``GROWTH_ERROR``: graded grids (width growing by 1 + g per cell) add ~ GROWTH_ERROR g^2,
  measured on the sheet against Crank eq. 4.18 over tau* >= 1e-3 and >= 1e-2 for
  g = 0.03-0.24: 0.040-0.063 g^2 (tests/test_diffusion_solid.py).
- ``MESH_ERROR``, ``GROWTH_REACH``: P1 elements on a mesh graded from the outline
  (finest spacing h0, growth g): relative uptake error ~ MESH_ERROR (h0 / sqrt(tau*) +
  GROWTH_REACH g)^2, 0.6-1.1x the error on graded discs against Crank eq. 5.23 and on
  the demo cam and a link against space-extrapolated fine meshes
  (tests/test_diffusion_plane.py).
- ``PLANE_PAIR``, ``PAIR_TO_TIME_ERROR``: the planform's unit-step response, coarse and
  fine march differ by at most PLANE_PAIR F(end) / m; the extrapolated time error is at
  most PAIR_TO_TIME_ERROR pair^2 (1.1-1.9 measured on the demo cam and a four-bar link,
  m = 3-12, against m = 32, sheet-weighted).
- ``ANALYTIC_ERROR``: Crank's series truncation and the Duhamel quadrature of the exact
  path (tests/test_diffusion_exact.py: 1e-10 and below against closed forms).

``MAX_CELLS`` is a choice, not a measurement: the most cells of the linear system a
direct model assembles, counted on what is solved (``sizing.unknowns``): the whole part
for Fick; for the D(c) sweeps the octant of a Bar or half the thickness of a CamPlate or
LinkBar (``symmetry_cuts``). What the solid cap costs (CPU time and memory of a
factorisation and of a whole D(c) march near it) is measured in benchmarks/results/tuned_constants.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

SPACE_ERROR_TAU = (1e-3, 1.78e-3, 3.16e-3, 5.62e-3, 1e-2, 1.78e-2, 3.16e-2, 5.62e-2, 0.1, 0.178,
                   0.316, 0.562, 1.0, 1.78, 3.16)
SPACE_ERROR_FACTOR = (5.6e-3, 7.0e-3, 9.9e-3, 1.25e-2, 1.55e-2, 1.96e-2, 2.57e-2, 3.54e-2, 4.97e-2,
                      5.7e-2, 3.9e-2, 9.8e-3, 3.9e-4, 5.7e-7, 1.1e-10)
TIME_ERROR = 1.3e-2
PAIR_TO_EXTRAPOLATED = 9.0
GROWTH_ERROR = 0.065
MESH_ERROR = 0.012
GROWTH_REACH = 1.2
PLANE_PAIR = 0.03
PAIR_TO_TIME_ERROR = 2.5
ANALYTIC_ERROR = 1e-8



def space_error(earliest: float) -> float:
    """The factor of the uniform grid's error model at the earliest output tau*_lo
    (``SPACE_ERROR_FACTOR``, interpolated in log tau; held beyond the table: below it the
    factor only falls, above it the error is below 1e-10 of the step).

    Parameters
    ----------
    earliest : float
        The earliest output's scaled time tau* = D t / L^2 after a change [-].

    Returns
    -------
    float
        The factor [-] of the uniform grid's relative error model at that time.
    """
    return float(np.interp(math.log(max(earliest, 1e-300)), np.log(SPACE_ERROR_TAU),
                           SPACE_ERROR_FACTOR))


# Planner choices (not measured)
FIRST_STEP = 1e-6        # first step after a change, scaled time tau D / L^2


@dataclass(frozen=True)
class CellCaps:
    """The most cells of the linear system each direct model may assemble (a mirrored D(c)
    part: the cells it solves; see above), ``caps["solid"]`` by model name. A run passes
    others through ``SolverSettings.cells``, never by changing ``MAX_CELLS``.

    Parameters
    ----------
    slab : int
        The most cells [-] of the ``slab`` model (a Sheet through its thickness).
    axisymmetric : int
        The most cells [-] of the ``axisymmetric`` model (a Disc in (r, z)).
    solid : int
        The most cells [-] of the ``solid`` model (3-D grid or prisms).
    plane : int
        The most nodes [-] of the ``plane`` model's planform mesh.
    """

    slab: int = 4000
    axisymmetric: int = 40_000
    solid: int = 120_000
    plane: int = 40_000

    def __getitem__(self, model: str) -> int:
        return getattr(self, model)


MAX_CELLS = CellCaps()
MIN_CELLS_PER_AXIS = 4
MIN_STEPS_PER_DOUBLING = 4
