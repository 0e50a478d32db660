"""Fourier series over one cam turn: the harmonics of a sampled periodic function and
their evaluation (with time derivatives at a speed) at any angles. A leaf of
fickcam.cam shared by the follower train (train.py), the polydyne correction
(polydyne.py) and the design motion (motion.py).

s(theta) = Re sum_n w_n S_n e^{i n theta}, w_0 = 1, w_n = 2 (the real FFT;
Press et al., Numerical Recipes 3rd ed. s. 12.3).
"""
from __future__ import annotations

import numpy as np


def harmonics(s) -> np.ndarray:
    """Complex amplitudes S_n (n = 0 .. N/2) with s(theta) = Re sum w_n S_n e^{i n theta},
    w_0 = 1 and w_n = 2 otherwise: the real FFT of s sampled at N angles over a turn.

    Parameters
    ----------
    s : array_like
        The function at N equally spaced angles over a turn, starting at 0 [any unit].

    Returns
    -------
    numpy.ndarray
        S_n, n = 0 .. N/2 [unit of s].

    References
    ----------
    Press, W. H., Teukolsky, S. A., Vetterling, W. T. & Flannery, B. P. (2007). Numerical
    Recipes: The Art of Scientific Computing, 3rd ed., sec. 12.3. Cambridge University Press.
    """
    return np.fft.rfft(np.asarray(s, float)) / len(s)


def series(coefficients, theta, order: int = 0, omega: float = 1.0):
    """d^order/dt^order of Re sum w_n X_n e^{i n theta} at theta = omega t (any angles).

    Parameters
    ----------
    coefficients : array_like of complex
        The harmonics X_n (:func:`harmonics`) [unit of s].
    theta : float or array_like
        Cam angles [rad].
    order : int
        Order of the time derivative.
    omega : float
        Cam speed [rad/s]; 1 gives derivatives per radian.

    Returns
    -------
    numpy.ndarray
        The derivative at each angle [unit of s / s^order].
    """
    n = np.arange(len(coefficients))
    weights = np.where(n == 0, 1.0, 2.0) * (1j * n * omega) ** order * coefficients
    theta = np.asarray(theta, float)
    phase = np.exp(1j * np.multiply.outer(theta, n))
    return np.real(phase @ weights)


def on_grid(coefficients, size: int, order: int = 0, omega: float = 1.0):
    """:func:`series` on the grid of ``size`` angles over a turn (inverse FFT).

    Parameters
    ----------
    coefficients : array_like of complex
        The harmonics X_n [unit of s].
    size : int
        Number of equally spaced angles, starting at 0.
    order : int
        Order of the time derivative.
    omega : float
        Cam speed [rad/s].

    Returns
    -------
    numpy.ndarray
        The derivative at each grid angle [unit of s / s^order].
    """
    n = np.arange(len(coefficients))
    return np.fft.irfft(coefficients * (1j * n * omega) ** order * size, n=size)


def at_angles(coefficients, theta, order: int = 0, omega: float = 1.0):
    """:func:`series` at ``theta``; through the inverse FFT on a multiple of the grid when
    theta is the regular grid of a turn starting at 0 (the result grid), which is exact too.

    Parameters
    ----------
    coefficients : array_like of complex
        The harmonics X_n [unit of s].
    theta : float or array_like
        Cam angles [rad].
    order, omega
        As :func:`series` takes them: derivative order, cam speed [rad/s].

    Returns
    -------
    numpy.ndarray
        The derivative at each angle [unit of s / s^order].
    """
    theta = np.asarray(theta, float)
    count = theta.size
    regular = np.linspace(0.0, 2 * np.pi, count, endpoint=False)
    if count < 4 or theta.shape != regular.shape or not np.allclose(theta, regular, atol=1e-12):
        return series(coefficients, theta, order, omega)
    step = -(-2 * (len(coefficients) - 1) // count)
    return on_grid(coefficients, count * step, order, omega)[::step]


def correction_motion(coefficients, theta):
    """(e, e', e'', e''') per radian of a correction series at cam angles.

    Parameters
    ----------
    coefficients : array_like of complex
        The harmonics of the correction e(theta) [m].
    theta : float or array_like
        Cam angles [rad].

    Returns
    -------
    tuple of numpy.ndarray
        e [m], de/dtheta [m/rad], d2e/dtheta2 [m/rad^2], d3e/dtheta3 [m/rad^3].
    """
    return tuple(series(coefficients, theta, order) for order in range(4))
