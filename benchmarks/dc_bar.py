"""Concentration-dependent D on a Bar: the direct 3-D FiPy cells on one octant (``solid``,
and ``auto`` above ``dispatch.BAR_CORRECTED_FROM``;
``diffusion/nonfickian/concentration_dependent.py``) and the corrected product of its
rectangular section (``auto`` from there down; ``diffusion/nonfickian/corrected_product.py``):
accuracy, honesty of the estimate and cost against independent references.

    python benchmarks/dc_bar.py reference   # tests/data/dc_bar_reference.json (method of lines)
    python benchmarks/dc_bar.py small [K ...] [--at A ...] [--only DIRECTION]
        # 6 x 4 x 2 mm bar: k = 0, 1, 2 at 1e-2, 3e-3, 1e-3, absorption and desorption
    python benchmarks/dc_bar.py corrected [K ...] [--at A ...] [--only DIRECTION]
        # the same through the corrected route (defect: sheet x rectangle, 3-D corrected)
    python benchmarks/dc_bar.py link [K ...]   # 60 x 8 x 4 mm link bar: k = 0 exact, k > 0 vs 3e-3
    python benchmarks/dc_bar.py sweeps      # inexact sweeps from the extrapolated state vs exact
    python benchmarks/dc_bar.py profile     # where the CPU goes (cProfile of k = 2 runs)
    python benchmarks/dc_bar.py cap [K DIRECTION ACCURACY]  # one system at the cell cap:
        # cells, assembly, LU fill, factorisation and solve CPU, peak memory (default: the
        # k = 1 drying small bar at 1e-3, capped at MAX_CELLS["solid"] octant cells)

References. k = 0: the exact block (Crank 1975 eq. 4.51, product of three sheets;
``solve(..., model="analytic")``). k > 0 (``reference``): an independent method of lines
on the same octant (this file, not fickcam's mesh or march): cell-centred finite volumes
for c_t = div(D0 grad Phi(c)), Phi = (Mm/k)(exp(k c/Mm) - 1) (the Kirchhoff transform,
Crank 1975 §9.2), on tensor grids graded from the exposed faces with the contact layer's
depth on a face, integrated by scipy's BDF (rtol 1e-9, analytic sparse Jacobian), on a
base grid and on the same grid with every cell halved; the pair is Richardson-extrapolated
(second order in space): at k = 0 the extrapolation is within 1.7e-5 (mean) and 7.6e-5
(contact layer) of the exact block, the fine grid alone 2.3e-3 and 3.0e-3 (stored
``own_error``: |fine - coarse| / 3, the fine grid's error, a loose bound of the
extrapolation's).
Error: largest over the outputs of |model - reference| / Mm (the swing), for the mean and
the contact layer (0.5 mm deep). CPU time: time.process_time with one BLAS thread (set
OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1); no single run is allowed past ``CPU_LIMIT``
(an accuracy whose predecessor took more than CPU_LIMIT / 4 is skipped and reported).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy import sparse
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "tests" / "data" / "dc_bar_reference.json"
H, D, MM, DEPTH = 2e-3, 5e-12, 2.0, 5e-4
TAU = [0.0, 0.01, 0.03, 0.1, 0.3]        # outputs, t D / h^2 (h: the bar's thickness)
SMALL = (6e-3, 4e-3, 2e-3)
LINK = (60e-3, 8e-3, 4e-3)
ACCURACIES = (1e-2, 3e-3, 1e-3)
LINK_ACCURACIES, LINK_REFERENCE = (1e-2,), 3e-3   # a k > 0 link at 1e-3: past CPU_LIMIT
EXPONENTS = (1.0, 2.0)
DIRECTIONS = ("absorption", "desorption")
BASE_FIRST, BASE_GROWTH = 5e-2, 0.3      # base grid: first width / h, growth per cell
CPU_LIMIT = 900.0
ROUTE = "solid"   # ``small``: the direct 3-D cells (octant); ``corrected``: ``defect``


def axis_faces(half: float, first: float, growth: float, depth: float) -> np.ndarray:
    """Faces (m) of one octant axis [0, half], exposed at 0: widths growing by 1 + growth
    from ``first``, rescaled to put a face at ``depth`` (the contact layer's edge) and
    at ``half``."""
    faces, width, position = [0.0], first, 0.0
    for end in (min(depth, half), half):
        piece = []
        while position + sum(piece) + width < end - 0.3 * width:
            piece.append(width)
            width *= 1.0 + growth
        piece.append(end - position - sum(piece))
        scale = (end - position) / sum(piece)
        faces.extend(position + np.cumsum(piece) * scale)
        position = end
        if end >= half:
            break
    return np.array(faces)


def halved(faces: np.ndarray) -> np.ndarray:
    """Every cell of an axis cut in two (nested refinement of a fixed mapping)."""
    middles = 0.5 * (faces[1:] + faces[:-1])
    return np.sort(np.concatenate([faces, middles]))


def kirchhoff(k: float):
    """(Phi, f = Phi'): the Kirchhoff potential of f = exp(k c/Mm) and f."""
    if k == 0:
        return (lambda c: c), (lambda c: np.ones_like(c))
    return (lambda c: MM / k * np.expm1(k * c / MM)), (lambda c: np.exp(k * c / MM))


def axis_operator(faces: np.ndarray):
    """(L, b): the 1-D two-point operator of one axis per unit D (flux (u_j - u_i) /
    centre distance, the exposed face at 0 a half cell from the first centre, the
    mirror plane insulated), divided by the widths; b the exposed face's coefficient."""
    widths, centres = np.diff(faces), 0.5 * (faces[1:] + faces[:-1])
    t = 1.0 / np.diff(centres)
    edge = np.zeros(widths.size)
    edge[0] = 1.0 / centres[0]
    diagonal = -np.concatenate([t, [0.0]]) - np.concatenate([[0.0], t]) - edge
    lap = sparse.diags([t, diagonal, t], [-1, 0, 1]).tocsr()
    return sparse.diags(1.0 / widths) @ lap, edge / widths


def method_of_lines(size, k: float, start: float, surface: float, times, d0=D,
                    refinements: int = 0, rtol: float = 1e-9):
    """Mean and contact-layer moisture (weight %) of a bar's octant at ``times`` by the
    method of lines (module docstring), ``refinements`` halvings of the base grid.
    Returns (mean, layer, cells, CPU s)."""
    started = time.process_time()
    axes = []
    for length in size:
        faces = axis_faces(0.5 * length, BASE_FIRST * size[2], BASE_GROWTH, DEPTH)
        for _ in range(refinements):
            faces = halved(faces)
        axes.append(faces)
    operators = [axis_operator(f) for f in axes]
    eye = [sparse.identity(f.size - 1, format="csr") for f in axes]
    a = d0 * (sparse.kron(sparse.kron(operators[0][0], eye[1]), eye[2])
              + sparse.kron(sparse.kron(eye[0], operators[1][0]), eye[2])
              + sparse.kron(sparse.kron(eye[0], eye[1]), operators[2][0])).tocsr()
    edges = [e for _, e in operators]
    b = d0 * (edges[0][:, None, None] + edges[1][None, :, None] + edges[2][None, None, :]).ravel()
    phi, f = kirchhoff(k)
    ug = float(phi(np.float64(surface)))
    solution = solve_ivp(lambda t, c: a @ phi(c) + b * ug, (0.0, times[-1]),
                         np.full(a.shape[0], float(start)), method="BDF", t_eval=times,
                         jac=lambda t, c: a @ sparse.diags(f(c)), rtol=rtol, atol=rtol * MM,
                         first_step=1e-10 * times[-1])
    if not solution.success:
        raise RuntimeError(solution.message)
    widths = [np.diff(x) for x in axes]
    volumes = np.einsum("i,j,k->ijk", *widths).ravel()
    inner = np.einsum("i,j,k->ijk", *[(x[:-1] >= DEPTH - 1e-15).astype(float) for x in axes])
    layer = volumes * (1.0 - inner.ravel())
    values = solution.y
    return (volumes @ values / volumes.sum(), layer @ values / layer.sum(), volumes.size,
            time.process_time() - started)


def case(size, direction: str, k: float):
    from fickcam.diffusion import Bar, Diffusivity, Exposure
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    times = np.array(TAU) * size[2] ** 2 / D
    start, surface = (0.0, MM) if direction == "absorption" else (MM, 0.0)
    exposure = Exposure.piecewise([0.0, times[-1]], [330.0], [surface], initial_moisture=start)
    return (Bar(*size), Diffusivity((D, D, D), 0.0), exposure, times,
            ConcentrationDependent(MM, exponent=k), start, surface)


def reference() -> None:
    """The method of lines on the small bar, k = 0 (checked against the exact block),
    1 and 2, absorption and desorption: base grid and every cell halved, extrapolated."""
    from fickcam.diffusion import solve

    out = {"tau": TAU, "size": SMALL, "mm": MM, "layer_depth": DEPTH,
           "made_by": "benchmarks/dc_bar.py reference"}
    for k in (0.0,) + EXPONENTS:
        for direction in DIRECTIONS:
            bar, d, exposure, times, _, start, surface = case(SMALL, direction, k)
            runs = [method_of_lines(SMALL, k, start, surface, times, refinements=r)
                    for r in (0, 1)]
            (mean0, layer0, cells0, cpu0), (mean1, layer1, cells1, cpu1) = runs
            mean, layer = (4 * mean1 - mean0) / 3, (4 * layer1 - layer0) / 3
            own = float(max(np.max(np.abs(mean1 - mean0)), np.max(np.abs(layer1 - layer0)))
                        / 3 / MM)
            line = (f"k={k:g} {direction}: cells {cells0}/{cells1}, CPU {cpu0:.1f}/{cpu1:.1f} s, "
                    f"own error {own:.1e}")
            if k == 0:
                exact = solve(bar, d, exposure, times, model="analytic")
                line += (f"; vs exact: mean {np.max(np.abs(mean - exact.mean)) / MM:.1e} "
                         f"(fine alone {np.max(np.abs(mean1 - exact.mean)) / MM:.1e}), layer "
                         f"{np.max(np.abs(layer - exact.surface)) / MM:.1e} (fine alone "
                         f"{np.max(np.abs(layer1 - exact.surface)) / MM:.1e})")
            print(line, flush=True)
            out[f"k{k:g}_{direction}"] = {"mean": mean.tolist(), "layer": layer.tolist(),
                                          "own_error": own, "cells": [cells0, cells1]}
    REFERENCE.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {REFERENCE}")


def measure(size, k: float, direction: str, accuracy: float, reference_mean, reference_layer):
    """One run of ``ROUTE`` (``solid`` at k = 0, which ``auto`` would hand to the exact
    block): (estimate, mean error, layer error, cells, steps, CPU s)."""
    from fickcam.diffusion import DiffusionProblem, solve
    from fickcam.diffusion.nonfickian.corrected_product import solve_corrected

    bar, d, exposure, times, law, _, _ = case(size, direction, k)
    started = time.process_time()
    if ROUTE == "corrected":
        result = solve_corrected(DiffusionProblem(bar, d, exposure, times, accuracy, sorption=law))
    else:
        result = solve(bar, d, exposure, times, accuracy=accuracy, sorption=law,
                       model="solid" if k == 0 else ROUTE)
    cpu = time.process_time() - started
    mean_error = np.max(np.abs(result.mean - reference_mean)) / MM
    layer_error = np.max(np.abs(result.surface - reference_layer)) / MM
    return result, result.error_estimate, mean_error, layer_error, result.cells, cpu


def options(accuracies):
    """(exponents, accuracies, directions) from ``K ... [--at A ...] [--only DIRECTION]``."""
    words, chosen = sys.argv[2:], {"--at": [], "--only": []}
    exponents, into = [], None
    for word in words:
        if word in chosen:
            into = chosen[word]
        elif into is None:
            exponents.append(float(word))
        else:
            into.append(word)
    return (tuple(exponents) or (0.0,) + EXPONENTS,
            tuple(float(a) for a in chosen["--at"]) or accuracies,
            tuple(chosen["--only"]) or DIRECTIONS)


def table(size, references, label: str, accuracies=ACCURACIES) -> None:
    """Rows |k|direction|accuracy|estimate|mean error|layer error|cells|steps|CPU s|."""
    print(f"| bar | k | direction | accuracy | estimate | mean error | layer error | "
          f"reference | cells (octant) | steps | CPU s |\n|{'---|' * 11}", flush=True)
    exponents, accuracies, directions = options(accuracies)
    for k in exponents:
        for direction in directions:
            previous = 0.0
            for accuracy in accuracies:
                if previous > CPU_LIMIT / 4:
                    print(f"| {label} | {k:g} | {direction} | {accuracy:g} | skipped: the "
                          f"previous accuracy took {previous:.0f} CPU s |", flush=True)
                    continue
                name, mean, layer = references(k, direction, accuracy)
                if name is None:
                    continue
                result, estimate, error, layer_error, cells, cpu = measure(
                    size, k, direction, accuracy, mean, layer)
                flag = "" if estimate >= error else " (estimate below the error)"
                print(f"| {label} | {k:g} | {direction} | {accuracy:g} | {estimate:.1e} | "
                      f"{error:.1e}{flag} | {layer_error:.1e} | {name} | {cells} | "
                      f"{result.steps} | {cpu:.1f} |", flush=True)
                previous = cpu


def exact_reference(size, direction):
    from fickcam.diffusion import solve

    bar, d, exposure, times, *_ = case(size, direction, 0.0)
    exact = solve(bar, d, exposure, times, model="analytic")
    return exact.mean, exact.surface


def small() -> None:
    stored = json.loads(REFERENCE.read_text())

    def references(k, direction, accuracy):
        if k == 0:
            return ("exact", *exact_reference(SMALL, direction))
        entry = stored[f"k{k:g}_{direction}"]
        return ("MOL", np.array(entry["mean"]),
                np.array(entry["layer"]))
    table(SMALL, references, "6x4x2")


def corrected() -> None:
    """``small`` through the corrected route (``defect.solve_corrected``: the bar as the
    prism of its rectangular section, thickness its smallest side), k > 0 only
    (``corrected [K ...] [--at A ...] [--only DIRECTION]``)."""
    global ROUTE
    ROUTE = "corrected"
    if len(sys.argv) < 3 or sys.argv[2].startswith("--"):
        sys.argv[2:2] = [str(k) for k in EXPONENTS]
    small()


def link() -> None:
    """k = 0 against the exact block; k > 0 (``link K ...``) against this route at
    ``LINK_REFERENCE`` (self-convergence: the difference from it is a lower bound of the
    error of the coarser runs, not the error)."""
    finest: dict = {}

    def references(k, direction, accuracy):
        if k == 0:
            return ("exact", *exact_reference(LINK, direction))
        if (k, direction) not in finest:
            result, *_, cpu = measure(LINK, k, direction, LINK_REFERENCE, 0.0, 0.0)
            finest[k, direction] = result
            print(f"| 60x8x4 | {k:g} | {direction} | {LINK_REFERENCE:g} | "
                  f"{result.error_estimate:.1e} | (reference) | (reference) | - | "
                  f"{result.cells} | {result.steps} | {cpu:.1f} |", flush=True)
        if accuracy <= LINK_REFERENCE:
            return None, None, None
        result = finest[k, direction]
        return f"auto {LINK_REFERENCE:g}", result.mean, result.surface
    table(LINK, references, "60x8x4", LINK_ACCURACIES)


def sweeps() -> None:
    """The k = 2 small bar absorbing at 1e-2 with the sweeps as they are (inexact, from the
    extrapolated state) and as they were (each system solved to LINEAR_TOLERANCE, from
    the old state: ``FORCING`` 0 and the extrapolation replaced by the latest state)."""
    from fickcam.diffusion.nonfickian import concentration_dependent
    from fickcam.diffusion import solve

    bar, d, exposure, times, law, _, _ = case(SMALL, "absorption", 2.0)
    means = []
    for name in ("inexact, extrapolated", "exact, from the old state"):
        if means:
            concentration_dependent.FORCING = 0.0
            concentration_dependent.extrapolated = lambda before, latest, dt_before, dt, g: latest
        started = time.process_time()
        result = solve(bar, d, exposure, times, accuracy=1e-2, sorption=law, model="solid")
        means.append(result.mean)
        print(f"{name}: {result.cells} cells, {time.process_time() - started:.1f} CPU s",
              flush=True)
    print(f"means differ by {np.max(np.abs(means[0] - means[1])) / MM:.1e} of Mm")


def profile() -> None:
    """Where the CPU of one k = 2 run goes (small bar, absorption and desorption)."""
    import cProfile
    import pstats

    from fickcam.diffusion import solve

    accuracy = float(sys.argv[2]) if len(sys.argv) > 2 else 1e-2
    for direction in DIRECTIONS:
        bar, d, exposure, times, law, _, _ = case(SMALL, direction, 2.0)
        profiler = cProfile.Profile()
        profiler.enable()
        result = solve(bar, d, exposure, times, accuracy=accuracy, sorption=law,
                       model="solid")
        profiler.disable()
        print(f"{direction} at {accuracy:g}: {result.cells} cells, {result.steps} steps")
        pstats.Stats(profiler).sort_stats("tottime").print_stats(12)


def cap() -> None:
    """What one linear system at the cap costs: the plan of the small bar (``cap K
    DIRECTION ACCURACY``), its octant assembled (FiPy), one system of a step factorised as
    ``concentration_dependent.Lagged`` does (SuperLU, symmetric mode) and solved on those factors; CPU
    (time.process_time) and peak resident memory (ru_maxrss) after each stage."""
    import resource

    from fickcam.diffusion.nonfickian import concentration_dependent
    from fickcam.diffusion import plan
    from fickcam.diffusion.forcing.clock import scales as scales_of
    from fickcam.diffusion.models.finite_volume import step_plan
    from fickcam.diffusion.operators.symmetry_cuts import mirrored
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    k = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
    direction = sys.argv[3] if len(sys.argv) > 3 else "desorption"
    accuracy = float(sys.argv[4]) if len(sys.argv) > 4 else 1e-3
    bar, d, exposure, times, law, start, _ = case(SMALL, direction, k)

    def report(stage, began):
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"{stage}: {time.process_time() - began:.2f} CPU s, peak RSS {peak:.0f} MB",
              flush=True)
        return time.process_time()

    began = report("start", time.process_time())
    chosen = plan(bar, d, exposure, times, accuracy=accuracy, sorption=law,
                  model="solid" if k == 0 else ROUTE)  # as ``measure``
    print(f"plan: {chosen.cells} cells {chosen.cells_per_axis} (octant), estimate "
          f"{chosen.error_estimate:.2e}, {chosen.steps} steps; {chosen.reason}", flush=True)
    began = report("plan", began)
    scaled = concentration_dependent.fastest(d, law, exposure, times)
    weights = mirrored(bar, tuple(float(v) for v in scaled.pre_exponential),
                       chosen.cells_per_axis, chosen.finest, chosen.growth, DEPTH)
    faces = concentration_dependent.Faces.of(weights)
    began = report(f"octant assembled ({weights.cells} cells)", began)
    steps = step_plan(exposure, times, scales_of(bar, scaled, exposure),
                      chosen.steps_per_doubling)
    dt = float(np.diff(steps.nodes)[-1])
    c = np.full(weights.cells, float(start))
    top = law.largest_factor(MM)
    system, f = faces.operator(c, 0.0 if direction == "desorption" else MM, law, top,
                               faces.volumes / dt)
    solver = concentration_dependent.Lagged()
    rhs = faces.volumes / dt * c + f
    solver.solve(system, rhs, c)
    fill = solver.lu.L.nnz + solver.lu.U.nnz
    began = report(f"factorised (L + U: {fill} non-zeros, {fill / weights.cells:.0f} a cell, "
                   f"{fill * 12 / 2 ** 20:.0f} MB of values and indices)", began)
    repeats = 10
    for _ in range(repeats):
        solver.lu.solve(rhs)
    report(f"{repeats} triangular solves on the factors", began)


if __name__ == "__main__":
    commands = {"reference": reference, "small": small, "corrected": corrected, "link": link,
                "sweeps": sweeps,
                "profile": profile, "cap": cap}
    if len(sys.argv) < 2 or sys.argv[1] not in commands:
        sys.exit(f"usage: {sys.argv[0]} {' | '.join(commands)}")
    commands[sys.argv[1]]()
