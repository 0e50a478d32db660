"""The two-phase demo cam under a constant climate and a daily chamber record (issue 13).

    python benchmarks/two_phase_cam_records.py [--reference] [--log]

- ``--log`` writes ``configs/chamber_daily_113C.csv``: a SYNTHETIC daily chamber log,
  181 rows (0 to 180 d), temperature uniform in 113 +- 4 degC and relative humidity in
  80 +- 12 %, drawn once (numpy default_rng seed 13); rows are joined linearly.
- ``--reference`` computes the fine references of the cam's diffusion (the plane
  two-phase path on fixed planform meshes 8 and 16 times finer in w0, 4 and 8 times in
  growth than the scene's first mesh, march at 1e-5, Richardson-extrapolated: the cells
  go as 1/(w0 g), second order) and writes ``tests/data/two_phase_cam_reference.json``
  (mean, bound, contact layer in weight %, with the two fine meshes' difference as the
  reference's own uncertainty bound).
- Default: the table of the README (accuracy asked, the run's estimate, the true error
  against the reference: the largest of mean, bound and layer / 4 relative to the swing,
  planform cells, CPU seconds of the whole scene run in this process), for
  ``configs/singh2017_cam_two_phase.yaml`` and ``configs/singh2017_cam_two_phase_daily.yaml``,
  and a circular plate (r 50 mm, 12 mm, the cam's transverse D) against the exact disc
  over the same record.

The work is in ``fickcam.bench_two_phase``.
"""
from __future__ import annotations

import argparse

from fickcam.bench_two_phase import (cam_rows, circle_rows, format_rows, write_log,
                                     write_reference)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--log", action="store_true", help="write the daily chamber log")
    parser.add_argument("--reference", action="store_true", help="write the fine references")
    args = parser.parse_args()
    if args.log:
        write_log()
    if args.reference:
        write_reference()
    if not (args.log or args.reference):
        print(format_rows(cam_rows() + circle_rows()))


if __name__ == "__main__":
    main()
