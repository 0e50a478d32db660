"""Cost of real climate records against a constant climate (issue 20).

    python benchmarks/climate_records.py [--months 1 3 12] [--plane-months 1]

Ages each scene through the first months of Greensboro's TMY3 year (hourly rows) and
through the same span at the record's mean climate, and prints the ratio and the growth
exponent of the cost with the number of rows (``fickcam.bench_records``). The exact-path
nylon eccentric cam runs by default; ``--plane-months`` adds the demo cam and the
four-bar (plane model: still Duhamel superposition per row, so expect minutes per month).
"""
from __future__ import annotations

import argparse

from fickcam.bench_records import CASES, format_record_table, run_record_bench

PLANE_CASES = {"demo cam (plane)": "configs/singh2017_cam.yaml",
               "four-bar (plane)": "configs/fourbar_r914_humid.yaml"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--months", type=int, nargs="+", default=[1, 3, 12])
    parser.add_argument("--plane-months", type=int, nargs="*", default=[])
    args = parser.parse_args()
    rows = run_record_bench(tuple(args.months), CASES)
    if args.plane_months:
        rows += run_record_bench(tuple(args.plane_months), PLANE_CASES)
    print(format_record_table(rows))


if __name__ == "__main__":
    main()
