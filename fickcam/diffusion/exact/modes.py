"""The Fickian modes of the separable parts (Sheet, solid Disc, Bar) for the two-phase
march (``two_phase_modes``): the unsaturated fraction of a unit surface step is a sum of
decaying modes, 1 - K(tau) = sum_n A_n exp(-lambda_n tau):

- sheet (thickness h, both faces): A_n = 8 / ((2n+1)^2 pi^2), lambda_n = (2n+1)^2 pi^2 D / h^2
  (Crank 1975 eq. 4.18); its mode shape (4 / ((2n+1) pi)) sin((2n+1) pi z / h)
  (Crank eq. 4.17) averaged over the core z/h in [f, 1-f] gives 8 cos((2n+1) pi f) /
  ((2n+1)^2 pi^2 (1 - 2f));
- solid cylinder (radius a): A_n = 4 / alpha_n^2, lambda_n = alpha_n^2 D / a^2, alpha_n the
  zeros of J0 (Crank eq. 5.23); its shape 2 J0(alpha r / a) / (alpha J1(alpha)) (Crank
  eq. 5.22) averaged over r/a < rho gives 4 J1(alpha rho) / (rho alpha^2 J1(alpha));
- a bar or a finite disc is a product of these (Crank §5.3; Carslaw & Jaeger 1959
  §1.16): product modes with multiplied amplitudes and summed rates; the contact layer
  is the part minus its core, (whole - V core) / (1 - V).

The product modes are lumped into narrow bins of rate (summed amplitudes at the mean
rate); a step of the surface value gets the transient of what was left out or merged back
from the closed-form step response (``step_corrections``), so steps stay exact. (These
were the Fickian record march's modes before the tabulated sum replaced it.)

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import j1, jn_zeros

from ..forcing.record import Forcing
from .separable import step_response

FIRST_COUNT = 32         # modes per factor to start with (doubled with the bins halved
FIRST_PER_OCTAVE = 4     # rate bins per octave to start with   while the two differ)
MAX_PRODUCT = 300_000    # product modes generated at most (memory, time)
TRANSIENT_CUTOFF = 50.0  # a step's transient past exp(-50) is nothing


@dataclass(frozen=True)
class Factor:
    """One separable direction of a part: its Fickian modes.

    Parameters
    ----------
    rates : numpy.ndarray
        Decay rate of each mode [1/s] (per second of rescaled time, the Arrhenius factor
        taken out: rate = eigenvalue x pre-exponential diffusivity / length^2).
    mean : numpy.ndarray
        Amplitude of each mode in the unsaturated fraction of the whole extent [-].
    core : numpy.ndarray
        Amplitude of each mode in the unsaturated fraction of the core (the extent less
        the contact layer) [-].
    core_share : float
        The share of this direction's extent in the core [-].
    """

    rates: np.ndarray
    mean: np.ndarray
    core: np.ndarray
    core_share: float


def sheet_factor(length, d0, depth, count) -> Factor:
    """Modes of a sheet exposed on both faces (Crank 1975, eqs. 4.17-4.18).

    Parameters
    ----------
    length : float
        Full thickness of the sheet [m].
    d0 : float
        Pre-exponential diffusivity across it [m^2/s].
    depth : float
        Depth of the contact layer under each face [m] (the core is the rest).
    count : int
        Number of modes [-].

    Returns
    -------
    Factor
        Rates (2n+1)^2 pi^2 d0 / length^2 [1/s], mean amplitudes 8 / ((2n+1)^2 pi^2) and
        core amplitudes 8 cos((2n+1) pi f) / ((2n+1)^2 pi^2 (1 - 2f)), f = depth / length
        [-], and the core share 1 - 2f [-].

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    k = 2 * np.arange(count) + 1.0
    fraction = min(depth / length, 0.5)
    mean = 8.0 / (k * np.pi) ** 2
    core = (8.0 * np.cos(k * np.pi * fraction) / ((k * np.pi) ** 2 * (1.0 - 2.0 * fraction))
            if fraction < 0.5 else mean)
    return Factor((k * np.pi) ** 2 * d0 / length ** 2, mean, core, 1.0 - 2.0 * fraction)


def cylinder_factor(radius, d0, depth, count) -> Factor:
    """Modes of a solid cylinder exposed on its round face (Crank 1975, eqs. 5.22-5.23);
    the core is r < radius - depth.

    Parameters
    ----------
    radius : float
        Radius of the cylinder [m].
    d0 : float
        Pre-exponential radial diffusivity [m^2/s].
    depth : float
        Depth of the contact layer under the round face [m].
    count : int
        Number of modes [-] (zeros alpha_n of J0).

    Returns
    -------
    Factor
        Rates alpha_n^2 d0 / radius^2 [1/s], mean amplitudes 4 / alpha_n^2 and core
        amplitudes 4 J1(alpha_n rho) / (rho alpha_n^2 J1(alpha_n)), rho = 1 - depth /
        radius [-], and the core share rho^2 [-].

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    alpha = jn_zeros(0, count)
    mean = 4.0 / alpha ** 2
    rho = 1.0 - depth / radius
    core = 4.0 * j1(alpha * rho) / (rho * alpha ** 2 * j1(alpha)) if rho > 0 else mean
    return Factor(alpha ** 2 * d0 / radius ** 2, mean, core, max(rho, 0.0) ** 2)


def factors(geometry, d0, depth, counts) -> list[Factor]:
    """The separable directions of a Sheet, a solid Disc (the axial sheet has no core:
    the layer is the rim over the full thickness) or a Bar, with ``counts`` modes each.

    Parameters
    ----------
    geometry : Sheet, Disc or Bar
        The part (solid disc: no bore).
    d0 : sequence of float
        Pre-exponential diffusivities along x (radial), y and z (through the thickness)
        [m^2/s].
    depth : float
        Depth of the contact layer [m].
    counts : sequence of int
        Modes per direction [-]: (through) for a sheet, (radial, axial) for a disc,
        (length, width, thickness) for a bar.

    Returns
    -------
    list of Factor
        One per direction, in the order of ``counts``.

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
    Clarendon Press, sec. 1.16 (products of one-dimensional solutions).
    """
    if geometry.exact_route == "sheet":
        return [sheet_factor(geometry.thickness, d0[2], depth, counts[0])]
    if geometry.exact_route == "disc":
        axial = sheet_factor(geometry.thickness, d0[2], 0.0, counts[1])
        return [cylinder_factor(geometry.outer_radius, d0[0], depth, counts[0]),
                Factor(axial.rates, axial.mean, axial.mean, 1.0)]
    return [sheet_factor(length, d0[axis], depth, count) for length, axis, count in
            zip((geometry.length, geometry.width, geometry.thickness), (0, 1, 2), counts)]


DIMENSIONS = {"sheet": 1, "disc": 2, "box": 3}  # separable directions by ``exact_route``


def dimensions(geometry) -> int:
    """The number of separable directions of a part.

    Parameters
    ----------
    geometry : Sheet, Disc or Bar
        The part.

    Returns
    -------
    int
        1 for a sheet, 2 for a solid disc, 3 for a bar [-].
    """
    return DIMENSIONS[geometry.exact_route]


@dataclass(frozen=True)
class Modes:
    """Product modes of a separable part.

    Parameters
    ----------
    rates : numpy.ndarray
        Decay rate of each mode [1/s] (per second of rescaled time).
    mean : numpy.ndarray
        Amplitude of each mode in the unsaturated fraction of the whole part [-].
    layer : numpy.ndarray
        Amplitude of each mode in the unsaturated fraction of the contact layer [-].
    tail_rate : float
        The slowest rate of any mode left out or merged [1/s]: a step's transient of
        those modes has died after ``TRANSIENT_CUTOFF / tail_rate``.
    """

    rates: np.ndarray
    mean: np.ndarray
    layer: np.ndarray
    tail_rate: float      # the slowest rate of any mode left out or merged


def product_modes(geometry, d0, depth, counts) -> Modes:
    """Outer products of the factors' modes (Crank 1975, sec. 5.3: the unsaturated
    fractions 1 - F of the directions multiply); the contact layer is the part less its
    core, (whole - V core) / (1 - V) with V the core's share of the volume.

    Parameters
    ----------
    geometry : Sheet, Disc or Bar
        The part.
    d0 : sequence of float
        Pre-exponential diffusivities along x, y and z [m^2/s] (as :func:`factors`).
    depth : float
        Depth of the contact layer [m].
    counts : sequence of int
        Modes per direction [-] (as :func:`factors`).

    Returns
    -------
    Modes
        Every product of one mode per direction: summed rates, multiplied amplitudes.

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    parts = factors(geometry, d0, depth, counts)
    rates, mean, core, volume = np.zeros(1), np.ones(1), np.ones(1), 1.0
    for factor in parts:
        rates = (rates[:, None] + factor.rates[None, :]).ravel()
        mean = (mean[:, None] * factor.mean[None, :]).ravel()
        core = (core[:, None] * factor.core[None, :]).ravel()
        volume *= factor.core_share
    layer = mean if volume <= 0.0 else (mean - volume * core) / (1.0 - volume)
    return Modes(rates, mean, layer, min(float(f.rates[-1]) for f in parts))


def lump(modes: Modes, per_octave: int) -> Modes:
    """Modes whose rates lie in one bin of 1/``per_octave`` octave merged into one: summed
    amplitudes at their weighted mean rate (a mode's miss y - Ms changes little across a
    narrow bin of rates; the error is measured by halving the bins,
    ``two_phase_modes.langmuir_history``).
    A bin of one mode is exact; ``tail_rate`` becomes the slowest rate merged.

    Parameters
    ----------
    modes : Modes
        The product modes.
    per_octave : int
        Bins per octave of rate [-].

    Returns
    -------
    Modes
        One mode per occupied bin.
    """
    bins = np.floor(np.log2(modes.rates / modes.rates.min()) * per_octave).astype(int)
    _, index, members = np.unique(bins, return_inverse=True, return_counts=True)
    weight = np.abs(modes.mean) + np.abs(modes.layer) + 1e-300
    total = np.bincount(index, weight)
    rates = np.bincount(index, weight * modes.rates) / total
    merged = rates[members > 1]
    return Modes(rates, np.bincount(index, modes.mean), np.bincount(index, modes.layer),
                 min(modes.tail_rate, float(merged.min()) if merged.size else np.inf))


def step_corrections(geometry, d0, depth, modes: Modes, force: Forcing,
                     response=None) -> np.ndarray:
    """Each step J of Ms (the initial one, held segments): J times the transient of the
    modes left out or merged, -J (u_exact - u_modes)(age), for the outputs it reaches;
    ``response(age)`` -> (mean, layer) replaces ``separable.step_response`` (a planform's
    own modes times the sheet, ``planform_modes``).

    Parameters
    ----------
    geometry : Sheet, Disc or Bar
        The part.
    d0 : sequence of float
        Pre-exponential diffusivities along x, y and z [m^2/s].
    depth : float
        Depth of the contact layer [m].
    modes : Modes
        The (lumped) modes the march keeps.
    force : Forcing
        The surface value Ms on the rescaled clock: its steps and the outputs' times.
    response : callable, optional
        ``response(age)`` -> (mean, layer) uptake fractions [-] of a unit step after
        ``age`` [s] of rescaled time; None: the closed form of ``separable.step_response``.

    Returns
    -------
    numpy.ndarray
        (outputs, 2): the corrections of the mean and of the layer at each output [%]
        (in the units of the exposure's surface moisture Ms).
    """
    response = response or (lambda age: step_response(geometry, d0, age, depth))
    jumps = force.right - force.left
    jumps[np.abs(jumps) <= 1e-12 * np.max(np.abs(force.right))] = 0.0  # round-off of ramps
    out_tau = force.tau[force.outputs]
    correction = np.zeros((out_tau.size, 2))
    reach = TRANSIENT_CUTOFF / modes.tail_rate
    for k in np.flatnonzero(jumps):
        age = out_tau - force.tau[k]
        near = (force.outputs >= k) & (age < reach)
        if not near.any():
            continue
        exact = 1.0 - np.stack(response(age[near]), axis=1)
        kept = np.exp(-np.outer(age[near], modes.rates)) @ np.stack([modes.mean, modes.layer], 1)
        correction[near] -= jumps[k] * (exact - kept)
    return correction
