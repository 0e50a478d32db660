"""``DiffusionResult.extend`` of the D(c) marches (``diffusion/dense_output.py``): new times read
between the stored solve's steps against a solve at the stored and new times together.

    python benchmarks/dc_extend.py sheet                 # 1-D D(c) sheet, wetted then dried
    python benchmarks/dc_extend.py cam K A               # the demo cam (corrected path)
    python benchmarks/dc_extend.py limits K A [before|extend [DEV]]  # fickcam run of the scene

``sheet``: the 2 mm sheet of tests/test_sorption_extend.py (D = 5e-12 m^2/s exp(2 c/Mm),
wetted to Mm, stepped down to Mm/2 at 0.3 h^2/D), accuracy 1e-2 and 1e-3: 20 new times read
by ``extend`` against ``solve_nonlinear`` at the stored and new times on the same plan: the
interpolation estimate and the distance (largest over the new times of the mean's and the
layer's / LAYER_TOLERANCE, of the swing). ``cam K A``: configs/singh2017_cam.yaml's cam with
``sorption: {model: concentration_dependent, exponent: K}`` (the demo cam of
dc_defect_correction.py) at accuracy A: 20 new times between 1 d and 60 d read by
``extend`` against ``solve`` at the stored and new times (what the limit search did
before): distance, the interpolation estimate, CPU s of each. ``limits K A``: the whole
scene (cam and roller with that sorption, the drawing's limits) by ``fickcam.run`` at
accuracy A (``DEV``: the follower displacement's deviation limit, mm, instead of 0.25: a
crossing after the first day): CPU s and time_out_of_spec; ``before``: every extend solves again
(``dense_output.INTERPOLATION_SHARE`` = -1), as the limit search did before ``dense``.
CPU time: time.process_time, one BLAS thread (set OPENBLAS_NUM_THREADS=1).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
NEW_DAYS = np.linspace(1.5, 59.0, 20)


def distance(mean, layer, other_mean, other_layer, swing) -> np.ndarray:
    from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE

    return np.maximum(np.abs(mean - other_mean),
                      np.abs(layer - other_layer) / LAYER_TOLERANCE) / swing


def sheet() -> None:
    from fickcam.diffusion import DiffusionProblem, Diffusivity, Exposure, Sheet, plan, solve
    from fickcam.diffusion.nonfickian.concentration_dependent import solve_nonlinear
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    h, d, mm = 2e-3, 5e-12, 2.0
    t = h ** 2 / d
    times = np.array([0.0, 0.01, 0.03, 0.1, 0.2, 0.3, 0.31, 0.6, 1.0]) * t
    exposure = Exposure.piecewise([0.0, 0.3 * t, times[-1]], [330.0, 330.0], [mm, 0.5 * mm],
                                  initial_moisture=0.0)
    law, diffusivity = ConcentrationDependent(mm, exponent=2.0), Diffusivity((d,) * 3, 0.0)
    new = np.concatenate([np.linspace(0.012, 0.29, 10), np.linspace(0.32, 0.99, 10)]) * t
    both = np.union1d(times, new)
    print("| accuracy | steps/doubling | stored estimate | interpolation estimate | "
          "distance to the same plan's solve |")
    for accuracy in (1e-2, 1e-3):
        stored = solve(Sheet(h), diffusivity, exposure, times, accuracy=accuracy, sorption=law)
        mean, layer, estimate = stored.extend.interpolated(new)
        chosen = plan(Sheet(h), diffusivity, exposure, times, accuracy, sorption=law)
        same = solve_nonlinear(DiffusionProblem(Sheet(h), diffusivity, exposure, both,
                                                sorption=law), chosen)
        rows = np.searchsorted(both, new)
        gap = distance(mean, layer, same.mean[rows], same.surface[rows], mm)
        print(f"| {accuracy:g} | {chosen.steps_per_doubling} | {stored.error_estimate:.1e} | "
              f"{np.max(estimate):.1e} | {np.max(gap):.1e} |", flush=True)


def demo_scene(k: float, accuracy: float, deviation: str = "") -> dict:
    """The demo cam scene with D(c) ``sorption`` (exponent k) on both parts; ``deviation``
    (mm): the follower displacement's limit instead of the drawing's 0.25 mm."""
    raw = yaml.safe_load((ROOT / "configs" / "singh2017_cam.yaml").read_text())
    raw["materials"]["cfrp"]["sorption"] = {"model": "concentration_dependent", "exponent": k}
    raw["diffusion"]["accuracy"] = accuracy
    raw["outputs"].pop("file", None)
    if deviation:
        raw["limits"]["follower_displacement"] = {"deviation": f"{deviation} mm"}
    return raw


def cam(k: str, accuracy: str) -> None:
    sys.path.insert(0, str(ROOT / "benchmarks"))   # a script beside this one, not the package
    from dc_defect_correction import demo_cam
    from fickcam.diffusion import solve

    geometry, d, exposure, times, law = demo_cam(float(k))
    a = float(accuracy)
    swing = float(exposure.surface_moisture(times[-1:])[0] - exposure.initial_moisture)
    start = time.process_time()
    stored = solve(geometry, d, exposure, times, accuracy=a, sorption=law)
    solved = time.process_time() - start
    new = NEW_DAYS * 86400.0
    start = time.process_time()
    extended = stored.extend(new)
    extending = time.process_time() - start
    start = time.process_time()
    again = solve(geometry, d, exposure, extended.times, accuracy=a, sorption=law)
    resolving = time.process_time() - start
    rows = np.isin(extended.times, new)
    gap = distance(extended.mean[rows], extended.surface[rows], again.mean[rows],
                   again.surface[rows], swing)
    read = "read between" in extended.reason
    print(f"| {float(k):g} | {a:g} | {stored.error_estimate:.1e} | "
          f"{extended.error_estimate - stored.error_estimate:.1e} | {np.max(gap):.1e} | "
          f"{again.error_estimate:.1e} | {extending:.2f} | {resolving:.1f} | {solved:.1f} | "
          f"{'read' if read else 'SOLVED AGAIN'} |", flush=True)


def limits(k: str, accuracy: str, before: str = "", deviation: str = "") -> None:
    import fickcam
    from fickcam.diffusion.stepping import dense_output

    if before == "before":
        dense_output.INTERPOLATION_SHARE = -1.0
    start = time.process_time()
    ds = fickcam.run(fickcam.load_scene(demo_scene(float(k), float(accuracy), deviation)))
    cpu = time.process_time() - start
    out = ds["time_out_of_spec"]
    ratio = ds["limit_ratio"].values
    print(f"| {float(k):g} | {float(accuracy):g} | {deviation or 0.25} | {before or 'extend'} | "
          f"{cpu:.1f} | {', '.join(f'{v:.6g}' for v in out.values)} "
          f"{out.attrs.get('units', '')} |", flush=True)
    print("limit_ratio (time x limit):", np.array2string(ratio, precision=4), flush=True)


if __name__ == "__main__":
    {"sheet": sheet, "cam": cam, "limits": limits}[sys.argv[1]](*sys.argv[2:])
