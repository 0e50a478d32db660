"""SYNTHETIC weight-gain data: coupons weighed at D5229-like times, uptake from the
exact Fickian or two-phase solution, Gaussian scatter. For tests and for the
labelled example data set (no measured table was reachable, see the user guide's materials page);
never to be presented as measurements."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from .data import Specimen
from .models import fickian_fraction, two_phase_fraction
from ..diffusion.problem.exposure import GAS_CONSTANT

DAY = 86400.0
EARLY_HOURS = (1.0, 2.0, 4.0, 8.0)
EARLY_DAYS = (1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 10.0, 14.0)


def d5229_times(end_days: float) -> np.ndarray:
    """Weighing times (s): dry at 0, 1/2/4/8 h, days 1-5, 7, 10, 14, then weekly to
    ``end_days`` (a D5229 procedure A schedule: frequent early, a 7-day reference
    period later).

    Parameters
    ----------
    end_days : float
        The last weighing [d].

    Returns
    -------
    numpy.ndarray
        The weighing times [s].
    """
    hours = np.array(EARLY_HOURS) / 24.0
    days = np.array([d for d in EARLY_DAYS if d <= end_days])
    weekly = np.arange(21.0, end_days + 1e-9, 7.0)
    return np.concatenate([[0.0], hours, days, weekly]) * DAY


def synthetic_specimen(name, temperature, relative_humidity, thickness, times, saturation,
                       diffusivity, rng, noise, width=None, length=None, gamma=0.0, beta=0.0):
    """One coupon: M = Mm F(t) + N(0, noise^2) (weight %); F Fickian (gamma = 0) or
    two-phase. ``noise`` is an absolute scatter in weight %.

    Parameters
    ----------
    name, temperature, relative_humidity, thickness
        The coupon's name and conditions, as :class:`~fickcam.fit.data.Specimen` holds
        them: temperature [K], relative humidity [%], thickness [m].
    times : array_like
        Weighing times [s].
    saturation : float
        Mm [weight %].
    diffusivity : float
        Through-thickness diffusivity D [m^2/s].
    rng : numpy.random.Generator
        The random numbers.
    noise : float
        Standard deviation of the scatter [weight %].
    width, length : float, optional
        In-plane sides [m]; None: edges sealed.
    gamma : float
        Binding rate of the two-phase model [1/s]; 0: Fickian.
    beta : float
        Release rate [1/s].

    Returns
    -------
    Specimen
        The coupon.
    """
    specimen = Specimen(name, temperature, relative_humidity, thickness, width, length,
                        np.asarray(times, float), np.zeros(len(times)), np.arange(len(times)) + 2)
    if gamma > 0:
        fraction = two_phase_fraction(specimen, diffusivity, gamma, beta)
    else:
        fraction = fickian_fraction(specimen, diffusivity)
    moisture = saturation * fraction + rng.normal(0.0, noise, fraction.shape)
    moisture[0] = 0.0 if times[0] == 0 else moisture[0]  # the dry weighing defines M = 0
    return Specimen(name, temperature, relative_humidity, thickness, width, length,
                    specimen.time, moisture, specimen.lines)


def _mm(length: float | None) -> str:
    """A length (m) as a CSV cell in mm; an empty cell for one not given."""
    return "" if length is None else f"{length * 1e3:g}"


def write_weight_gain_csv(specimens, path, comments=(), dry_mass_g: float | None = None) -> Path:
    """Write coupons as a tidy CSV (``# comments`` first). With ``dry_mass_g`` the
    masses are written (dry_mass, mass in g, 5 decimals like a 0.01 mg balance),
    else the moisture content in %. Coupons with sealed edges among open ones get empty
    width and length cells.

    Parameters
    ----------
    specimens : list of Specimen
        The coupons (SI; moisture [weight %]).
    path : str or pathlib.Path
        The CSV file.
    comments : sequence of str
        Comment lines written first.
    dry_mass_g : float, optional
        Dry mass [g]: write masses instead of moisture content.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    path = Path(path)
    with open(path, "w", newline="", encoding="utf-8") as handle:
        for line in comments:
            handle.write(f"# {line}\n")
        writer = csv.writer(handle)
        edges = any(s.width is not None for s in specimens)  # empty cells: sealed edges
        head = ["specimen", "temperature [degC]", "relative_humidity [%]", "thickness [mm]"]
        head += ["width [mm]", "length [mm]"] if edges else []
        head += ["time [d]"] + (["dry_mass [g]", "mass [g]"] if dry_mass_g else ["moisture [%]"])
        writer.writerow(head)
        for s in specimens:
            for t, m in zip(s.time, s.moisture):
                row = [s.name, f"{s.temperature - 273.15:g}", f"{s.relative_humidity:g}",
                       f"{s.thickness * 1e3:g}"]
                row += [_mm(s.width), _mm(s.length)] if edges else []
                row.append(f"{t / DAY:.6g}")
                if dry_mass_g:
                    row += [f"{dry_mass_g:.5f}", f"{dry_mass_g * (1 + m / 100):.5f}"]
                else:
                    row.append(f"{m:.4f}")
                writer.writerow(row)
    return path


# ------------------------------------------------------------ the example data set
EXAMPLE_SEED = 5229
EXAMPLE_D_20C = 3.8e-13      # m^2/s, epoxy moulding compound at 20 degC (TU Delft repository abstract)
EXAMPLE_D_85C = 3.6e-12      # m^2/s, the same at 85 degC
EXAMPLE_COEFFICIENT = 5.0    # %, 3502 equilibrium moisture, Singh & Sanyal (2016) Table 4
EXAMPLE_EXPONENT = 1.4       # solubility ~ RH^1.4, Piggott & Woo (1987) abstract
EXAMPLE_CONDITIONS = ((40.0, 85.0), (60.0, 85.0), (85.0, 85.0), (85.0, 50.0), (85.0, 70.0))
EXAMPLE_BALANCE_SCATTER_G = 2e-4   # weighing scatter (g), 1 sigma; masses rounded to 0.1 mg
EXAMPLE_DRY_MASS_G = 6.35          # 50 x 50 x 2 mm of a 1.27 g/cm3 resin


def example_arrhenius() -> tuple[float, float]:
    """(D0 m^2/s, Ea J/mol) of the Arrhenius law through the example's two diffusivities
    (at 20 and 85 degC).

    Returns
    -------
    tuple of float
        D0 [m^2/s] and Ea [J/mol].
    """

    t1, t2 = 293.15, 358.15
    ea = GAS_CONSTANT * np.log(EXAMPLE_D_85C / EXAMPLE_D_20C) / (1.0 / t1 - 1.0 / t2)
    return EXAMPLE_D_20C * np.exp(ea / (GAS_CONSTANT * t1)), ea


def write_example(path) -> Path:
    """The SYNTHETIC example shipped as configs/weight_gain_synthetic_epoxy.csv: two
    50 x 50 x 2 mm coupons (edges open) per condition, weighed 70 days.

    Parameters
    ----------
    path : str or pathlib.Path
        Where the example CSV goes.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    rng = np.random.default_rng(EXAMPLE_SEED)
    d0, ea = example_arrhenius()

    coupons = []
    for t_c, rh in EXAMPLE_CONDITIONS:
        tk = t_c + 273.15
        d = d0 * np.exp(-ea / (GAS_CONSTANT * tk))
        mm = EXAMPLE_COEFFICIENT * (rh / 100.0) ** EXAMPLE_EXPONENT
        for k in (1, 2):
            coupons.append(synthetic_specimen(
                f"T{t_c:g}-RH{rh:g}-{k}", tk, rh, 2e-3, d5229_times(70.0), mm, d, rng,
                EXAMPLE_BALANCE_SCATTER_G / EXAMPLE_DRY_MASS_G * 100.0, width=50e-3, length=50e-3))
    comments = [
        "SYNTHETIC DATA - NOT MEASURED. Generated by fickcam.fit.synthetic.write_example",
        "(seed 5229) from the exact Fickian series of 50 x 50 x 2 mm coupons, edges open.",
        "D(T): Arrhenius through D = 3.8e-7 mm^2/s at 20 degC and 3.6e-6 mm^2/s at 85 degC",
        "  (epoxy moulding compound, TU Delft repository abstract, 'Effect of temperature and",
        f"  humidity on moisture diffusion in an epoxy moulding compound material'): D0 = {d0:.4g} m^2/s,",
        f"  Ea = {ea / 1e3:.4g} kJ/mol.",
        "Mm = a (RH/100)^b: a = 5.0 % (3502 equilibrium moisture, Singh & Sanyal 2016,",
        "  IJIRSET 5(12), Table 4), b = 1.4 (Piggott & Woo 1987: solubility ~ RH^1.4).",
        "Scatter: 0.2 mg (1 sigma) on each weighing, masses rounded to 0.1 mg.",
        "No published weight-gain table was reachable (see the user guide, 'Materials and fickcam fit').",
    ]
    return write_weight_gain_csv(coupons, path, comments, dry_mass_g=EXAMPLE_DRY_MASS_G)
