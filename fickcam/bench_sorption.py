"""``fickcam bench`` rows for non-Fickian sorption (``materials.NAME.sorption``).

Unit surface step (c0 = 0, Ms = 1 weight %, isothermal), the full uptake curve at the
bench's 61 times, error = largest |mean - reference| (relative to the step):

- two-phase (Langmuir; gamma = beta = 0.1 pi^2 D/h^2): the sheet against Carter &
  Kibler's exact series (``two_phase.two_phase_sheet_uptake``), the disc's FiPy (r, z)
  block march against its exact modes at accuracy 1e-8, and a circular cam plate (a
  160-gon, area short by 2.6e-4) on its planform quadrature (``planmodes``) against the
  exact modes of that disc;
- concentration-dependent (D = D0 exp(2 c/Mm)): the FiPy slab against a 800-node method
  of lines (scipy BDF, tolerances 1e-10), an independent discretisation; a 4 x 3 x 2 mm
  plate (CamPlate, the 3-D prisms cut at the mid-plane, ``mirrored``) against the same
  model run at ``PLANFORM_REFERENCE`` (a fine run: no independent 3-D solution exists),
  by the 3-D cells alone (``solid``) and by ``auto``'s corrected sheet x planform product
  (``diffusion.defect``), the two against the same fine 3-D run.
"""
from __future__ import annotations

import numpy as np

EXPONENT = 2.0
EXCHANGE = 0.1   # gamma = beta = EXCHANGE pi^2 D / h^2
PLANFORM_REFERENCE = 2e-2  # accuracy of the plate's fine reference run (15.6 k cells)


def sorption_cases(quick: bool) -> list[tuple]:
    """(name, geometry, law name, models, accuracies)."""
    from .diffusion import CamPlate, Disc, Sheet

    accuracies = (1e-2,) if quick else (1e-2, 1e-3)
    angle = np.linspace(0.0, 2.0 * np.pi, 160, endpoint=False)
    plate = CamPlate(5e-3 * np.cos(angle), 5e-3 * np.sin(angle), 2e-3)
    block = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), 2e-3)
    return [("sheet 2 mm, two-phase", Sheet(2e-3), "langmuir", ("analytic", "slab"), accuracies),
            ("disc r5 x 2 mm, two-phase", Disc(5e-3, 2e-3), "langmuir",
             ("analytic", "axisymmetric"), accuracies),
            ("cam plate circle r5 x 2 mm, two-phase", plate, "langmuir", ("plane",), accuracies),
            ("sheet 2 mm, D exp(2c/Mm)", Sheet(2e-3), "concentration_dependent", ("slab",),
             accuracies)] + ([] if quick else [  # the 3-D row: full bench only
            ("plate 4x3x2 mm, D exp(2c/Mm)", block, "concentration_dependent", ("solid",),
             (5e-2, 3e-2)),
            ("plate 4x3x2 mm, D exp(2c/Mm), corrected", block, "concentration_dependent",
             ("auto",), (3e-2, 1e-2))])


def sorption_row_count(quick: bool) -> int:
    return sum(len(models) * len(accuracies) for *_, models, accuracies in sorption_cases(quick))


def _law(kind: str, d_ref: float, thickness: float):
    from .diffusion.problem.sorption import ConcentrationDependent, Langmuir, Rate

    if kind == "langmuir":
        rate = EXCHANGE * np.pi ** 2 * d_ref / thickness ** 2
        return Langmuir(Rate(rate), Rate(rate))
    return ConcentrationDependent(1.0, exponent=EXPONENT)


def _method_of_lines(times, d_ref: float, thickness: float, nodes: int = 800) -> np.ndarray:
    """Mean uptake of dc/dt = d/dz (D0 exp(k c) dc/dz), c = 1 on both faces, c0 = 0."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import diags

    dz = 1.0 / nodes

    def rhs(_, c):
        full = np.concatenate([[1.0], c, [1.0]])
        return np.diff(np.exp(EXPONENT * 0.5 * (full[1:] + full[:-1])) * np.diff(full) / dz) / dz

    scale = d_ref / thickness ** 2
    pattern = diags([1.0, 1.0, 1.0], [-1, 0, 1], shape=(nodes - 1, nodes - 1))
    solution = solve_ivp(rhs, (0.0, times[-1] * scale), np.zeros(nodes - 1), t_eval=times * scale,
                         method="BDF", rtol=1e-10, atol=1e-12, jac_sparsity=pattern)
    full = np.vstack([np.ones(times.size), solution.y, np.ones(times.size)])
    return np.where(times > 0, np.trapezoid(full, dx=dz, axis=0), 0.0)  # t = 0: dry


def reference(name, geometry, kind, times, diffusivity, exposure, d_ref):
    """(values, label) of the reference uptake curve of a case."""
    from .diffusion import CamPlate, Disc, Sheet, solve
    from .diffusion.exact.two_phase import two_phase_sheet_uptake

    law = _law(kind, d_ref, geometry.thickness)
    if kind != "langmuir" and not isinstance(geometry, Sheet):
        return solve(geometry, diffusivity, exposure, times, accuracy=PLANFORM_REFERENCE,
                     sorption=law).mean, f"fine run ({PLANFORM_REFERENCE:g})"
    if kind != "langmuir":
        return _method_of_lines(times, d_ref, geometry.thickness), "method of lines"
    if isinstance(geometry, Sheet):
        rate = law.binding.pre_exponential
        return two_phase_sheet_uptake(times, d_ref, geometry.thickness, rate, rate).total, "exact"
    if isinstance(geometry, CamPlate):  # the disc its outline approximates
        geometry = Disc(float(np.max(np.hypot(geometry.profile_x, geometry.profile_y))), geometry.thickness)
    return solve(geometry, diffusivity, exposure, times, accuracy=1e-8,
                 sorption=law).mean, "exact modes"


def sorption_rows(quick, times_of, diffusivity, d_ref, timed, make_row, progress) -> list[dict]:
    """The rows: each case, model and accuracy timed (``timed``) and compared."""
    from .diffusion import Exposure, solve

    rows, references = [], {}
    for name, geometry, kind, models, accuracies in sorption_cases(quick):
        times = times_of(geometry)
        exposure = Exposure.piecewise([0.0, times[-1]], 300.0, [1.0], 0.0)
        law = _law(kind, d_ref, geometry.thickness)
        if (kind, geometry) not in references:  # the 3-D rows share their fine run
            references[kind, geometry] = reference(name, geometry, kind, times, diffusivity,
                                                   exposure, d_ref)
        values, label = references[kind, geometry]
        for model in models:
            for accuracy in accuracies:
                progress(f"{name}: {model} {accuracy:g}")
                result, wall = timed(lambda: solve(geometry, diffusivity, exposure, times,
                                                   accuracy=accuracy, model=model, sorption=law))
                rows.append(make_row(name, result.model, accuracy, result.cells, result.steps,
                                     wall, float(np.max(np.abs(result.mean - values))),
                                     result.error_estimate, label))
    return rows
