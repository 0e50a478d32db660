"""Polydyne cams (Stoddart, 'Polydyne cam design', Machine Design 1953; Norton, Design of
Machinery 5th ed., ch. 15): the cam is cut so that the elastic follower train of
:mod:`fickcam.cam.train`, run at the design speed, moves its mass along the chosen motion.

With x = y (the chosen motion) the train equation
m x'' + c (x' - s') + k (x - s) + k_s x + P = 0 gives the cam motion s = y + e, with
k e + c e' = m y'' + k_s y + P. Its periodic solution is exact harmonic by harmonic,
S_n = Y_n / H_n (H_n the train's transfer function at the design speed), i.e. the
inverse of the steady-state response (without damping: Stoddart's s = y + (m y'' + k_s y)/k).
The constant P/k is left out, so that the cam keeps its base circle in the low dwell and
the output is the chosen motion minus the static compression P/(k + k_s) of the train,
the same constant offset an elastic follower on an ordinary cam has.

The correction's harmonics ride on the motion segments (``MotionSegment.correction``);
its second derivative jumps where y'''' does (the cam's curvature steps at the joints of a
4-5-6-7 law), which the truncated series rounds over 1/N of a turn.
"""
from __future__ import annotations

from dataclasses import replace
import math

import numpy as np

from .fourier import harmonics
from .train import FINE, Train, transfer
from .motion import follower_motion
from .design import CamState
from .train import train_of


def _correction_harmonics(segments, train: Train, speed: float) -> np.ndarray:
    """Harmonics of e - P/k = s - y for the chosen motion ``segments`` at cam speed ``speed``."""

    fine = np.linspace(0.0, 2 * math.pi, FINE, endpoint=False)
    y = harmonics(follower_motion(segments, fine)[0])
    n = np.arange(len(y))
    return y * (1.0 / transfer(train, speed, n) - 1.0)


def polydyne_design(design, modulus: float | None):
    """``design`` with its segments carrying the polydyne correction, for the train at the
    as-designed state (dry mass; a rod/lever with the dry modulus ``modulus``).

    Parameters
    ----------
    design : CamDesign
        The design, with its polydyne speed [rad/s].
    modulus : float or None
        Dry modulus of the rod or lever [Pa]; None for a train given by its stiffness.

    Returns
    -------
    CamDesign
        The design whose segments carry the correction harmonics [m].

    References
    ----------
    Stoddart, D. (1953). Polydyne cam design. Machine Design 25(1), January 1953.
    Norton (2012), ch. 15; in full in :mod:`fickcam.cam`.
    """


    state = CamState(follower_train_modulus=modulus)
    train = train_of(design, state, 0.0)
    coefficients = tuple(_correction_harmonics(design.segments, train, design.polydyne_speed))
    return replace(design, segments=tuple(replace(s, correction=coefficients) for s in design.segments))
