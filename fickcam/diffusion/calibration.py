"""Measured error-model constants of the numerical models, and the planner's fixed
choices. Every constant says how it was measured; the measurements are repeated by
the tests named beside them.

Measured (upper ends of the measured ranges, so estimates err on the safe side):

- ``SPACE_ERROR``: error of the mean uptake of a uniform cell-centred grid after a
  unit step, relative to the step, ~ SPACE_ERROR (dx / L)^2 / tau*_lo per axis. Measured
  on the sheet (FiPy Grid1D, small backward-Euler steps) against Crank 1975 eq. 4.18,
  largest over tau* >= tau*_lo = 1e-2: 100 cells gave 6e-4 and 400 cells 4e-5 of the
  uptake F there, (dx/L)^2 / (16 tau*_lo) of F, with F(1e-2) = 0.23: 1.4e-2
  (tests/test_diffusion_convergence.py).
- ``TIME_ERROR``: Richardson-extrapolated backward Euler on geometric steps with m steps
  per doubling: relative error of the mean ~ TIME_ERROR / m^2, measured on the sheet
  for m = 4-32 against Crank eq. 4.18 (tests/test_diffusion_solve.py).
- ``PAIR_TO_EXTRAPOLATED``: the extrapolated error against the coarse/fine difference
  d of the Richardson pair, <= 7 d^2 over the same runs.
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
"""
from __future__ import annotations

SPACE_ERROR = 1.4e-2
TIME_ERROR = 6.3e-3
PAIR_TO_EXTRAPOLATED = 7.0
GROWTH_ERROR = 0.065
MESH_ERROR = 0.012
GROWTH_REACH = 1.2
PLANE_PAIR = 0.03
PAIR_TO_TIME_ERROR = 2.5
ANALYTIC_ERROR = 1e-8

# Planner choices (not measured)
FIRST_STEP = 1e-6        # first step after a change, scaled time tau D / L^2
MAX_CELLS = {"slab": 4000, "axisymmetric": 40_000, "solid": 120_000, "plane": 40_000}
MIN_CELLS_PER_AXIS = 4
MIN_STEPS_PER_DOUBLING = 4
EXPANSION_SHARE = 0.25   # plane: share of the accuracy allowed to the short-time expansion
