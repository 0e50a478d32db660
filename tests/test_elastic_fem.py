"""Plane-stress finite elements (fickcam.elastic.fem) against exact elasticity solutions."""
import logging
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid
from scipy.special import j0, j1, jn_zeros

from fickcam.elastic.fem import PlaneElasticity, isotropic_stiffness, stiffness_matrix
from fickcam.elastic.mesh import disc_plate, planform_mesh


def _radial(pe, u):
    """Radial displacement at the vertices."""
    x, y = pe.mesh.p
    ux, uy = pe.displacement_at_nodes(u).T
    r = np.hypot(x, y)
    return r, (ux * x + uy * y) / r


def _pressure_load(pe, facets, pressure):
    """Load vector of a pressure on the facets (traction -p n, n the outward normal)."""
    _, normals, _, operator = pe.traction_operator(facets)
    traction = -pressure * normals
    return operator @ np.concatenate([traction[:, 0], traction[:, 1]])


@pytest.mark.slow
def test_lame_thick_ring_under_internal_and_external_pressure():
    """u_r = ((1 - nu) A r + (1 + nu) B / r) / E, A = (pi a^2 - po b^2)/(b^2 - a^2),
    B = (pi - po) a^2 b^2 / (b^2 - a^2) (Timoshenko & Goodier 1970 sec. 28, plane stress)."""
    a, b, e, nu = 0.01, 0.02, 70e9, 0.3
    mesh = planform_mesh(disc_plate(b, 0.005, a), 5e-4)
    pe = PlaneElasticity(mesh.points, mesh.triangles, 0.005, order=2)
    k = pe.stiffness(isotropic_stiffness(e, nu))
    solve = pe.factorise(k, pe.statically_determinate_support())
    inner = pe.boundary_facets(lambda x, y: np.hypot(x, y) < 1.5 * a)
    outer = pe.boundary_facets(lambda x, y: np.hypot(x, y) > 1.5 * a)
    for p_in, p_out in ((1e6, 0.0), (0.0, 1e6)):
        f = _pressure_load(pe, inner, p_in) + _pressure_load(pe, outer, p_out)
        r, u_r = _radial(pe, pe.without_rigid_motion(solve(f)))
        big_a = (p_in * a ** 2 - p_out * b ** 2) / (b ** 2 - a ** 2)
        big_b = (p_in - p_out) * a ** 2 * b ** 2 / (b ** 2 - a ** 2)
        exact = ((1 - nu) * big_a * r + (1 + nu) * big_b / r) / e
        assert np.max(np.abs(u_r - exact)) < 1e-3 * np.max(np.abs(exact))


def _square(n: int, side: float = 1.0):
    x = np.linspace(0.0, side, n + 1)
    gx, gy = np.meshgrid(x, x, indexing="ij")
    index = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]
    triangles = np.vstack([np.column_stack([a.ravel(), b.ravel(), c.ravel()]),
                           np.column_stack([a.ravel(), c.ravel(), d.ravel()])])
    return np.column_stack([gx.ravel(), gy.ravel()]), triangles


def test_uniformly_loaded_orthotropic_plate_strains_by_the_ply_compliance():
    """Uniform tractions (sx, sy, txy) on a free orthotropic square: eps = S sigma with
    S = Q^-1, S11 = 1/E1, S12 = -nu12/E1, S22 = 1/E2, S66 = 1/G12 (Jones 1999 eq. 2.58).
    The linear displacement lies in the element space, so only round-off remains."""
    e1, e2, g12, nu12 = 138e9, 9e9, 6.9e9, 0.3
    q = stiffness_matrix(e1, e2, g12, nu12)
    points, triangles = _square(6, 0.05)
    pe = PlaneElasticity(points, triangles, 0.003, order=1)
    solve = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())
    sigma = np.array([40e6, -15e6, 10e6])
    facets = pe.boundary_facets(lambda x, y: np.ones_like(x, bool))
    _, normals, _, operator = pe.traction_operator(facets)
    traction = np.column_stack([sigma[0] * normals[:, 0] + sigma[2] * normals[:, 1],
                                sigma[2] * normals[:, 0] + sigma[1] * normals[:, 1]])
    u = solve(operator @ np.concatenate([traction[:, 0], traction[:, 1]]))
    strain = np.array([s.mean() for s in pe.strain(u)])
    compliance = np.array([[1 / e1, -nu12 / e1, 0], [-nu12 / e1, 1 / e2, 0], [0, 0, 1 / g12]])
    exact = compliance @ sigma
    assert np.max(np.abs(strain - exact)) < 1e-6 * np.max(np.abs(exact))
    assert np.allclose(pe.stress(u, q), sigma[:, None, None], rtol=0, atol=1e-6 * 40e6)


@pytest.mark.parametrize("order", [1, 2])
def test_displacement_converges_at_the_element_order(order):
    """Airy function phi = cosh x cos y (biharmonic) on a unit square with its exact
    displacement on the boundary, u = (1 + nu)/E (-sinh x cos y, cosh x sin y): the L2 error
    falls as h^(order + 1) (Ciarlet 1978 Theorem 3.2.5)."""
    e, nu = 1.0, 0.3

    def exact(x, y):
        return np.array([-(1 + nu) / e * np.sinh(x) * np.cos(y), (1 + nu) / e * np.cosh(x) * np.sin(y)])

    errors = []
    for n in (4, 8, 16):
        pe = PlaneElasticity(*_square(n), 1.0, order=order)
        held = pe.basis.get_dofs().flatten()
        at_dofs = np.where(pe.component() == 0, *exact(*pe.basis.doflocs))
        u = pe.factorise(pe.stiffness(isotropic_stiffness(e, nu)), held)(np.zeros(pe.dofs), at_dofs[held])
        difference = np.asarray(pe.basis.interpolate(u)) - exact(*pe.quadrature_points())
        errors.append(np.sqrt(np.sum((difference ** 2).sum(axis=0) * pe.basis.dx)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert rates == pytest.approx(order + 1, abs=0.1)


def _cylinder_moisture(radius: float, fourier: float):
    """M/M_inf in an infinite cylinder after a step at its surface, D t / a^2 = ``fourier``:
    1 - (2/a) sum exp(-D alpha_n^2 t) J0(r alpha_n) / (alpha_n J1(a alpha_n)) (Crank 1975 eq. 5.22)."""
    alpha = jn_zeros(0, 80) / radius

    def profile(r):
        r = np.asarray(r, float)
        terms = (np.exp(-(alpha * radius) ** 2 * fourier)[:, None] * j0(np.outer(alpha, r.ravel()))
                 / (alpha * j1(alpha * radius))[:, None])
        return (1.0 - 2.0 / radius * terms.sum(axis=0)).reshape(r.shape)
    return profile


def _polar(sigma, x, y):
    """(sigma_r, sigma_theta) from Voigt Cartesian stresses at (x, y)."""
    r = np.hypot(x, y)
    c, s = x / r, y / r
    sxx, syy, sxy = sigma
    return (sxx * c * c + syy * s * s + 2 * sxy * c * s, sxx * s * s + syy * c * c - 2 * sxy * c * s)


@pytest.mark.slow
def test_disc_with_cylinder_moisture_profile_gives_thin_disc_thermal_stress():
    """Solid disc, free, eigenstrain beta M(r) with M the exact cylinder uptake profile:
    sigma_r = beta E (1/b^2 int_0^b M r dr - 1/r^2 int_0^r M r dr),
    sigma_t = beta E (-M + 1/b^2 int_0^b M r dr + 1/r^2 int_0^r M r dr)
    (Timoshenko & Goodier 1970 sec. 152, alpha T -> beta M); within 1e-3 of the peak."""
    b, e, nu, beta = 0.02, 3e9, 0.35, 3e-3
    moisture = _cylinder_moisture(b, 0.02)
    mesh = planform_mesh(disc_plate(b, 0.004), 6e-4)
    pe = PlaneElasticity(mesh.points, mesh.triangles, 0.004, order=2)
    q = isotropic_stiffness(e, nu)
    x, y = pe.quadrature_points()
    strain = beta * moisture(np.hypot(x, y))
    free = (strain, strain, 0.0 * strain)
    u = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())(pe.eigenstrain_load(q, free))
    radial, hoop = _polar(pe.stress(u, q, free), x, y)

    fine = np.linspace(0.0, b, 20001)
    integral = cumulative_trapezoid(moisture(fine) * fine, fine, initial=0.0)
    r = np.hypot(x, y)
    inner = np.interp(r, fine, integral) / r ** 2
    mean = integral[-1] / b ** 2
    exact_radial = beta * e * (mean - inner)
    exact_hoop = beta * e * (-moisture(r) + mean + inner)
    peak = np.max(np.abs(exact_hoop))
    assert np.max(np.abs(radial - exact_radial)) < 1e-3 * peak
    assert np.max(np.abs(hoop - exact_hoop)) < 1e-3 * peak
    assert exact_hoop[r > 0.99 * b].max() < 0 < exact_hoop[r < 0.1 * b].min()  # skin in compression


def test_uniform_moisture_gives_free_swelling_and_no_stress():
    """A uniform free strain in a free orthotropic plate: u = eps* x (rigid motion removed),
    sigma = 0 (Timoshenko & Goodier 1970 sec. 150)."""
    q = stiffness_matrix(138e9, 9e9, 6.9e9, 0.3)
    mesh = planform_mesh(disc_plate(0.02, 0.004, 0.005), 2e-3)
    pe = PlaneElasticity(mesh.points, mesh.triangles, 0.004, order=2)
    free = (2e-4, 6e-3, 0.0)
    u = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())(pe.eigenstrain_load(q, free))
    stress = pe.stress(u, q, free)
    assert np.max(np.abs(stress)) < 1e-8 * 9e9 * 6e-3
    displacement = pe.displacement_at_nodes(pe.without_rigid_motion(u))
    x, y = pe.mesh.p
    expected = np.column_stack([2e-4 * (x - x.mean()), 6e-3 * (y - y.mean())])
    assert np.allclose(displacement, expected, rtol=0, atol=1e-9 * 6e-3 * 0.02)


def test_importing_the_model_leaves_scikit_fems_logger_and_the_solve_keeps_it_quiet():
    """Importing fickcam.elastic.fem changes no other library's logging; a model's
    assembly and solve hold scikit-fem's INFO lines back (one per mesh, basis and
    assembly) and give its logger back as it was."""
    code = ("import logging; import fickcam.elastic.fem; "
            "print(logging.getLogger('skfem').level)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == str(logging.NOTSET), done.stderr
    heard = []

    class Heard(logging.Handler):
        def emit(self, record):
            heard.append(record)

    skfem_log, listener = logging.getLogger("skfem"), Heard(logging.DEBUG)
    level = skfem_log.level
    skfem_log.addHandler(listener)
    skfem_log.setLevel(logging.DEBUG)
    try:
        points, triangles = _square(4, 0.05)
        pe = PlaneElasticity(points, triangles, 0.003, order=1)
        q = isotropic_stiffness(70e9, 0.3)
        solve = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())
        u = solve(pe.eigenstrain_load(q, (1e-3, 1e-3, 0.0)))
        pe.stress(u, q, (1e-3, 1e-3, 0.0))
        pe.strain_operator()
        assert skfem_log.level == logging.DEBUG
    finally:
        skfem_log.removeHandler(listener)
        skfem_log.setLevel(level)
    assert [r.getMessage() for r in heard if r.levelno < logging.WARNING] == []
