"""Cost of real climate records against a constant climate (issue 20).

    python benchmarks/climate_records.py [--months 1 3 12]

Ages the demo cam (plane model), the nylon eccentric cam (exact disc) and the four-bar
(plane model) through the first months of Greensboro's TMY3 year (hourly rows) and
through the same span at the record's mean climate, and prints the CPU seconds, their
ratio and the growth exponent of the cost with the number of rows; then the accuracy of
a year: a solid disc through all 8760 rows against its modes advanced exactly through the
record (``fickcam.bench_records``; the same as ``fickcam bench --records``).
"""
from __future__ import annotations

import argparse

from fickcam.bench_records import (format_record_table, format_year_accuracy, run_record_bench,
                                   year_accuracy)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--months", type=int, nargs="+", default=[1, 3, 12])
    args = parser.parse_args()
    print(format_record_table(run_record_bench(tuple(args.months))))
    print(format_year_accuracy(year_accuracy()))


if __name__ == "__main__":
    main()
