"""FiPy, the finite-volume library every mesh operator but the plane model's P1 is
assembled by: the one module of fickcam that imports it.

FiPy (Guyer, Wheeler & Warren 2009, "FiPy: partial differential equations with Python",
Computing in Science & Engineering 11(3):6-15, doi:10.1109/MCSE.2009.52) builds the
cell-centred finite-volume system of ``TransientTerm == DiffusionTerm`` with two-point
fluxes across the faces (Eymard, Gallouet & Herbin 2000, "Finite volume methods",
Handbook of Numerical Analysis VII:713-1020, doi:10.1016/S1570-8659(00)07005-8). Here it
builds the meshes (its structured grids, and generic meshes of prisms and planar cells
with given cell points) and assembles each operator once; scipy then marches it
(``stepping.march``), one factorisation per step size, instead of FiPy rebuilding the
matrix at every step.

Assembly goes through FiPy's public API: with ``cacheMatrix()`` and ``cacheRHSvector()``,
``justResidualVector`` builds the linear system without solving it, and ``matrix`` and
``RHSvector`` return it. With dt = 1 and c_old = 0 the matrix of
``TransientTerm() == DiffusionTerm(1)`` is M + K (M = diag(cell volumes)) and its right
side is f, the exposed faces' coupling to a unit surface value; K and f do not depend on
dt, so backward Euler with any step and surface value g is (M/dt + K) c_new =
M c_old/dt + g f (tests/test_diffusion_fv.py checks it against FiPy's own solve).

The one private part of FiPy used is in ``centred_mesh``: FiPy computes a generic mesh's
cell points as the mean of its face centres and offers no public way to give them, so a
subclass overrides ``_calcCellCenters`` (and ``_calcFaceCenters`` for the prisms' top and
bottom faces). The mesh is checked on construction and raises if a FiPy release stops
calling those methods; tests/test_diffusion_fv.py fails on it too.

References
----------
- Eymard, R., Gallouët, T. & Herbin, R. (2000). Finite volume methods. Handbook of Numerical
  Analysis VII:713-1020. doi:10.1016/S1570-8659(00)07005-8
- Guyer, J. E., Wheeler, D. & Warren, J. A. (2009). FiPy: partial differential equations with
  Python. Computing in Science & Engineering 11(3):6-15. doi:10.1109/MCSE.2009.52
"""
from __future__ import annotations


import numpy as np
from scipy import sparse


def assemble(mesh, corrected: bool = False, exposed: np.ndarray | None = None
             ) -> tuple[np.ndarray, sparse.csr_matrix, np.ndarray]:
    """(volumes, K, f) of dc/dt = laplacian(c) on a FiPy mesh.

    Parameters
    ----------
    mesh : fipy mesh
        Any FiPy mesh, in scaled coordinates [-].
    corrected : bool
        FiPy's ``DiffusionTermCorrection`` (non-orthogonal correction) instead of
        ``DiffusionTerm``.
    exposed : (n_faces,) bool array, optional
        Faces held at the surface value; default every exterior face. The other exterior
        faces are insulated (FiPy's default: zero flux, e.g. a mirror plane).

    Returns
    -------
    volumes : (n,) array [-]
        Cell volumes, the lumped mass M = diag(volumes).
    stiffness : (n, n) CSR matrix [-]
        K = A - M, with A FiPy's matrix at dt = 1.
    boundary : (n,) array [-]
        f, FiPy's right side at dt = 1, c_old = 0, for a unit surface value.
    """
    # deferred: keeps fipy off the start-up path
    from fipy import (CellVariable, DiffusionTerm, DiffusionTermCorrection, LinearLUSolver,
                      TransientTerm)

    var = CellVariable(mesh=mesh, value=0.0)
    var.constrain(1.0, mesh.exteriorFaces if exposed is None else exposed)
    diffusion = DiffusionTermCorrection if corrected else DiffusionTerm
    equation = TransientTerm(coeff=1.0) == diffusion(coeff=1.0)
    equation.cacheMatrix()
    equation.cacheRHSvector()
    equation.justResidualVector(var=var, solver=LinearLUSolver(tolerance=1e-10), dt=1.0)
    volumes = np.asarray(mesh.cellVolumes, float).copy()
    matrix = sparse.csr_matrix(equation.matrix.matrix)
    stiffness = (matrix - sparse.diags(volumes)).tocsr()
    boundary = np.asarray(equation.RHSvector, float).copy()
    return volumes, stiffness, boundary


def interval_mesh(dx, nx: int | None = None):
    """FiPy ``Grid1D`` from x = 0 [-]: ``nx`` cells of width ``dx``, or (``nx`` None) cells
    of the widths in the array ``dx``.

    Parameters
    ----------
    dx : float or numpy.ndarray
        The cell width, or the widths, in scaled units [-].
    nx : int, optional
        The number of cells [-]; None: one per width of ``dx``.

    Returns
    -------
    fipy.Grid1D
        The 1-D mesh.
    """
    # deferred: keeps fipy off the start-up path
    from fipy import Grid1D

    return Grid1D(dx=dx, nx=nx)


def cylindrical_mesh(radial: dict, axial: dict, inner_radius: float):
    """FiPy ``CylindricalGrid2D`` in (r, z) [-]: each axis a count ``n`` and a spacing
    ``d`` (uniform) or ``n = None`` and the array of widths ``d``; the axis starts at
    ``inner_radius`` [-] (the bore), z at 0.

    Parameters
    ----------
    radial, axial : dict
        ``{"n": count or None, "d": spacing or widths}`` of r and z, scaled [-].
    inner_radius : float
        Where r starts, scaled [-] (0: a solid disc).

    Returns
    -------
    fipy.CylindricalGrid2D
        The axisymmetric mesh in (r, z).
    """
    # deferred: keeps fipy off the start-up path
    from fipy import CylindricalGrid2D

    return CylindricalGrid2D(nr=radial["n"], nz=axial["n"], dr=radial["d"], dz=axial["d"],
                             origin=((inner_radius,), (0.0,)))


def box_mesh(axes: list[dict]):
    """FiPy ``Grid3D`` [-]: each of x, y, z a count ``n`` and a spacing ``d`` (uniform) or
    ``n = None`` and the array of widths ``d``.

    Parameters
    ----------
    axes : list of dict
        ``{"n": count or None, "d": spacing or widths}`` of x, y and z, scaled [-].

    Returns
    -------
    fipy.Grid3D
        The box mesh from the origin.
    """
    # deferred: keeps fipy off the start-up path
    from fipy import Grid3D

    x, y, z = axes
    return Grid3D(nx=x["n"], ny=y["n"], nz=z["n"], dx=x["d"], dy=y["d"], dz=z["d"])


def centred_mesh(dimensions: int, vertex_coords: np.ndarray, face_vertex_ids: np.ndarray,
                 cell_face_ids: np.ndarray, cell_centres: np.ndarray,
                 centred_faces: np.ndarray | None = None,
                 face_centres: np.ndarray | None = None):
    """A FiPy generic mesh (``Mesh2D`` or 3-D ``Mesh``) with given cell points.

    FiPy would average the face centres; the admissible cells need their circumcentres,
    and the prisms' top and bottom faces (``centred_faces``) centred on them, so that the
    segment from a cell point to those faces is vertical. Cell volumes do not depend on
    those points (FiPy's divergence-theorem volume uses the face normals and, in 3-D,
    only their x component, zero on horizontal faces; in 2-D the face centres, the
    sides' midpoints, which are kept).

    Parameters
    ----------
    dimensions : int
        2 or 3.
    vertex_coords : (dimensions, n_vertices) array [-]
    face_vertex_ids : (k, n_faces) int array
        Vertices of each face, padded with -1.
    cell_face_ids : (m, n_cells) int array
        Faces of each cell, padded with -1.
    cell_centres : (dimensions, n_cells) array [-]
    centred_faces : int array, optional
        Faces whose centres are given by ``face_centres`` [-] instead of FiPy's own.

    Raises
    ------
    RuntimeError
        If the installed FiPy did not take the given points (a release that no longer
        calls ``_calcCellCenters`` or ``_calcFaceCenters``).
    """
    mesh = _centred_mesh_class(dimensions)(vertex_coords, face_vertex_ids, cell_face_ids,
                                           cell_centres, centred_faces, face_centres)
    taken = np.allclose(np.asarray(mesh.cellCenters), cell_centres, rtol=1e-12, atol=0.0)
    if centred_faces is not None:
        faces = np.asarray(mesh.faceCenters)[:, centred_faces]
        taken &= np.allclose(faces, face_centres, rtol=1e-12, atol=0.0)
    if not taken:
        # deferred: FiPy only where its solver is asked for
        import fipy

        raise RuntimeError(f"FiPy {fipy.__version__} ignores the given cell points of a "
                           "generic mesh; fickcam's prism meshes need FiPy 4.0")
    return mesh


def _centred_mesh_class(dimensions: int):
    """The subclass of FiPy's ``Mesh2D`` or ``Mesh`` behind ``centred_mesh`` (private
    FiPy API: ``_calcCellCenters``, ``_calcFaceCenters``), made per mesh (a class costs
    microseconds beside the mesh)."""
    # deferred: keeps fipy off the start-up path
    from fipy.meshes.mesh import Mesh
    from fipy.meshes.mesh2D import Mesh2D

    class CentredMesh(Mesh2D if dimensions == 2 else Mesh):
        def __init__(self, vertex_coords, face_vertex_ids, cell_face_ids, cell_centres,
                     centred_faces=None, face_centres=None):
            self._given_cells = cell_centres
            self._given_faces = (centred_faces, face_centres)
            super().__init__(vertex_coords, face_vertex_ids, cell_face_ids)

        def _calcCellCenters(self):
            return self._given_cells

        def _calcFaceCenters(self):
            centres = np.array(super()._calcFaceCenters())
            ids, values = self._given_faces
            if ids is not None:
                centres[:, ids] = values
            return centres

    return CentredMesh
