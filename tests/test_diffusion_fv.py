"""Finite-volume engine: FiPy extraction, boundedness, conservation, solver errors."""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fickcam.diffusion import CamPlate, LinkBar
from fickcam.diffusion.operators import discretisation, fipy_backend, grids, prisms
from fickcam.diffusion.planform import outline, admissible, triangles
from fickcam.diffusion.stepping import march
from fickcam.diffusion.stepping.step_plans import StepPlan
from fickcam.errors import SolverError
from tolerance import roundoff

pytest.importorskip("fipy")

PLATE = CamPlate(np.array([0.0, 1.0, 1.0, 0.0]), np.array([0.0, 0.0, 0.6, 0.6]), 1.0)


def plain_fipy_steps(mesh, dt, steps, corrected=False):
    """The reference: FiPy solving TransientTerm == DiffusionTerm itself, every step."""
    from fipy import (CellVariable, DiffusionTerm, DiffusionTermCorrection, LinearLUSolver,
                      TransientTerm)

    var = CellVariable(mesh=mesh, value=0.0)
    var.constrain(1.0, mesh.exteriorFaces)
    term = DiffusionTermCorrection if corrected else DiffusionTerm
    equation = TransientTerm() == term(coeff=1.0)
    for _ in range(steps):
        equation.solve(var=var, dt=dt, solver=LinearLUSolver(tolerance=1e-10))
    return np.asarray(var.value)


def extracted_steps(mesh, dt, steps, corrected=False):
    volumes, stiffness, boundary = fipy_backend.assemble(mesh, corrected)
    ones = np.ones(volumes.size)
    disc = discretisation.Discretisation(volumes, stiffness, boundary, ones / ones.sum(), ones / ones.sum())
    nodes = dt * np.arange(steps + 1)
    history = march.march(disc, StepPlan.without_jumps(nodes, np.ones(steps + 1), np.array([steps])),
                          0.0, keep_fields=True)
    return history.fields[0]


@pytest.mark.parametrize("dimensions", [2, 3])
def test_fipy_takes_the_given_cell_points_of_a_generic_mesh(dimensions):
    """The one private FiPy API fickcam uses: a generic mesh's cell points (and the prisms'
    horizontal face centres) given through overridden ``_calcCellCenters`` and
    ``_calcFaceCenters``. A FiPy release that stops calling them fails here (and
    ``fipy_backend.centred_mesh`` raises) instead of moving the cell points silently."""
    from fipy.meshes.mesh import Mesh

    assert hasattr(Mesh, "_calcCellCenters") and hasattr(Mesh, "_calcFaceCenters")
    tess = admissible.admissible(triangles.triangulate(PLATE, 0.2), PLATE)
    if dimensions == 2:
        sides, cell_sides = prisms.sides_of_cells(tess)
        faces = np.full((max(c.size for c in cell_sides), tess.cells), -1)
        for k, row in enumerate(cell_sides):
            faces[:row.size, k] = row
        mesh = fipy_backend.centred_mesh(2, tess.points.T, sides.T, faces, tess.centres.T)
        given = tess.centres.T
    else:
        mesh, _ = prisms.prism_mesh(tess, 1.0, np.array([0.0, 0.3, 1.0]), mid_plane=False)
        given = np.vstack([np.tile(tess.centres.T, 2), np.repeat([0.15, 0.65], tess.cells)])
    assert np.array_equal(np.asarray(mesh.cellCenters), given)


@pytest.mark.parametrize("kind", ["grid1d", "cylindrical", "grid3d", "prisms"])
def test_extracted_operator_reproduces_plain_fipy_solve(kind):
    from fipy import CylindricalGrid2D, Grid1D, Grid3D

    corrected = False  # DiffusionTermCorrection is explicit (old-gradient source): not extractable
    mesh = {"grid1d": lambda: Grid1D(nx=20, dx=0.05),
            "cylindrical": lambda: CylindricalGrid2D(nr=6, nz=5, dr=0.1, dz=0.2,
                                                     origin=((0.3,), (0.0,))),
            "grid3d": lambda: Grid3D(nx=4, ny=3, nz=5, dx=0.3, dy=0.2, dz=0.2),
            "prisms": lambda: prisms.prism_mesh(admissible.admissible(triangles.triangulate(
                PLATE, 0.2), PLATE), 1.0, np.array([0.0, 0.3, 1.0]), mid_plane=False)[0]}[kind]()
    expected = plain_fipy_steps(mesh, 0.01, 5, corrected)
    assert np.allclose(extracted_steps(mesh, 0.01, 5, corrected), expected, rtol=0, atol=1e-10)


def test_uniform_field_at_the_surface_value_is_steady():
    """K 1 = f: a part saturated at g stays there (conservative, consistent fluxes)."""
    disc = grids.bar(0.02, 0.01, 0.004, (5, 4, 3), 5e-4, (2e-12, 1e-12, 5e-13))
    row_scale = abs(disc.stiffness) @ np.ones(disc.cells)   # sum of |K_ij| per row
    np.testing.assert_allclose(disc.stiffness @ np.ones(disc.cells), disc.boundary, rtol=0,
                               atol=roundoff(row_scale))


FOURIER = st.floats(min_value=1e-3, max_value=1e6)


@lru_cache(maxsize=None)
def cached_sheet(cells):
    return grids.sheet(1e-3, cells, 1e-4)


@lru_cache(maxsize=None)
def cached_annulus():
    return grids.disc(0.01, 0.004, 0.002, 6, 5, 5e-4, 1e-12, 2e-12)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(fourier=FOURIER, initial=st.floats(0.0, 5.0), surface=st.floats(0.0, 5.0),
       cells=st.integers(2, 60))
def test_backward_euler_stays_between_initial_and_surface_values(fourier, initial, surface,
                                                                  cells):
    """Maximum principle: every cell between c0 and g at any Fourier number, monotone in time."""
    disc = cached_sheet(cells)
    nodes = fourier * np.arange(4)
    history = march.march(disc, StepPlan.without_jumps(nodes, np.full(4, surface), np.arange(4)),
                          initial, keep_fields=True)
    lo, hi = min(initial, surface), max(initial, surface)
    span = max(hi, 1.0)
    fields = history.fields
    assert np.all(np.isfinite(fields))
    assert fields.min() >= lo - 1e-12 * span and fields.max() <= hi + 1e-12 * span
    direction = np.sign(surface - initial)
    assert np.all(direction * np.diff(history.mean) >= -1e-12 * span)


@settings(max_examples=25, deadline=None)
@given(dt=FOURIER, surface=st.floats(0.0, 5.0), initial=st.floats(0.0, 5.0))
def test_mass_balance_closes_each_step(dt, surface, initial):
    """Sum of V (c_new - c_old) equals dt times the boundary inflow f g - K c_new."""
    disc = cached_annulus()
    stepper = march.ThetaStepper(disc)
    old = np.full(disc.cells, initial)
    new = stepper.step(old, dt, surface, surface, 1, dt)
    uptake = np.sum(disc.volumes * (new - old))
    inflow = dt * np.sum(surface * disc.boundary - disc.stiffness @ new)
    # round-off of dt (g f - K c): both terms are O(dt |f| max(g, c0)) before cancelling
    scale = (np.sum(disc.volumes) + dt * np.sum(np.abs(disc.boundary))) * max(surface, initial, 1.0)
    assert uptake == pytest.approx(inflow, rel=1e-9, abs=1e-12 * scale)


def test_failed_solve_names_part_step_and_time():
    disc = cached_sheet(10)
    with pytest.raises(SolverError) as caught:
        march.march(disc, StepPlan.without_jumps(np.array([0.0, 1.0, 2.0]),
                                                 np.array([1.0, np.nan, np.nan]), np.array([2]),
                                                 np.array([0.0, 3600.0, 7200.0])),
                    0.0, part="cam")
    assert caught.value.part == "cam" and caught.value.step == 1
    assert "cam" in str(caught.value) and "step 1" in str(caught.value)


def test_backward_euler_bounded_where_crank_nicolson_overshoots():
    """Steps doubling every step reach large Fourier numbers: CN (even restarted
    with two BE steps) overshoots saturation, BE does not (the reason BE is the default)."""
    disc = cached_sheet(50)
    nodes = np.concatenate([[0.0], 1e-6 * 2.0 ** np.arange(25)])
    steps = StepPlan.without_jumps(nodes, np.ones(nodes.size), np.arange(nodes.size))
    fields = {scheme: march.march(disc, steps, 0.0, keep_fields=True, scheme=scheme,
                                  restart_steps=2).fields
              for scheme in ("backward_euler", "crank_nicolson")}
    assert fields["backward_euler"].max() <= 1.0 + 1e-14
    assert fields["crank_nicolson"].max() > 1.0 + 1e-3


def test_link_outline_excludes_holes_and_includes_bosses():
    link = LinkBar(0.1, 0.02, 0.01, 0.015, 0.005)
    inside = link.inside(np.array([0.0, 0.0, 0.05, -0.012, 0.05]),
                              np.array([0.0, 0.008, 0.0, 0.0, 0.012]))
    assert inside.tolist() == [False, True, True, True, False]


def test_triangulated_planform_has_the_outline_area():
    link = LinkBar(0.1, 0.02, 0.01, 0.015, 0.005)
    mesh = triangles.triangulate(link, 0.002)
    corners = mesh.points[mesh.triangles]
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    area = 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]).sum()
    assert area == pytest.approx(link_area(link), rel=5e-3)


def link_area(link):
    """Strip 2w L, plus per boss the half disc beyond the bar end and the two half
    circular segments |y| > w beside it, minus the holes."""
    r, w = link.boss_outer_radius, link.width / 2
    segment = r * r * np.arccos(w / r) - w * np.sqrt(r * r - w * w)
    return link.length * 2 * w + 2 * (np.pi * r * r / 2 + segment) \
        - 2 * np.pi * link.boss_inner_radius ** 2
