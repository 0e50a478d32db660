"""Large meshes: a part's FiPy diffusion solve with PETSc under MPI (docs/guide/sweeps-montecarlo.md).

Runs the moisture uptake of Singh & Sanyal 2016's crank (a 100 x 30 x 10 mm bar, all faces
wet, non-dimensional time D t / h^2) on a FiPy Grid3D twice: serially, and with
``FIPY_SOLVERS=petsc`` under ``mpirun -np 2`` (FiPy partitions the grid over the
ranks). The two mean-uptake curves must agree. Skipped, with the reason, where
petsc4py (or mpirun) is not available: PyPI has only source distributions of
PETSc/petsc4py, which build PETSc itself. Point ``FICKCAM_PETSC_PYTHON`` at a
Python that has fipy and petsc4py (conda-forge, or Debian's python3-petsc4py)
to run it there.
"""
import json
import os
import shutil
import subprocess
import sys

import pytest

PYTHON = os.environ.get("FICKCAM_PETSC_PYTHON", sys.executable)

SCRIPT = """
import json, sys
import fipy
from fipy import CellVariable, DiffusionTerm, Grid3D, TransientTerm
from fipy.tools import numerix

# Singh & Sanyal 2016 crank: 100 x 30 x 10 mm, lengths scaled by the thickness h = 10 mm
nx, ny, nz = 40, 12, 8
mesh = Grid3D(nx=nx, ny=ny, nz=nz, dx=10.0 / nx, dy=3.0 / ny, dz=1.0 / nz)
c = CellVariable(mesh=mesh, value=0.0)
c.constrain(1.0, mesh.exteriorFaces)
equation = TransientTerm() == DiffusionTerm(coeff=1.0)
solver = fipy.solvers.DefaultSolver(tolerance=1e-12, iterations=5000)
means = []
for step in range(12):          # backward Euler, t* = D t / h^2 from 0.005 to 0.06
    equation.solve(var=c, dt=0.005, solver=solver)
    means.append(float(numerix.array(c.globalValue).mean()))   # uniform cells
if mesh.communicator.procID == 0:
    print(json.dumps({"solver": type(solver).__module__, "ranks": mesh.communicator.Nproc,
                      "cells_here": int(mesh.numberOfCells), "means": means}))
"""


def _has(python: str, modules: str) -> bool:
    done = subprocess.run([python, "-c", f"import {modules}"], capture_output=True)
    return done.returncode == 0


def _run(command, tmp_path, solvers: str) -> dict:
    script = tmp_path / "uptake.py"
    script.write_text(SCRIPT)
    env = dict(os.environ, FIPY_SOLVERS=solvers, OMP_NUM_THREADS="1",
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    done = subprocess.run(command + [str(script)], capture_output=True, text=True, env=env,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.skipif(not _has(PYTHON, "petsc4py, fipy"),
                    reason="petsc4py is not importable: PyPI ships PETSc/petsc4py only as source "
                           "that builds PETSc itself; install them from conda-forge or Debian "
                           "(python3-petsc4py) and set FICKCAM_PETSC_PYTHON (docs/guide/sweeps-montecarlo.md)")
@pytest.mark.skipif(shutil.which("mpirun") is None, reason="mpirun (an MPI launcher) is not installed")
def test_fipy_solve_with_petsc_under_mpi_matches_the_serial_solve(tmp_path):
    serial = _run([PYTHON], tmp_path, "scipy")
    parallel = _run(["mpirun", "-np", "2", "--oversubscribe", PYTHON], tmp_path, "petsc")
    assert parallel["ranks"] == 2 and "petsc" in parallel["solver"]
    assert parallel["cells_here"] < 40 * 12 * 8, "the mesh is partitioned over the ranks"
    assert all(0 < m < 1 for m in serial["means"])
    assert serial["means"] == pytest.approx(parallel["means"], rel=1e-6)
