"""The modes of a CamPlate or LinkBar: every eigenmode of its planform's finite-volume
operator times the exact through-thickness sheet modes, for the two-phase march
(``langmuir``) where the plane model's superposed step responses do not apply.

The part is a prism (planform x thickness), so in the scaled coordinates of
``discretisation`` its Laplacian separates (Crank 1975 §5.3; Carslaw & Jaeger 1959
§1.16): modes psi_i(x, y) sin(k pi z/h), rates mu_i + (k pi)^2. The planform operator is
FiPy's, on the Delaunay-admissible cells of ``prism`` (one layer of prisms between a face
and the insulated mid-plane, whose face-to-cell coupling 2 V/w^2 is taken off the
diagonal and off f: the remainder is the in-plane two-point-flux operator, K_p 1 = f_p).
Its generalised eigenproblem K_p v = mu M v (M = diag(volumes), symmetric after
M^-1/2 K_p M^-1/2) is solved whole (dense ``eigh``), so the planform direction is not
truncated: the deficit of a unit step is sum_i c_i v_i exp(-mu_i t) exactly (the
semi-discrete solution), c_i = v_i^T M 1. Its error is the planform mesh's, sized from
the accuracy by ``layout`` (2 graded directions) under ``PLANFORM_CAP`` cells.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.linalg import eigh

from ..errors import InputError
from . import layout
from .calibration import space_error
from .fvprism import prism
from .langmuir import ModeSource
from .modes import Modes, sheet_factor
from .prism import band_share
from .scaling import stretch_of
from .series import sheet_uptake

PLANFORM_CAP = 2500   # dense eigh of 2 500 cells: about 3 s of CPU, 50 MB
OTHER_MESHES = (2.0, 1.5, 0.5)  # the second mesh of the error estimate: w0 times these


def planform_design(geometry, d, accuracy: float, t_lo: float) -> layout.Layout:
    """Graded planform rows (w0, g) from the error model, shrunk under the cap."""
    stretch = stretch_of(d)
    return layout.graded((1.0, 1.0), ("both", "both"), accuracy, t_lo, PLANFORM_CAP,
                         space_error(t_lo), lambda w0, g: (
                             layout._estimated_prism_cells(geometry, w0, g, stretch)[0],))


@lru_cache(maxsize=8)
def planform_spectrum(geometry, d, depth: float, finest: float, growth: float):
    """(rates in 1/s of rescaled time, mean amplitudes, layer amplitudes, cells) of the
    planform: a unit step's deficit 1 - u has mean sum A_i exp(-rate_i tau). Cached: a
    run re-ages its parts at extra times to locate limit crossings (read-only arrays)."""
    tess = layout.planform_cells(geometry, finest, growth, stretch_of(d))
    half = 0.5 * geometry.thickness
    disc = prism(tess, geometry.thickness, np.array([half]), band_share(tess, depth), d,
                 mid_plane=True)
    volumes = disc.volumes
    vertical = 2.0 * volumes / 0.5 ** 2      # face-to-cell coupling of the exposed face
    stiffness = disc.stiffness.toarray() - np.diag(vertical)
    root = np.sqrt(volumes)
    mu, vectors = eigh(stiffness / root[:, None] / root[None, :])
    coefficients = vectors.T @ root                # c_i of the constant 1 (M-orthonormal v)
    mean = (disc.mean_weights / root) @ vectors * coefficients
    layer = (disc.layer_weights / root) @ vectors * coefficients
    rates = np.maximum(mu, 0.0) * d[2] / geometry.thickness ** 2
    for array in (rates, mean, layer):
        array.flags.writeable = False
    return rates, mean, layer, tess.cells


def planform_error(geometry, d, depth: float, finest: float, growth: float, source,
                   ages) -> float:
    """A-posteriori error of the planform mesh: the unit-step mean uptake at ``ages``
    (rescaled s) on this mesh and on one with w0 times r (2, else 1.5 where a coarse mesh
    cannot resolve the outline, else a finer one, 0.5), their difference / |r^2 - 1|
    (second order, Richardson); infinity if no other mesh can be built."""
    ages = np.asarray(ages, float)
    for ratio in OTHER_MESHES:
        try:
            coarse = planform_source(geometry, d, depth, ratio * finest, growth)
        except InputError:
            continue
        difference = np.abs(source.response(ages)[0] - coarse.response(ages)[0])
        return float(np.max(difference, initial=0.0)) / abs(ratio ** 2 - 1.0)
    return float("inf")


def planform_source(geometry, d, depth: float, finest: float, growth: float) -> ModeSource:
    """The product modes (planform whole x ``count`` sheet modes) and the exact step
    response of the semi-discrete planform times Crank's sheet (eq. 4.18)."""
    rates, mean, layer, cells = planform_spectrum(geometry, d, depth, finest, growth)

    def modes(counts) -> Modes:
        sheet = sheet_factor(geometry.thickness, d[2], 0.0, counts[0])
        return Modes((rates[:, None] + sheet.rates[None, :]).ravel(),
                     (mean[:, None] * sheet.mean[None, :]).ravel(),
                     (layer[:, None] * sheet.mean[None, :]).ravel(), float(sheet.rates[-1]))

    def response(age):
        age = np.asarray(age, float)
        planar = np.exp(-np.outer(age, rates))
        through = 1.0 - sheet_uptake(d[2] * age / geometry.thickness ** 2)
        return 1.0 - (planar @ mean) * through, 1.0 - (planar @ layer) * through

    return ModeSource(modes, response, 1, cells)
