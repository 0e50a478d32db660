"""The rescaled clock: every direction shares one Arrhenius factor a(T) = exp(-Ea/RT),
so with tau(t) = integral_0^t a(T(s)) ds Fick's law dc/dt = div(D(T) grad c) becomes
dc/dtau = div(D0 grad c) with a constant operator (Crank 1975 §7.2, eq. 7.5: a
diffusion coefficient depending on time only). Held segments have a constant factor
(tau exact); ramps are integrated by Gauss-Legendre (the integrand is analytic).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

from dataclasses import dataclass
import numpy as np

from ..problem.cache import RunCache, run_cache
from ..problem.exposure import Diffusivity, Exposure, sample_times

TAU_NODES = 12
_TAU_NODES, _TAU_WEIGHTS = np.polynomial.legendre.leggauss(TAU_NODES)


class RescaledTime:
    """The rescaled clock tau(t) = integral_0^t exp(-Ea / (R T(s))) ds of an exposure.

    Exact on held segments; Gauss-Legendre (12 nodes, analytic integrand: exact to
    ~1e-15 for a 40 K ramp at Ea = 40 kJ/mol) on ramps. Calling it with physical times
    t [s] returns tau [s] (seconds weighted by the Arrhenius factor, which is [-]).

    Parameters
    ----------
    diffusivity : Diffusivity
        Gives the Arrhenius factor exp(-Ea/(R T)) [-] of a temperature [K].
    exposure : Exposure
        The history: change times [s], temperature [K].

    References
    ----------
    Crank (1975) §7.2, eq. 7.5 (module docstring).
    """

    def __init__(self, diffusivity, exposure):
        self.rate = diffusivity.arrhenius_factor
        self.exposure = exposure
        self.edges = np.asarray(exposure.change_times, float)
        self.ramp = np.asarray(exposure.ramp, bool)
        self.held_rate = self.rate(exposure.temperature(self.edges[:-1]))
        whole = self.partial(np.arange(self.ramp.size), self.edges[:-1], self.edges[1:])
        self.cumulative = np.concatenate([[0.0], np.cumsum(whole)])

    def segment(self, t) -> np.ndarray:
        return np.clip(np.searchsorted(self.edges, t, side="right") - 1, 0, self.ramp.size - 1)

    def partial(self, segment, lower, upper) -> np.ndarray:
        """integral over [lower, upper] inside one segment."""
        segment, lower, upper = np.broadcast_arrays(segment, np.asarray(lower, float),
                                                    np.asarray(upper, float))
        value = self.held_rate[segment] * (upper - lower)
        ramped = self.ramp[segment] & (upper != lower)  # an empty interval adds 0
        if np.any(ramped):
            lo, hi = lower[ramped], upper[ramped]
            half = 0.5 * (hi - lo)
            s = (lo + hi)[..., None] * 0.5 + half[..., None] * _TAU_NODES
            rate = self.rate(self.exposure.temperature(s))
            value[ramped] = half * (rate @ _TAU_WEIGHTS)
        return value

    def between(self, s, t) -> np.ndarray:
        """tau(t) - tau(s) for s <= t, as a sum of positive parts."""
        s, t = np.broadcast_arrays(np.asarray(s, float), np.asarray(t, float))
        ks, kt = self.segment(s), self.segment(t)
        same = ks == kt
        upper_s = np.where(same, t, self.edges[np.minimum(ks + 1, self.ramp.size)])
        head = self.partial(kt, np.where(same, t, self.edges[kt]), t)
        middle = np.where(same, 0.0, self.cumulative[kt] - self.cumulative[np.minimum(ks + 1, kt)])
        return np.maximum(self.partial(ks, s, upper_s) + middle + head, 0.0)

    def __call__(self, t) -> np.ndarray:
        return self.between(np.zeros_like(np.asarray(t, float)), t)


def clock_of(diffusivity: Diffusivity, exposure: Exposure, cache: RunCache) -> RescaledTime:
    """The ``RescaledTime`` of a (diffusivity, exposure), built once per run.

    The plan, the scales and the superposition share it (a year of hourly rows
    integrates 8760 ramps, 0.07 s); the tables it made itself are read-only.

    Parameters
    ----------
    diffusivity : Diffusivity
        The material's diffusivity (its activation energy [J/mol]).
    exposure : Exposure
        The history (times [s], temperature [K]).
    cache : RunCache
        The run's cache.

    Returns
    -------
    RescaledTime
        The clock, t [s] -> tau [s].
    """
    def build():
        clock = RescaledTime(diffusivity, exposure)
        for array in (clock.held_rate, clock.cumulative):
            array.setflags(write=False)
        return clock
    return cache.get(("rescaled clock", diffusivity, exposure), build)


def reference_factor(diffusivity: Diffusivity, exposure: Exposure) -> float:
    """The largest Arrhenius factor met in the history, a_ref (the hottest segment's).

    Parameters
    ----------
    diffusivity : Diffusivity
        Gives the factor exp(-Ea/(R T)) (Ea [J/mol]).
    exposure : Exposure
        Its temperatures [K] at the sample times [s].

    Returns
    -------
    float
        a_ref = max exp(-Ea / (R T)) [-] over the sampled history.
    """
    t = sample_times(exposure)
    return float(np.max(diffusivity.arrhenius_factor(exposure.temperature(t))))


def rescaled_time(diffusivity: Diffusivity, exposure: Exposure, t: np.ndarray,
                  cache: RunCache | None = None, a_ref: float | None = None) -> np.ndarray:
    """The rescaled time tau(t) / a_ref: seconds at the reference (hottest) temperature.

    Parameters
    ----------
    diffusivity : Diffusivity
        The Arrhenius law of the material (Ea [J/mol]).
    exposure : Exposure
        The temperature history (T [K] over t [s]).
    t : numpy.ndarray
        Physical times [s].
    cache : RunCache, optional
        The run's cache (None: a fresh one).
    a_ref : float, optional
        The reference Arrhenius factor [-] (None: ``reference_factor``).

    Returns
    -------
    numpy.ndarray
        The rescaled times [s].
    """
    a_ref = reference_factor(diffusivity, exposure) if a_ref is None else a_ref
    return clock_of(diffusivity, exposure, run_cache(cache))(np.asarray(t, float)) / a_ref


@dataclass(frozen=True)
class Scales:
    """Rescaled time and the length scale of the non-dimensional problem.

    Parameters
    ----------
    a_ref : float
        The reference (largest) Arrhenius factor [-].
    d_ref : float
        The through-thickness diffusivity at the reference temperature [m^2/s].
    length : float
        The part's thickness [m].
    clock : RescaledTime
        The rescaled clock, t [s] -> tau [s].
    """

    a_ref: float
    d_ref: float      # through-thickness D at the reference (hottest) temperature, m^2/s
    length: float     # thickness, m
    clock: RescaledTime

    def star(self, tau_seconds: np.ndarray) -> np.ndarray:
        """tau* = tau D_ref / L^2 (Fourier number of the rescaled time, tau in reference s)."""
        return np.asarray(tau_seconds) * self.d_ref / self.length ** 2

    def tau_star(self, t: np.ndarray) -> np.ndarray:
        """tau* at physical times ``t`` (s)."""
        return self.star(self.clock(np.asarray(t, float)) / self.a_ref)


def scales(geometry, diffusivity: Diffusivity, exposure: Exposure,
           cache: RunCache | None = None) -> Scales:
    """The scales of a part: reference factor, its D_z there, its thickness, the clock.

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part; its ``thickness`` [m] is the length scale.
    diffusivity : Diffusivity
        The material's diffusivity (pre-exponential factors [m^2/s]).
    exposure : Exposure
        The history (times [s], temperature [K]).
    cache : RunCache, optional
        The run's cache for the clock (None: a fresh one).

    Returns
    -------
    Scales
        a_ref [-], D_z at the reference temperature [m^2/s], thickness [m] and clock.
    """
    a_ref = reference_factor(diffusivity, exposure)
    return Scales(a_ref, float(diffusivity.pre_exponential[2]) * a_ref,
                  float(geometry.thickness), clock_of(diffusivity, exposure, run_cache(cache)))
