"""Boundary and material data a diffusion solve needs: the exposure history of
a part's surface and its (Arrhenius, anisotropic) diffusivity."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

GAS_CONSTANT = 8.314462618  # J/(mol K), CODATA 2018


@dataclass(frozen=True, eq=False)
class Exposure:
    """Surface history of one part.

    ``change_times`` (s, shape n+1) are the segment boundaries, 0 first and the
    end of the history last; segment k spans [t_k, t_k+1). ``ramp[k]`` says the
    segment changes linearly from the previous segment's end values (True) or is
    held, stepping at t_k (False). ``temperature(t)`` (K) and
    ``surface_moisture(t)`` (weight %, the saturation value Mm(T, RH) of this
    part's material) are right-continuous functions of time arrays.

    Parameters
    ----------
    change_times : numpy.ndarray
        The segment boundaries [s], shape (n+1,), 0 first and the history's end last.
    ramp : numpy.ndarray of bool
        Per segment, shape (n,): linear from the previous segment's end values (True)
        or held (False).
    temperature : callable
        t [s] -> the surface temperature [K], right-continuous.
    surface_moisture : callable
        t [s] -> the surface moisture [weight %] (the saturation value Mm(T, RH) of the
        part's material), right-continuous.
    initial_moisture : float
        The part's uniform moisture at t = 0 [weight %].
    """

    change_times: np.ndarray
    ramp: np.ndarray
    temperature: Callable[[np.ndarray], np.ndarray]
    surface_moisture: Callable[[np.ndarray], np.ndarray]
    initial_moisture: float = 0.0

    @property
    def end(self) -> float:
        return float(self.change_times[-1])

    def surface_before(self, t) -> np.ndarray:
        """The left limit g(t-) of the right-continuous surface history: its value just
        before ``t`` (the largest float below it); g(0-) is the initial moisture.

        Parameters
        ----------
        t : float or array_like
            The time [s].

        Returns
        -------
        numpy.ndarray
            g(t-) [weight %].
        """
        t = np.asarray(t, float)
        value = np.asarray(self.surface_moisture(np.nextafter(t, -np.inf)), float)
        return np.where(t <= self.change_times[0], self.initial_moisture, value)

    @classmethod
    def piecewise(cls, change_times, temperatures, surface_values, initial_moisture=0.0,
                  ramp=None) -> "Exposure":
        """Segments with temperature ``temperatures[k]`` (K) and surface moisture
        ``surface_values[k]`` (weight %) on [t_k, t_k+1): held, or, where
        ``ramp[k]``, linear from the previous segment's values (tests, bench).

        Parameters
        ----------
        change_times : array_like
            The segment boundaries [s], shape (n+1,).
        temperatures : float or array_like
            Each segment's temperature [K], shape (n,) (a scalar: all of them).
        surface_values : float or array_like
            Each segment's surface moisture [weight %], shape (n,).
        initial_moisture : float
            The moisture at t = 0 [weight %].
        ramp : array_like of bool, optional
            Per segment: linear from the previous segment's values; None: all held.

        Returns
        -------
        Exposure
        """
        edges = np.asarray(change_times, float)
        n = edges.size - 1
        ramp = np.zeros(n, bool) if ramp is None else np.asarray(ramp, bool)
        temps = np.broadcast_to(np.asarray(temperatures, float), (n,)).copy()
        values = np.broadcast_to(np.asarray(surface_values, float), (n,)).copy()
        return cls(edges, ramp, _piecewise_function(edges, ramp, temps),
                   _piecewise_function(edges, ramp, values), float(initial_moisture))


@dataclass(frozen=True)
class Diffusivity:
    """D_i(T) = D0_i exp(-Ea / (R T)) along the part axes (x, y, z).

    Arrhenius law as used for epoxies by Shen & Springer (1976), J. Compos.
    Mater. 10:2-20, eq. 9. One activation energy for all directions, so the
    history enters only through the rescaled time tau = integral of
    exp(-Ea/RT(t)) dt.

    Parameters
    ----------
    pre_exponential : tuple of float
        D0 along the part axes x, y, z [m^2/s].
    activation_energy : float
        Ea [J/mol].

    References
    ----------
    C.-H. Shen and G. S. Springer, "Moisture absorption and desorption of composite
    materials", *Journal of Composite Materials* 10(1), 2-20, 1976,
    doi:10.1177/002199837601000101.
    """

    pre_exponential: tuple[float, float, float]
    activation_energy: float

    def arrhenius_factor(self, temperature: np.ndarray) -> np.ndarray:
        """exp(-Ea / (R T)), dimensionless.

        Parameters
        ----------
        temperature : float or array_like
            T [K].

        Returns
        -------
        numpy.ndarray
            The Arrhenius factor [-].
        """
        return np.exp(-self.activation_energy / (GAS_CONSTANT * np.asarray(temperature, float)))

    def __call__(self, temperature: np.ndarray) -> np.ndarray:
        """Principal diffusivities, shape (..., 3), m^2/s.

        Parameters
        ----------
        temperature : float or array_like
            The temperature [K], any shape (...).

        Returns
        -------
        numpy.ndarray
            D along x, y, z [m^2/s], shape (..., 3).
        """
        factor = self.arrhenius_factor(temperature)[..., None]
        return factor * np.asarray(self.pre_exponential, float)


def _piecewise_function(edges: np.ndarray, ramp: np.ndarray, values: np.ndarray):
    """Right-continuous f(t): held at values[k] or linear from values[k-1] over segment k."""
    def evaluate(t):
        t = np.asarray(t, float)
        k = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, values.size - 1)
        start = np.where(ramp[k] & (k > 0), values[np.maximum(k - 1, 0)], values[k])
        fraction = np.clip((t - edges[k]) / (edges[k + 1] - edges[k]), 0.0, 1.0)
        return start + (values[k] - start) * fraction
    return evaluate


def sample_times(exposure: Exposure) -> np.ndarray:
    """Nine samples per segment (its edges included): where T and g are looked at.

    Parameters
    ----------
    exposure : Exposure
        The surface history.

    Returns
    -------
    numpy.ndarray
        The sample times [s], increasing.
    """
    edges = np.asarray(exposure.change_times, float)
    share = np.linspace(0.0, 1.0, 9)[:-1]
    inner = edges[:-1, None] + np.diff(edges)[:, None] * share[None, :]
    return np.concatenate([inner.ravel(), edges[-1:]])


def swing(exposure: Exposure, times=()) -> float:
    """The largest |g - c0| over the history: the scale every accuracy is relative to.

    Parameters
    ----------
    exposure : Exposure
        The surface history g(t) [weight %] and the initial moisture c0 [weight %].
    times : array_like, optional
        More times [s] to look at (the outputs); g is always looked at on nine samples
        of every segment (``sample_times``: a ramp between its ends) and just before each
        change (a held segment's or a ramp's end value).

    Returns
    -------
    float
        max |g - c0| [weight %].
    """
    edges = np.asarray(exposure.change_times, float)
    at = np.concatenate([sample_times(exposure), np.asarray(times, float).ravel()])
    values = np.concatenate([np.asarray(exposure.surface_moisture(at), float),
                             np.asarray(exposure.surface_before(edges), float)])
    return float(np.max(np.abs(values - exposure.initial_moisture)))
