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
    w_0 = 1 and w_n = 2 otherwise: the real FFT of s sampled at N angles over a turn."""
    return np.fft.rfft(np.asarray(s, float)) / len(s)


def series(coefficients, theta, order: int = 0, omega: float = 1.0):
    """d^order/dt^order of Re sum w_n X_n e^{i n theta} at theta = omega t (any angles)."""
    n = np.arange(len(coefficients))
    weights = np.where(n == 0, 1.0, 2.0) * (1j * n * omega) ** order * coefficients
    theta = np.asarray(theta, float)
    phase = np.exp(1j * np.multiply.outer(theta, n))
    return np.real(phase @ weights)


def on_grid(coefficients, size: int, order: int = 0, omega: float = 1.0):
    """The same series on the grid of ``size`` angles over a turn (inverse FFT)."""
    n = np.arange(len(coefficients))
    return np.fft.irfft(coefficients * (1j * n * omega) ** order * size, n=size)


def at_angles(coefficients, theta, order: int = 0, omega: float = 1.0):
    """:func:`series` at ``theta``; through the inverse FFT on a multiple of the grid when
    theta is the regular grid of a turn starting at 0 (the result grid), which is exact too."""
    theta = np.asarray(theta, float)
    count = theta.size
    regular = np.linspace(0.0, 2 * np.pi, count, endpoint=False)
    if count < 4 or theta.shape != regular.shape or not np.allclose(theta, regular, atol=1e-12):
        return series(coefficients, theta, order, omega)
    step = -(-2 * (len(coefficients) - 1) // count)
    return on_grid(coefficients, count * step, order, omega)[::step]


def correction_motion(coefficients, theta):
    """(e, e', e'', e''') per radian at cam angles theta (rad) from the harmonics."""
    return tuple(series(coefficients, theta, order) for order in range(4))
