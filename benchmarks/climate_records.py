"""Cost of real climate records against a constant climate.

    python benchmarks/climate_records.py [--months 1 3 12]

Ages the demo cam (plane model), the nylon eccentric cam (exact disc) and the four-bar
(plane model) through the first months of Greensboro's TMY3 year (hourly rows) and
through the same span at the record's mean climate, and prints the CPU seconds, their
ratio and the growth exponent of the cost with the number of rows; then the accuracy of
a year: a solid disc through all 8760 rows against its modes advanced exactly through the
record (the same as ``fickcam bench --records``).

Method.

Each case is a shipped scene aged through the first 1, 3 and 12 months (730 h each) of
Greensboro's TMY3 year (``pvlib:723170TYA.CSV``, hourly rows; 12 months = its 8760 rows)
and, for the ratio, through the same span under a constant climate (the record's mean
temperature and humidity), with the same ageing times. Whole scene runs, in-process
(``simulate.run``), after a warm-up of each kind; each cost is the median of three runs
taken alternately with its pair. Costs are CPU seconds of this process
(``time.process_time``: other work on a shared machine does not move them). The growth
exponent is the slope of log(cost) against log(rows).
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

MONTH_HOURS = 730
ROOT = Path(__file__).resolve().parents[1]
CASES = {"demo cam (plane)": "configs/singh2017_cam.yaml",
         "nylon eccentric cam (exact disc)": "configs/eccentric_cam.yaml",
         "four-bar (plane)": "configs/fourbar_r914_humid.yaml"}


def record_scene(config: Path, environment: dict, months: int) -> dict:
    """The config with ``environment`` replaced, aged weekly-ish (10 ageing times)."""
    scene = yaml.safe_load(config.read_text())
    scene["environment"] = {"reference_temperature": scene["environment"]
                            .get("reference_temperature", "23 degC"), **environment}
    span = _rows(months) - 1
    scene["outputs"] = {**scene.get("outputs", {}), "file": None,
                        "ageing_times": [f"{h:g} h" for h in np.linspace(0, span, 10)]}
    return scene


def record_csv(folder: Path, months: int) -> tuple[Path, float, float]:
    """The first ``months`` of Greensboro as a CSV history; also its mean T (degC) and RH."""
    from fickcam.climate.records import read_record, resolve_record_path

    record = read_record(resolve_record_path("pvlib:723170TYA.CSV", ROOT))
    rows = _rows(months)
    hours = record.time[:rows] / 3600.0
    celsius = record.temperature[:rows] - 273.15
    humidity = record.relative_humidity[:rows]
    path = folder / f"greensboro_{months}m.csv"
    lines = [f"{h:g},{t:.2f},{rh:.2f}" for h, t, rh in zip(hours, celsius, humidity)]
    path.write_text("time [h],temperature [degC],relative_humidity [%]\n" + "\n".join(lines))
    return path, float(np.mean(celsius)), float(np.mean(humidity))


def _rows(months: int) -> int:
    return min(months * MONTH_HOURS + 1, 8760)


def _cost(scene: dict) -> float:
    """CPU time (s) of one in-process run of ``scene``."""
    from fickcam.simulation.simulate import run

    start = time.process_time()
    run(scene)
    return time.process_time() - start


def _median_costs(constant: dict, record: dict, repeats: int = 3) -> tuple[float, float]:
    """Median CPU time of ``repeats`` runs of each scene, taken alternately: a run of
    the demo cam costs about 0.1 s, where one timing scatters by some 10-20 %."""
    pairs = [(_cost(constant), _cost(record)) for _ in range(repeats)]
    return tuple(float(np.median(column)) for column in zip(*pairs))


def run_record_bench(months=(1, 3, 12), cases=None) -> list[dict]:
    """Rows (case, months, rows, record s, constant s, ratio) and, per case, the exponent."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, config in (cases or CASES).items():
            config = ROOT / config
            timings = []
            for count in months:
                path, celsius, humidity = record_csv(Path(folder), count)
                record = record_scene(config, {"history_file": str(path)}, count)
                constant = record_scene(config, {"history": [{
                    "duration": f"{count * MONTH_HOURS} h", "temperature": f"{celsius:.2f} degC",
                    "relative_humidity": f"{humidity:.2f} %"}]}, count)
                if not timings:
                    _cost(constant), _cost(record)  # warm-up: imports, caches
                held, cost = _median_costs(constant, record)
                timings.append((_rows(count), cost))
                rows.append({"case": name, "months": count, "rows": _rows(count),
                             "record": cost, "constant": held, "ratio": cost / held})
            counts, walls = np.log([t[0] for t in timings]), np.log([t[1] for t in timings])
            exponent = float(np.polyfit(counts, walls, 1)[0]) if len(timings) > 1 else np.nan
            for row in rows[-len(months):]:
                row["exponent"] = exponent
    return rows


# ------------------------------------------------------- accuracy of a year


def isotherm(temperature, humidity):
    """Ms = 8.5 (RH/100)^1.6 weight %: the shape of a polyamide's sorption isotherm (the
    accuracy benchmark's and tests' surface value; its swing sets the scale)."""
    return 8.5 * (np.asarray(humidity, float) / 100.0) ** 1.6


def modal_disc_mean(disc, diffusivity, environment, times, modes=(60, 30), substeps=32):
    """Independent reference for a solid disc whose surface follows ``isotherm``: the mean
    as Crank's finite-cylinder modes (eqs. 4.18 and 5.23, ``modes`` radial x axial), each
    advanced exactly through Ms taken linear in tau on ``substeps`` sub-steps per row
    (y' = lambda (Ms - y), exponential update); tau by the trapezoid rule on them. The
    modes left out are fast: each sits at Ms - (dMs/dtau) / lambda (its lag behind a ramp),
    so they add (1 - sum a) Ms - (sum of a / lambda over them) dMs/dtau, the latter sum being
    that over 2000 x 2000 modes less the kept ones. The part starts at Ms(0): no step."""
    from scipy.integrate import cumulative_trapezoid

    rows = environment.change_times
    t = np.unique(np.concatenate([np.linspace(a, b, substeps + 1)
                                  for a, b in zip(rows[:-1], rows[1:])] + [times]))
    tau = cumulative_trapezoid(diffusivity.arrhenius_factor(environment.temperature(t)), t,
                               initial=0.0)
    ms = isotherm(environment.temperature(t), environment.relative_humidity(t))
    rates, amplitudes = _cylinder_modes(disc, diffusivity.pre_exponential[0], modes)
    every, weights = _cylinder_modes(disc, diffusivity.pre_exponential[0], (2000, 2000))
    lag = float(weights @ (1 / every) - amplitudes @ (1 / rates))
    y, mean = np.full(rates.size, ms[0]), [ms[0]]
    for i in range(t.size - 1):
        d = tau[i + 1] - tau[i]
        slope = (ms[i + 1] - ms[i]) / d
        y = ms[i + 1] + (y - ms[i]) * np.exp(-rates * d) - slope * -np.expm1(-rates * d) / rates
        mean.append(amplitudes @ y + (1 - amplitudes.sum()) * ms[i + 1] - lag * slope)
    return np.interp(times, t, np.array(mean))


def _cylinder_modes(disc, d0, modes):
    """(rates lambda, amplitudes a) of the finite cylinder's mean unsaturated fraction
    sum a exp(-lambda tau): 4 / alpha_m^2 x 8 / ((2k+1) pi)^2 (Crank 1975 eqs. 5.23, 4.18)."""
    from scipy.special import jn_zeros

    alpha, k = jn_zeros(0, modes[0]), 2 * np.arange(modes[1]) + 1.0
    rates = ((alpha[:, None] / disc.outer_radius) ** 2
             + (k[None, :] * np.pi / disc.thickness) ** 2).ravel() * d0
    return rates, (4 / alpha[:, None] ** 2 * 8 / (k[None, :] * np.pi) ** 2).ravel()


def greensboro(rows: int | None = None, initial_moisture: float | None = None):
    """The first ``rows`` of Greensboro's TMY3 year (all 8760 by default) as an Environment,
    starting at the isotherm's value of its first row unless ``initial_moisture`` is given."""
    from fickcam.climate.environment import Environment
    from fickcam.climate.records import read_record, resolve_record_path

    record = read_record(resolve_record_path("pvlib:723170TYA.CSV", ROOT))
    rows = record.time.size if rows is None else rows
    time, temperature = record.time[:rows], record.temperature[:rows]
    humidity = record.relative_humidity[:rows]
    start = (float(isotherm(temperature[0], humidity[0])) if initial_moisture is None
             else initial_moisture)
    return Environment.from_samples(time, temperature, humidity, 296.15, start)


def year_accuracy(accuracy: float = 1e-4) -> dict:
    """A solid disc (r 10 mm, 4 mm thick, D0 0.04 m2/s, Ea 50 kJ/mol: it follows the
    weather within days) through Greensboro's whole TMY3 year, read daily at 12:30 (mid-row:
    just after a row the reference's left-out modes still lag the new slope, 7e-5 of the
    swing 10 s after a large hourly change; mid-row it errs by ~3e-6 against 120 x 60 modes
    and 64 sub-steps): the largest |mean - ``modal_disc_mean``| over the year relative to the
    isotherm's swing, against the requested ``accuracy`` and the run's estimate; CPU
    seconds of the solve."""
    from fickcam.diffusion import Diffusivity, Disc, solve

    environment = greensboro()
    disc, diffusivity = Disc(0.01, 0.004), Diffusivity((4e-2,) * 3, 50e3)
    exposure = environment.exposure(isotherm)
    times = 86400.0 * np.arange(365) + 45000.0
    start = time.process_time()
    result = solve(disc, diffusivity, exposure, times, accuracy=accuracy)
    cost = time.process_time() - start
    reference = modal_disc_mean(disc, diffusivity, environment, times)
    edges = environment.change_times
    swing = float(np.max(np.abs(isotherm(environment.temperature(edges),
                                         environment.relative_humidity(edges))
                                - environment.initial_moisture)))
    return {"rows": int(edges.size - 1), "outputs": int(times.size), "accuracy": accuracy,
            "error": float(np.max(np.abs(result.mean - reference))) / swing,
            "estimate": float(result.error_estimate), "cost": cost, "model": result.model}


def format_year_accuracy(found: dict) -> str:
    """One line: the year's error against the requested accuracy and the estimate."""
    verdict = "within" if found["error"] <= found["accuracy"] else "ABOVE"
    return (f"solid disc through Greensboro's TMY3 year ({found['rows']} rows, "
            f"{found['outputs']} daily outputs at 12:30, {found['model']}): "
            f"error {found['error']:.1e} "
            f"of the swing vs modal reference, {verdict} the requested {found['accuracy']:g} "
            f"(estimate {found['estimate']:.1e}; {found['cost']:.2f} CPU s)")


# (key, title, width, format): the case left-aligned, numbers right-aligned
COLUMNS = (("case", "case", 36, "s"), ("months", "months", 6, "d"), ("rows", "rows", 6, "d"),
           ("record", "record [s]", 10, ".2f"), ("constant", "constant [s]", 12, ".2f"),
           ("ratio", "ratio", 6, ".2f"), ("exponent", "growth exponent", 16, ".2f"))


def format_record_table(rows: list[dict]) -> str:
    """One line per (case, months): CPU seconds under the record and the constant climate."""
    def align(key):
        return "<" if key == "case" else ">"

    header = " ".join(f"{title:{align(key)}{width}}" for key, title, width, _ in COLUMNS)
    body = [" ".join(f"{row[key]:{align(key)}{width}{form}}" for key, _, width, form in COLUMNS)
            for row in rows]
    return "\n".join([header, "-" * len(header), *body])


def result_tables(rows: list[dict], year: dict) -> dict[str, dict]:
    """The cost table and the year's accuracy as the tables of a result file."""
    cost = {"columns": [title for _, title, _, _ in COLUMNS],
            "rows": [[f"{row[key]:{form}}" for key, _, _, form in COLUMNS] for row in rows]}
    accuracy = {"columns": ["case", "rows", "outputs", "requested", "error (of the swing)",
                            "estimate", "CPU s"],
                "rows": [["solid disc r 10 mm, 4 mm, daily at 12:30, vs its modes", year["rows"],
                          year["outputs"], f"{year['accuracy']:g}", f"{year['error']:.1e}",
                          f"{year['estimate']:.1e}", f"{year['cost']:.2f}"]]}
    return {"cost": cost, "year": accuracy}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--months", type=int, nargs="+", default=[1, 3, 12])
    parser.add_argument("--out", type=Path, default=None,
                        help="result file to write (JSON with the commit, date, machine and "
                             "load), e.g. benchmarks/results/climate_records.json")
    args = parser.parse_args()
    load = os.getloadavg()[0]
    rows = run_record_bench(tuple(args.months))
    print(format_record_table(rows))
    year = year_accuracy()
    print(format_year_accuracy(year))
    if args.out is not None:
        from stamp import write_result

        write_result(args.out, "climate records against a constant climate; a year's accuracy",
                     "python benchmarks/climate_records.py --out "
                     "benchmarks/results/climate_records.json", result_tables(rows, year), load)


if __name__ == "__main__":
    main()
