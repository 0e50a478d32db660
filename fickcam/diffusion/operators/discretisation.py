"""The operator interface of every mesh model (``Discretisation``): M dc/dt + K c = g f
with the weights that integrate its values.

Every mesh is built in non-dimensional, anisotropy-scaled coordinates
x_i' = (x_i / L) sqrt(D_z / D_i) with L the part thickness, so that the
operator is the isotropic Laplacian with unit coefficient (Crank 1975, §2.6,
eq. 2.13: anisotropic diffusion along principal axes reduces to isotropic
diffusion by scaling each coordinate with sqrt(D_ref / D_i)). Time is then
tau* = tau D_z(T_ref) / L^2.

FiPy assembles ``TransientTerm == DiffusionTerm`` once per mesh with all exposed faces
constrained to 1 (``fipy_backend.assemble``; ``DiffusionTermCorrection`` is not used: its
non-orthogonal correction is an explicit source built from the current gradient, so it is
not part of a constant matrix); the P1 elements of the plane model (``p1``) build their
own. Backward Euler with any step and any uniform surface value g is then
(M/dt + K) c_new = M c_old/dt + g f, one scipy factorisation per distinct dt serving every
step of that size (``stepping.march``).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import sparse


@dataclass
class Discretisation:
    """An operator M dc/dt + K c = g f with the weights that integrate its values.

    FiPy's finite volumes: M = diag(volumes). The hand-written P1 elements of the plane
    model (``p1``) add a consistent ``mass`` and nodes held at the surface value g
    (eliminated): their mass coupling ``held_mass`` (M_fb 1, the jump term of a change
    of g) and their shares of the mean and the layer (``held_mean``, ``held_layer``).

    Parameters
    ----------
    volumes : numpy.ndarray
        The scaled cell volumes [-], shape (n,): the lumped mass M = diag(volumes).
    stiffness : scipy.sparse.csr_matrix
        K [-], shape (n, n).
    boundary : numpy.ndarray
        f [-], shape (n,): the coupling to a unit surface value.
    mean_weights : numpy.ndarray
        Weights [-] of the volume mean, summing to 1 with ``held_mean``.
    layer_weights : numpy.ndarray
        Weights [-] of the contact-layer mean, summing to 1 with ``held_layer``.
    coordinates : dict of str to numpy.ndarray
        The physical cell centres [m] by axis name.
    mass : scipy.sparse.csr_matrix, optional
        The consistent mass [-]; None: diag(volumes).
    held_mass : numpy.ndarray, optional
        M_fb 1 of the nodes held at the surface value [-].
    held_mean, held_layer : float
        The held nodes' shares of the mean and of the layer mean [-].
    factors : OrderedDict
        (dt, theta) -> (matrix, LU): the factorisations every march on this operator
        shares.
    """

    volumes: np.ndarray            # (n,) scaled cell volumes (M = diag(volumes)), lumped mass
    stiffness: sparse.csr_matrix   # K, (n, n)
    boundary: np.ndarray           # f, (n,) for a unit surface value
    mean_weights: np.ndarray       # (n,), sum 1 with held_mean: volume mean
    layer_weights: np.ndarray      # (n,), sum 1 with held_layer: mean over the surface layer
    coordinates: dict[str, np.ndarray] = field(default_factory=dict)  # physical cell centres, m
    mass: sparse.csr_matrix | None = None  # consistent mass (None: diag(volumes))
    held_mass: np.ndarray | None = None    # (n,) M_fb 1 of the held nodes
    held_mean: float = 0.0
    held_layer: float = 0.0
    factors: OrderedDict = field(default_factory=OrderedDict, repr=False, compare=False)
    # (dt, theta) -> (matrix, LU or None): shared by every march on this operator

    @property
    def cells(self) -> int:
        return int(self.volumes.size)

    def mass_matrix(self) -> sparse.spmatrix:
        return sparse.diags(self.volumes) if self.mass is None else self.mass

    def lumped(self) -> Discretisation:
        """The same operator with its mass lumped (itself where it already is): an
        M-matrix, whose backward-Euler fields obey the maximum principle (Thomée 2006
        ch. 15), for fields rather than means."""
        if self.mass is None:
            return self
        return replace(self, mass=None, held_mass=None, factors=OrderedDict())
