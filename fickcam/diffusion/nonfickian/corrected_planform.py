"""The planform reference of the corrected product (``defect``): the D(c) planform alone
(``defectparts.planform_disc``) on a graded planform refined by 2, 4 and 8 (every finest
width and growth / R), Richardson-extrapolated (second order, then three meshes by
``gridcheck.three_levels``; Richardson 1911, Phil. Trans. R. Soc. A 210:307-357; Roache
1998, Verification and Validation in Computational Science and Engineering, ch. 5), and the
norm every estimate of the corrected product is measured in (``gap``).
"""
from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np

from .corrected_pieces import Level, Pair, Setting, corrected
from ..stepping.dense_output import combined
from ..accuracy.grid_convergence import taken, three_levels
from ..accuracy.error_model import LAYER_TOLERANCE
from ..problem.results import Plan

REFINE = (2.0, 4.0, 8.0)   # planform refinements (finest and growth / R) for Richardson;
#   8 where 4 leaves more than ``PLANFORM_SHARE`` (the bar, k = 2 absorbing at 1e-3: 8.7e-4
#   at x 4, 2 889 cells; x 8 11 569 cells)
PLANFORM_CELLS = 60_000    # the finest planform tried
PLANFORM_SHARE = 0.5       # of the accuracy: the planform's Richardson estimate


def refined_reference(setting: Setting, start: Plan, level: Level, sheet: Pair,
                      accuracy: float, scale, total=None):
    """(planform reference Pair, estimate, planform cells, factor R): the graded planform of
    the plan ``start`` refined by R in ``REFINE`` (finest and growth / R) until the estimate
    is ``PLANFORM_SHARE`` of the accuracy, or ``total(reference, estimate, cells, R)`` (the
    whole estimate of the solve with this reference: ``corrected_levels``) is within the
    accuracy, or the next mesh would pass ``PLANFORM_CELLS`` (the estimate: the change of
    ``level``'s corrected result). The demo cam (k = 2) at 1e-2: the 2x planform's estimate
    6.3e-3 is above the share, but with the 3.3 plan's nested pair (3-D change 7.6e-4) and
    the sheet (8.6e-4) the whole is 8.3e-3: the 4x planform (27 303 cells, 59 CPU s alone)
    is not marched, the run takes 28 CPU s (143-153 on the 1.0 plan's pair with the 4x
    planform, estimate 2.0e-3; the two results 2.8e-3 apart in ``gap``'s norm;
    ``benchmarks/dc_defect_correction.py corrected cam-2 1e-2``).
    After the first refinement: the Richardson extrapolation of the two (second order:
    p_2 + (p_2 - p_1) / 3), its estimate the whole change p_2 - p_1 (R = 1 may be short of
    the asymptotic range: on the demo cam with k = 1 the change the first extrapolation
    made, (p_2 - p_1) / 3, was half of what the next one found). After the second: the mean
    and the layer each by ``three_levels`` (the corrected result is affine in the planform
    reference, so its changes are the reference's).
    Before, the second extrapolation with a third of its change from the first (Romberg's
    check): on the demo cam (k = 2, 1e-3) an estimate 9.0e-4 for an error 1.8e-4."""
    surface = np.asarray(setting.exposure.surface_before(setting.times), float)

    def result(reference):
        return corrected(level.plate, (level.slab, sheet), (level.planform, reference), surface,
                         level.union)
    _, first, start_cells = setting.planform(start.finest, start.growth)
    planforms, cells, factor = [first], 0, 1.0
    for refine in REFINE:
        if cells and start_cells * refine ** 2 > PLANFORM_CELLS:
            break
        _, fine, cells = setting.planform(start.finest / refine, start.growth / refine)
        planforms.append(fine)
        weight, factor = 1.0 / ((refine / factor) ** 2 - 1.0), refine
        if len(planforms) == 2:
            reference = combined(planforms, lambda coarse, f: f + weight * (f - coarse))
            estimate = gap(result(planforms[0]), result(fine), scale)
        else:
            (mean, mean_error), (layer, layer_error) = (
                three_levels(*(result(p)[i] for p in planforms[-3:])) for i in range(2))
            reference = combined(planforms[-2:], partial(taken, mean), partial(taken, layer))
            estimate = max(mean_error, layer_error / LAYER_TOLERANCE) / scale
        if estimate <= PLANFORM_SHARE * accuracy or (
                total is not None and total(reference, estimate, cells, factor) <= accuracy):
            break
    return replace(reference, coarser=(planforms[-2], weight)), estimate, cells, factor



def gap(a, b, scale: float) -> float:
    """The larger of the mean's and the layer's (/ ``LAYER_TOLERANCE``) largest difference,
    relative to ``scale``."""
    return max(float(np.max(np.abs(a[0] - b[0]))),
               float(np.max(np.abs(a[1] - b[1]))) / LAYER_TOLERANCE) / scale
