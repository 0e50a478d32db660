"""The error budget: the accuracy a user may ask for, checked in one place
(``check_accuracy``), and how each solve shares the accuracy it is asked between the errors
it makes (the mesh, the steps in time, the interpolation of a tabulated response, a
quadrature...). Every share and margin of the engine is here, named for what it divides and
documented with why it has its value; the modules that spend a share import it from here.

A share ``s`` of the accuracy ``a`` means the part of the error that one approximation may
make is ``s a``; the shares of one solve add up to at most 1. A margin ``m`` (> 1) means a
plan aims at ``a / m`` where its own error model is known to be optimistic.

This module imports nothing of fickcam but the errors, so the scene (which checks
``diffusion.accuracy`` with ``check_accuracy``) loads no part of the engine with it.
"""
from __future__ import annotations

import math

from ...errors import InputError

#: The accuracy a run may ask for: a relative error of the mean moisture [-], a fraction of
#: the moisture swing, in (0, ``MAX_ACCURACY``]. Coarser than 10 % is not an estimate of a
#: moisture any more (the error models behind the plans are measured up to a few %).
MAX_ACCURACY = 0.1


def accuracy_problem(value) -> str | None:
    """Why ``value`` is not an accuracy a run may ask for, or None when it is.

    Parameters
    ----------
    value : float
        The relative accuracy asked [-].

    Returns
    -------
    str or None
        The reason, one phrase ("must lie in (0, 0.1] ..."); None: accepted.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value) or not 0 < value <= MAX_ACCURACY:
        return (f"must lie in (0, {MAX_ACCURACY:g}], a fraction of the moisture swing "
                f"(e.g. 1e-3)")
    return None


def check_accuracy(value, name: str = "accuracy") -> float:
    """The accuracy a run asks for, refused outside (0, ``MAX_ACCURACY``] with one line:
    the one check of the accepted range (the scene's ``diffusion.accuracy``, the command
    line's ``--accuracy``, ``fickcam.run(accuracy=...)`` and ``solve`` all apply it).

    Parameters
    ----------
    value : float
        The relative accuracy asked [-], a fraction of the moisture swing.
    name : str
        What the value was given as, for the message (``accuracy``, ``--accuracy``,
        ``diffusion.accuracy``).

    Returns
    -------
    float
        ``value`` as a float [-].

    Raises
    ------
    fickcam.errors.InputError
        One line naming ``name``, the value and the accepted range.
    """
    why = accuracy_problem(value)
    if why is not None:
        raise InputError(f"{name} {value!r}: {why}")
    return float(value)


# ---------------------------------------------------------------- how a solve shares it
# The Fickian plans (``models``)

#: plane: share of the accuracy allowed to the short-time expansion of the planform's
#: response (the rest: the mesh and the march).
EXPANSION_SHARE = 0.25
#: plane: share of the accuracy allowed to the time steps (the rest: the mesh).
PLANE_TIME_SHARE = 0.1
#: plane: the plan aims at this share of the accuracy, since its error models err by 10-20 %.
PLANE_PLAN_MARGIN = 0.8
#: The planform's mesh error, of the accuracy, where a planform is refined in two phases
#: (two-phase and D(c) planforms; the rest: the march in time).
PLANFORM_SHARE = 0.5
#: The contact layer may be this many times less accurate than the mean (its few cells
#: converge later than the volume's mean; every result states the mean's error).
LAYER_TOLERANCE = 4.0

# The climate (``forcing``, ``superposition``)

#: Share of the accuracy a numerical model (plane) leaves to the sum over a long record
#: (Ms interpolation + tabulation); the exact paths give it all.
RECORD_SHARE = 0.2
#: Tabulated superposition: share of the tolerance for Ms piecewise linear in tau.
TABULATED_INTERPOLATION_SHARE = 0.25
#: Tabulated superposition: share of the tolerance for the tabulation.
TABLE_SHARE = 0.25

# The non-Fickian laws (``nonfickian``)

#: Two-phase modes: share of the tolerance for Ms piecewise linear between nodes (the rest:
#: the modes' march).
TWO_PHASE_INTERPOLATION_SHARE = 0.25
#: Two-phase planform: share of the tolerance left to the Lanczos quadrature.
LANCZOS_SHARE = 0.05
#: Two-phase planform: refine a little past the Richardson prediction (it is asymptotic).
REFINEMENT_SAFETY = 1.2
#: D(c) corrected product: the fine sheet's accuracy is this share of the requested one,
#: not loosened at loose accuracies (measured: benchmarks/results/tuned_constants.md).
SHEET_SHARE = 0.1
#: D(c) sweeps, a drying part (skin): cells at D_min for accuracy / (1 + it (sqrt(ratio) - 1)).
SKIN_CELLS_MARGIN = 1.0
#: D(c) sweeps, no skin: cells sized at D_max for accuracy / ``ABSORPTION_MARGIN``.
ABSORPTION_MARGIN = 2.0
#: D(c) corrected product: on the two-mesh 3-D change of a drying part (``skin_margin``),
#: the cells' margin as ``SKIN_CELLS_MARGIN`` (measured: benchmarks/results/tuned_constants.md).
SKIN_ESTIMATE_MARGIN = 1.0

# Checks of a converging sequence (``accuracy.grid_convergence``)

#: Roache's factor of safety on the three-grid convergence index (Roache, "Perspective: a
#: method for uniform reporting of grid refinement studies", J. Fluids Eng. 116, 1994).
CONVERGENCE_INDEX_SAFETY = 1.25

# After the solve (the limit search of the results)

#: The limit search: a bracket closes when the cubic through the four samples about its
#: crossing and the quadratics through three of them put the crossing within this share of
#: the tolerance of each other (the quadratics' error, which bounds the cubic's).
CROSSING_INTERPOLATION_SHARE = 0.5
