r"""Elastic follower train: Norton's single-degree-of-freedom model of a cam follower.

The cam imposes the displacement :math:`s(t)` on one end of the follower train (stiffness
:math:`k`, internal damping :math:`c` in parallel with it); the other end is the lumped
follower mass :math:`m`, held against the cam by the return spring :math:`k_s` and the
constant load :math:`P` (preload, external load, weight and the spring compression from a
swollen base circle), acting on the mass (Norton, Design of Machinery 5th ed., ch. 15;
Koster, Vibrations of Cam Mechanisms, 1974, ch. 2):

.. math::

    m \ddot x + c (\dot x - \dot s) + k (x - s) + k_s x + P = 0, \qquad
    F_c = k (s - x) + c (\dot s - \dot x),

:math:`F_c` the force the cam transmits along the follower axis (contact is lost where
it would be negative), with :math:`c = 2 \zeta \sqrt{(k + k_s) m}` and
:math:`\omega_n = \sqrt{(k + k_s)/m}`. Damping sits in the train (material damping), so
that :math:`k \to \infty` gives :math:`x \to s` and :math:`F_c \to m \ddot s + k_s s + P`,
the rigid follower of :mod:`fickcam.cam.dynamics`.

The periodic steady state at a constant cam speed :math:`\omega` is exact through the
Fourier series of :math:`s(\theta)`: each harmonic :math:`n` passes with the transfer
function

.. math::

    H_n = \frac{k + i n \omega c}{k + k_s - m n^2 \omega^2 + i n \omega c}

(linear system, Norton ch. 15 frequency response; Koster sec. 2.3). The coefficients
come from the FFT of :math:`s` on a fine grid (aliasing error of order :math:`N^{-p}` for
a motion with :math:`p - 1` continuous derivatives) and the series is summed at any angle.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..mechanisms.response import Response
from .fourier import at_angles, harmonics, on_grid, series
from . import dynamics as dyn
from .kinematics import dry_lowest_height, follower_heights
from .motion import follower_motion

#: samples per revolution for the Fourier coefficients of the cam motion
FINE = 8192
#: speeds scanned for the dynamic jump speed, up to SCAN_LIMIT x the rigid jump speed
SCAN_SPEEDS = 240
SCAN_LIMIT = 2.0


@dataclass(frozen=True)
class Train:
    """Follower train at one ageing time (SI): stiffness k, mass m, return spring k_s,
    damping ratio zeta, constant load P on the mass.

    Parameters
    ----------
    stiffness : float
        The train's stiffness k [N/m].
    mass : float
        The lumped follower mass m [kg].
    spring_rate : float
        The return spring's rate k_s [N/m].
    damping_ratio : float
        zeta [-].
    load : float
        The constant load P on the mass [N].

    References
    ----------
    R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, ch. 15.

    M. P. Koster, *Vibrations of Cam Mechanisms*, Macmillan, 1974.
    """

    stiffness: float
    mass: float
    spring_rate: float
    damping_ratio: float
    load: float = 0.0

    @property
    def total_stiffness(self) -> float:
        return self.stiffness + self.spring_rate

    @property
    def natural_frequency(self) -> float:
        """omega_n = sqrt((k + k_s)/m) (rad/s) (Norton ch. 15 with k_eff = k + k_s)."""
        return math.sqrt(self.total_stiffness / self.mass)

    @property
    def damping(self) -> float:
        """c = 2 zeta sqrt(k_eff m) (Norton ch. 10, critical damping 2 sqrt(k m))."""
        return 2.0 * self.damping_ratio * math.sqrt(self.total_stiffness * self.mass)

    @property
    def damped_frequency(self) -> float:
        return self.natural_frequency * math.sqrt(1.0 - self.damping_ratio ** 2)

    def equilibrium(self, s):
        """Static position of the mass for a cam at s: x = (k s - P)/(k + k_s)."""
        return (self.stiffness * np.asarray(s, float) - self.load) / self.total_stiffness


def rod_stiffness(modulus: float, length: float, diameter: float) -> float:
    """k = E A/L of a round stem in tension/compression, A = pi d^2/4 (Gere & Goodno,
    Mechanics of Materials, eq. 2.3).

    Parameters
    ----------
    modulus : float
        Young's modulus E [Pa].
    length : float
        The stem's length L [m].
    diameter : float
        Its diameter d [m].

    Returns
    -------
    float
        The axial stiffness k [N/m].
    """
    return modulus * math.pi * diameter ** 2 / 4.0 / length


def lever_stiffness(modulus: float, length: float, width: float, height: float) -> float:
    """k = 3 E I/L^3 at the tip of a cantilever lever, I = w h^3/12 (Gere & Goodno,
    Table H-1, case 4).

    Parameters
    ----------
    modulus : float
        Young's modulus E [Pa].
    length : float
        The lever's length L from its support to the tip [m].
    width : float
        The section's width w [m].
    height : float
        The section's height h, in the direction of the load [m].

    Returns
    -------
    float
        The tip stiffness k [N/m].
    """
    return 3.0 * modulus * width * height ** 3 / 12.0 / length ** 3


# ------------------------------------------------------------------ steady state


def transfer(train: Train, omega: float, n) -> np.ndarray:
    """H_n = X_n/S_n = (k + i n omega c)/(k + k_s - m (n omega)^2 + i n omega c).

    Parameters
    ----------
    train : Train
        The follower train.
    omega : float
        The cam speed [rad/s].
    n : int or array_like
        The harmonic orders [-].

    Returns
    -------
    numpy.ndarray
        H_n [-], complex.
    """
    w = np.asarray(n, float) * omega
    num = train.stiffness + 1j * w * train.damping
    return num / (train.total_stiffness - train.mass * w ** 2 + 1j * w * train.damping)


def _steady_harmonics(train: Train, omega: float, s_harmonics) -> np.ndarray:
    """X_n of the periodic steady state; the constant load shifts the mean (n = 0) only."""
    n = np.arange(len(s_harmonics))
    x = transfer(train, omega, n) * s_harmonics
    x[0] -= train.load / train.total_stiffness
    return x


# ------------------------------------------------------------------ start from rest


def _from_rest(train: Train, omega: float, x_harmonics, s0: float, theta):
    """(x, x') over the first turn when the mass starts at rest in equilibrium at theta = 0:
    the periodic solution plus the free vibration u = e^{-zeta wn t}(A cos wd t + B sin wd t)
    that makes up the initial difference (superposition; Norton ch. 10). zeta < 1."""
    theta = np.asarray(theta, float)
    t = theta / omega
    u0 = train.equilibrium(s0) - series(x_harmonics, 0.0)
    v0 = -series(x_harmonics, 0.0, 1, omega)
    wn, wd, zeta = train.natural_frequency, train.damped_frequency, train.damping_ratio
    a, b = u0, (v0 + zeta * wn * u0) / wd
    decay = np.exp(-zeta * wn * t)
    u = decay * (a * np.cos(wd * t) + b * np.sin(wd * t))
    du = decay * ((b * wd - zeta * wn * a) * np.cos(wd * t) - (a * wd + zeta * wn * b) * np.sin(wd * t))
    return (at_angles(x_harmonics, theta) + u, at_angles(x_harmonics, theta, 1, omega) + du)


def free_amplitude(train: Train, offset, velocity):
    """Amplitude of the damped free vibration that starts from an offset u and velocity v
    about the equilibrium: sqrt(u^2 + ((v + zeta wn u)/wd)^2).

    Parameters
    ----------
    train : Train
        The follower train.
    offset : float or array_like
        The start offset u from the equilibrium [m].
    velocity : float or array_like
        The start velocity v [m/s].

    Returns
    -------
    numpy.ndarray
        The amplitude [m].
    """
    wn, wd = train.natural_frequency, train.damped_frequency
    return np.hypot(offset, (velocity + train.damping_ratio * wn * offset) / wd)


def cycloidal_residual_amplitude(lift: float, rise_time: float, natural_frequency: float,
                                 static_ratio: float = 1.0) -> float:
    """Residual vibration after a cycloidal rise of ``lift`` in ``rise_time`` on an undamped
    SDOF follower starting at rest: A = g h |sin(pi r)|/(pi r |1 - r^2|), r = t1 f_n, g = k/(k+k_s).

    Derivation (Duhamel; Koster 1974 sec. 3.2; Norton ch. 15): u = x - g s obeys
    u'' + wn^2 u = -g s'', s'' = (2 pi h/t1^2) sin(a t), a = 2 pi/t1, so after the rise
    A = g/wn |int_0^t1 s'' e^{-i wn t} dt| = g/wn (2 pi h/t1^2) a |1 - e^{-i wn t1}|/|a^2 - wn^2|,
    and |1 - e^{-i wn t1}| = 2 |sin(wn t1/2)|. r = 1 is the removable limit g h/2.

    Parameters
    ----------
    lift : float
        The rise h [m].
    rise_time : float
        The rise's duration t1 [s].
    natural_frequency : float
        The follower's natural angular frequency wn [rad/s].
    static_ratio : float
        g = k/(k + k_s) [-], the static share of the cam's motion the mass follows.

    Returns
    -------
    float
        The residual vibration amplitude [m].
    """
    r = rise_time * natural_frequency / (2.0 * math.pi)
    if abs(r - 1.0) < 1e-9:
        return static_ratio * lift / 2.0
    return static_ratio * lift * abs(math.sin(math.pi * r)) / (math.pi * r * abs(1.0 - r * r))


# ------------------------------------------------------------------ jump


def _lowest_axial_force(train: Train, omega: float, s_harmonics, s_fine, ds_fine):
    """Smallest F_c = k (s - x) + c (s' - x') over the fine grid at cam speed omega."""
    size = len(ds_fine)
    x_harm = _steady_harmonics(train, omega, s_harmonics)
    deflection = s_fine - on_grid(x_harm, size)
    rate = omega * ds_fine - on_grid(x_harm, size, 1, omega)
    return float(np.min(train.stiffness * deflection + train.damping * rate))


def dynamic_jump_speed(train: Train, s_harmonics, s_fine, ds_fine, upper: float) -> float:
    """Lowest cam speed at which the steady-state contact force reaches zero somewhere:
    scan SCAN_SPEEDS speeds up to ``upper``, then Brent on the first sign change. 0 if the
    follower is not held at rest, inf if it never separates below ``upper``.

    Parameters
    ----------
    train : Train
        The follower train (SI).
    s_harmonics : numpy.ndarray
        Harmonics of the cam motion s [m] (:func:`fickcam.cam.fourier.harmonics`).
    s_fine, ds_fine : numpy.ndarray
        The cam motion s [m] and ds/dtheta [m/rad] on the fine grid of a turn.
    upper : float
        Highest cam speed scanned [rad/s].

    Returns
    -------
    float
        The dynamic jump speed [rad/s].

    References
    ----------
    Norton (2012), ch. 15; Koster (1974); in full in :class:`Train`.
    """
    # deferred: keeps scipy.optimize off the start-up path
    from scipy.optimize import brentq

    def margin(omega):
        return _lowest_axial_force(train, omega, s_harmonics, s_fine, ds_fine)

    if margin(0.0) <= 0.0:
        return 0.0
    speeds = np.linspace(0.0, upper, SCAN_SPEEDS + 1)[1:]
    previous = 0.0
    for omega in speeds:
        if margin(omega) <= 0.0:
            return float(brentq(margin, previous, omega, xtol=1e-9 * omega, rtol=1e-12))
        previous = omega
    return float("inf")


# ------------------------------------------------------------------ one ageing time


def train_of(design, state, load: float) -> Train:
    """The follower train of ``design`` at ageing state ``state`` (needs design.train): its
    stiffness given, or that of a rod or lever of the aged modulus.

    Parameters
    ----------
    design : CamDesign
        The design (train kind and sizes [m], spring rate [N/m], damping ratio [-]).
    state : CamState
        The aged state (train modulus [Pa], follower mass [kg]).
    load : float
        Constant load on the follower mass [N].

    Returns
    -------
    Train
        The train.
    """
    kind, *sizes = design.train
    if kind == "stiffness":
        k = sizes[0]
    else:
        modulus = state.follower_train_modulus or design.follower_modulus
        k = (rod_stiffness if kind == "rod" else lever_stiffness)(modulus, *sizes)
    mass = design.follower_mass if state.follower_mass is None else state.follower_mass
    return Train(k, mass, design.spring_rate, design.damping_ratio, load)


def _events(design):
    """Cam angles at which a dwell follows a rise or return (residual vibration is measured there)."""
    segments = design.segments
    return [b.start for a, b in zip(segments, segments[1:] + segments[:1])
            if a.law is not None and a.height != 0.0 and b.height == 0.0]


@dataclass(frozen=True)
class SteadyState:
    """The train and its periodic steady state at the scene speed, on the fine grid:
    cam motion s (m, from the aged lowest position), ds/dtheta, d2s/dtheta2, the rigid
    holding force (N), and the harmonics of s and of the mass position x.

    Parameters
    ----------
    train : Train
        The follower train.
    lowest : float
        Aged lowest follower position, the origin of s [m].
    s : numpy.ndarray
        Cam motion [m].
    ds : numpy.ndarray
        ds/dtheta [m/rad].
    d2s : numpy.ndarray
        d2s/dtheta2 [m/rad^2].
    holding : numpy.ndarray
        Rigid holding force (spring, preload, load) [N].
    s_harmonics, x_harmonics : numpy.ndarray
        Harmonics of s and of the mass position x [m].
    """

    train: Train
    lowest: float
    s: np.ndarray
    ds: np.ndarray
    d2s: np.ndarray
    holding: np.ndarray
    s_harmonics: np.ndarray
    x_harmonics: np.ndarray


def _steady_state(design, state) -> SteadyState:
    """:class:`SteadyState` of ``design`` at ageing state ``state`` (needs design.train)."""

    fine = np.linspace(0.0, 2 * np.pi, FINE, endpoint=False)
    (height, d1, d2, _), (lowest, _) = follower_heights(design, state, fine)
    mass = design.follower_mass if state.follower_mass is None else state.follower_mass
    holding = dyn.axial_force(mass, 0.0, design.spring_rate, height - dry_lowest_height(design),
                              design.spring_preload, design.external_load, design.gravity)
    train = train_of(design, state, float(holding[0] - design.spring_rate * (height[0] - lowest)))
    s_harm = harmonics(height - lowest)
    return SteadyState(train, lowest, height - lowest, d1, d2, holding, s_harm,
                       _steady_harmonics(train, design.speed, s_harm))


def dynamic_response(design, state, cam_angle, rigid) -> Response:
    """Elastic-follower variables at one ageing time (SI; speeds in rad/s, frequency in Hz)
    from the rigid variables ``rigid`` (pressure angle) of
    :func:`~fickcam.cam.model.cam_response`. Displacements are measured like
    follower_displacement, from the lowest rigid position: the static compression of the
    train under the load P shows as a constant offset -P/(k + k_s).

    Parameters
    ----------
    design : CamDesign
        The design (SI; speed [rad/s]).
    state : CamState
        The aged state.
    cam_angle : array_like
        Cam angles [rad].
    rigid : Mapping
        Variables of the rigid follower; its pressure_angle [rad] is used.

    Returns
    -------
    Response
        dynamic_follower_displacement, dynamic_displacement_error,
        startup_follower_displacement [m], dynamic_contact_force [N], natural_frequency
        [Hz], follower_train_stiffness [N/m], dynamic_jump_speed [rad/s],
        residual_vibration [m], minimum_dynamic_contact_force [N], and the notices.

    References
    ----------
    Norton (2012), ch. 15; Koster (1974); in full in :class:`Train`.
    """

    theta = np.asarray(cam_angle, float)
    omega = design.speed
    steady = _steady_state(design, state)
    train, x_harm = steady.train, steady.x_harmonics
    (s, ds, _, _), _ = follower_heights(design, state, theta)
    s = s - steady.lowest
    x, dx = at_angles(x_harm, theta), at_angles(x_harm, theta, 1, omega)
    axial = train.stiffness * (s - x) + train.damping * (omega * ds - dx)
    force = dyn.normal_force(axial, rigid["pressure_angle"], dx, design.guide_factor)
    rigid_jump = dyn.jump_speed(train.mass, steady.d2s, steady.holding)
    upper = SCAN_LIMIT * (rigid_jump if math.isfinite(rigid_jump) else
                          max(omega, train.natural_frequency))
    jump = dynamic_jump_speed(train, steady.s_harmonics, steady.s, steady.ds, upper)
    residual = residual_vibrations(design, state, steady)
    variables = {
        "dynamic_follower_displacement": x,
        "dynamic_displacement_error": x - s,
        "dynamic_contact_force": force,
        "startup_follower_displacement": _from_rest(train, omega, x_harm, steady.s[0], theta)[0],
        "natural_frequency": train.natural_frequency / (2 * np.pi),
        "follower_train_stiffness": train.stiffness,
        "dynamic_jump_speed": jump,
        "residual_vibration": float(np.max(residual)) if residual.size else np.nan,
        "minimum_dynamic_contact_force": float(np.min(force)),
    }
    if design.polydyne_speed is not None:
        variables.update(_polydyne_variables(design, theta, x))
    return Response(variables, _separation_notices(theta, force))


def _polydyne_variables(design, theta, x) -> dict:
    """Profile correction (cam motion minus chosen motion, dry design) and the output error:
    the mass's motion minus the chosen motion, both from the chosen motion's lowest point
    (which removes the constant static compression of the train)."""

    chosen = follower_motion(design.segments, theta, corrected=False)[0]
    low = int(np.argmin(chosen))
    error = (x - x[low]) - (chosen - chosen[low])
    return {"polydyne_correction": follower_motion(design.segments, theta)[0] - chosen,
            "polydyne_output_error": error,
            "peak_polydyne_output_error": float(np.max(np.abs(error)))}


def residual_vibrations(design, state, steady: SteadyState | None = None) -> np.ndarray:
    """Free-vibration amplitude (m) at the start of each dwell that follows a rise or return,
    over the first turn from rest (Koster 1974 sec. 3.2 'residual vibration'); empty for an
    eccentric cam or a motion without such a dwell.

    Parameters
    ----------
    design : CamDesign
        The design (SI).
    state : CamState
        The aged state.
    steady : SteadyState, optional
        The steady state, if already computed.

    Returns
    -------
    numpy.ndarray
        The amplitude at each such dwell [m].

    References
    ----------
    Koster, M. P. (1974). Vibrations of Cam Mechanisms, sec. 3.2. London: Macmillan.
    """

    events = np.asarray(_events(design) if design.kind == "motion" else [], float)
    if events.size == 0:
        return np.zeros(0)
    steady = steady or _steady_state(design, state)
    train = steady.train
    x, dx = _from_rest(train, design.speed, steady.x_harmonics, float(steady.s[0]), events)
    s_end = follower_heights(design, state, events)[0][0] - steady.lowest
    return free_amplitude(train, x - train.equilibrium(s_end), dx)


def _separation_notices(theta, force) -> list[str]:
    apart = np.nonzero(force < 0.0)[0]
    if not apart.size:
        return []
    return [f"elastic follower leaves the cam at the running speed: dynamic contact force < 0 "
            f"over {apart.size * 360.0 / theta.size:.3g} deg of the turn, first at "
            f"{math.degrees(theta[apart[0]]):.4g} deg (see dynamic_jump_speed)"]
