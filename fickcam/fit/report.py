"""The whole calibration: read the CSV, fit every specimen and condition, test for
anomalous uptake, fit the laws across conditions, map ply values to the matrix."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, Problem, SceneError
from ..messages import warn
from . import across
from .anomalous import AnomalyTest, LangmuirFit, check_fickian
from .data import Specimen, condition_label, read_weight_gain
from .single import FickFit, fit_fickian
from pydantic import ValidationError
from ..materials import MaterialSpec, resolve
from ..materials import temperature_limit_reasons
import xarray as xr


UNDETERMINED = 10.0       # D interval wider than this factor (or Mm's wider than Mm): not determined
NEAR_EQUILIBRIUM = 0.99   # fitted M/Mm at the last weighing above which Mm is not called extrapolated


@dataclass(frozen=True)
class FitReport:
    """Everything ``fickcam fit`` finds. Ply (coupon) values throughout; for a
    composite ``diffusivity_factor`` = D22/Dm and ``moisture_factor`` = M_ply/M_matrix
    (Chamis 1983, as the scene's material model uses them) map them to the matrix
    overrides a scene takes (``matrix_values``).

    Parameters
    ----------
    name : str
        The material's name.
    source : str
        The data file.
    matrix : str
        The matrix (library name).
    fiber : str or None
        The fibre of a composite.
    fiber_volume_fraction : float or None
        The composite's fibre volume fraction [-].
    specimens : list of Specimen
        The coupons.
    specimen_fits : list of FickFit
        One Fickian fit per coupon.
    conditions : list of FickFit
        One Fickian fit per condition.
    anomalies : list of AnomalyTest
        The anomaly test per condition.
    arrhenius : LawFit
        D0 [m^2/s] and Ea [J/mol].
    saturation : LawFit
        a [weight %] and b [-] of Mm = a (RH/100)^b.
    diffusivity_factor : float
        D22/Dm of the composite [-].
    moisture_factor : float
        M_ply/M_matrix of the composite [-].
    in_plane : tuple of float
        In-plane over through-thickness diffusivity along length and width [-].
    notes : list of str
        Sentences for the user (values taken from the library, equilibrium not reached,
        parameters the weighings do not determine).

    References
    ----------
    Chamis (1983); in full in :mod:`fickcam.materials`.
    """

    name: str
    source: str
    matrix: str
    fiber: str | None
    fiber_volume_fraction: float | None
    specimens: list[Specimen]
    specimen_fits: list[FickFit]
    conditions: list[FickFit]
    anomalies: list[AnomalyTest]
    arrhenius: across.LawFit
    saturation: across.LawFit
    diffusivity_factor: float = 1.0
    moisture_factor: float = 1.0
    in_plane: tuple[float, float] = (1.0, 1.0)
    notes: list[str] = field(default_factory=list)

    @property
    def non_fickian(self) -> list[str]:
        """Labels of the conditions whose data Fick does not describe."""
        return [c.label for c, _ in self.two_phase_fits()]

    def two_phase_fits(self) -> list[tuple[FickFit, LangmuirFit]]:
        """(condition, two-phase fit) of every condition flagged non-Fickian."""
        return [(c, a.langmuir) for c, a in zip(self.conditions, self.anomalies) if a.non_fickian]

    def matrix_values(self) -> dict:
        """The matrix overrides of a scene (SI; moisture in %): ply D0 / diffusivity_factor,
        ply a / moisture_factor; Ea, b unchanged; covariances carried along."""
        d, s = self.arrhenius, self.saturation
        scale = np.array([1.0 / self.moisture_factor, 1.0])   # diag(scale) C diag(scale)
        return {"pre_exponential": d.first.value / self.diffusivity_factor,
                "activation_energy": d.second.value, "coefficient": s.first.value / self.moisture_factor,
                "exponent": s.second.value, "diffusivity_covariance": d.covariance,
                "saturation_covariance": np.outer(scale, scale) * s.covariance}

    def to_dataset(self):
        """The condition fits (dimension ``condition``) and the specimen fits (``specimen_*``
        variables, dimension ``specimen``) as an xarray Dataset, the laws as attributes."""

        def column(get):
            return ("condition", np.array([get(c) for c in self.conditions], float))

        def column_of_anomalies(get):  # NaN where the two-phase model was not fitted
            return ("condition", np.array([np.nan if a.langmuir is None else get(a.langmuir)
                                           for a in self.anomalies], float))

        variables = {
            "temperature": column(lambda c: c.temperature),
            "relative_humidity": column(lambda c: c.relative_humidity),
            "diffusivity": column(lambda c: c.diffusivity.value),
            "diffusivity_low": column(lambda c: c.diffusivity.low),
            "diffusivity_high": column(lambda c: c.diffusivity.high),
            "saturation_moisture": column(lambda c: c.saturation.value),
            "saturation_moisture_low": column(lambda c: c.saturation.low),
            "saturation_moisture_high": column(lambda c: c.saturation.high),
            "initial_slope_diffusivity": column(lambda c: c.initial_slope_diffusivity),
            "edge_corrected_diffusivity": column(lambda c: c.edge_corrected_diffusivity),
            "at_equilibrium": ("condition", np.array([c.at_equilibrium for c in self.conditions])),
            "runs_p_value": ("condition", np.array([a.runs_p_value for a in self.anomalies])),
            "two_phase_p_value": column_of_anomalies(lambda l: l.p_value),
            "non_fickian": ("condition", np.array([a.non_fickian for a in self.anomalies])),
            "binding_rate": column_of_anomalies(lambda l: l.binding_rate.value),
            "release_rate": column_of_anomalies(lambda l: l.release_rate.value),
        }
        for name, get in (("diffusivity", lambda f: f.diffusivity), ("saturation_moisture", lambda f: f.saturation)):
            for suffix, part in (("", "value"), ("_low", "low"), ("_high", "high")):
                variables[f"specimen_{name}{suffix}"] = (
                    "specimen", np.array([getattr(get(f), part) for f in self.specimen_fits]))
        ds = xr.Dataset(variables, coords={"condition": [c.label for c in self.conditions],
                                           "specimen": [f.specimens[0] for f in self.specimen_fits]})
        units = {"temperature": "K", "relative_humidity": "%", "saturation_moisture": "%",
                 "binding_rate": "1/s", "release_rate": "1/s"}
        for name in ds.data_vars:
            base = name.replace("_low", "").replace("_high", "").replace("specimen_", "")
            ds[name].attrs["units"] = units.get(base, "m2/s" if "diffusivity" in name else "1")
        ds.attrs.update(source=self.source, material=self.name,
                        pre_exponential=self.arrhenius.first.value,
                        activation_energy=self.arrhenius.second.value,
                        saturation_coefficient=self.saturation.first.value,
                        saturation_exponent=self.saturation.second.value)
        return ds


def _material(matrix: str, fiber: str | None, fiber_volume_fraction: float | None):
    """The library material the coupons are made of (names checked like a scene's)."""


    spec = {"matrix": matrix}
    if fiber is not None or fiber_volume_fraction is not None:
        spec.update(fiber=fiber, fiber_volume_fraction=fiber_volume_fraction)
    try:
        return resolve("coupon", MaterialSpec.model_validate(spec))
    except ValidationError as exc:
        reasons = "; ".join(e["msg"].removeprefix("Value error, ") for e in exc.errors())
        raise InputError(f"--matrix/--fiber: {reasons}") from None


def _check_temperatures(specimens: list[Specimen], material, name: str, file: str) -> None:
    """Coupons aged at or above the material's dry Tg or melting point are refused at their
    first line; above its service limit they are warned once per temperature."""

    problems, warned = [], set()
    for specimen in specimens:
        refusals, warnings = temperature_limit_reasons(material, name, specimen.temperature)
        line = int(specimen.lines[0]) if len(specimen.lines) else None
        problems += [Problem(file, line, "temperature", f"specimen {specimen.name!r}: {reason}")
                     for reason in refusals]
        for reason in warnings:
            if specimen.temperature not in warned:
                warned.add(specimen.temperature)
                warn("%s:%s temperature: %s", file, line, reason)
    if problems:
        raise SceneError(problems)


def _groups(specimens: list[Specimen]) -> list[list[Specimen]]:
    groups: dict[tuple, list[Specimen]] = {}
    for s in specimens:
        groups.setdefault(s.condition, []).append(s)
    return [groups[key] for key in sorted(groups)]


def fit_weight_gain(data, matrix: str, fiber: str | None = None,
                    fiber_volume_fraction: float | None = None, name: str | None = None) -> FitReport:
    """Calibrate from a weight-gain CSV (path) or a list of :class:`~fickcam.fit.data.Specimen`.

    Coupons of a composite are taken as unidirectional with the fibres along their
    length (D along the length = D11, across the width = D22 = through the thickness).

    Parameters
    ----------
    data : str, pathlib.Path or list of Specimen
        The weight-gain CSV (:func:`~fickcam.fit.data.read_weight_gain`), or coupons already read.
    matrix : str
        The library matrix material of the coupons; its activation energy and humidity
        exponent stand in where the data hold one temperature or one humidity only.
    fiber : str, optional
        The library fibre, for composite coupons.
    fiber_volume_fraction : float, optional
        The coupons' fibre volume fraction [-], with ``fiber``.
    name : str, optional
        The fitted material's name; None: the CSV file's stem.

    Returns
    -------
    FitReport
        Per coupon and per condition: D [m^2/s] and Mm [weight %] with 95 % intervals,
        the non-Fickian test; across conditions the Arrhenius law (D0 [m^2/s],
        Ea [J/mol]) and the saturation law Mm = a (RH/100)^b.

    Raises
    ------
    fickcam.errors.SceneError
        When the CSV cannot be read or a cell is faulty (file, line and column).
    fickcam.errors.InputError
        When the matrix or fibre is not in the library.
    """
    material = _material(matrix, fiber, fiber_volume_fraction)
    specimens = read_weight_gain(data) if isinstance(data, (str, Path)) else list(data)
    source = Path(data).name if isinstance(data, (str, Path)) else "<specimens>"
    _check_temperatures(specimens, material, matrix, str(data) if isinstance(data, (str, Path)) else source)
    f11, f22 = material.principal_diffusivity_factors()
    in_plane = (f11 / f22, 1.0)
    groups = _groups(specimens)
    conditions = [fit_fickian(g, in_plane, condition_label(g[0].condition)) for g in groups]
    anomalies = [check_fickian(g, c, in_plane) for g, c in zip(groups, conditions)]
    library = material.matrix
    moisture_factor = float(material.saturation_moisture(300.0, 100.0)) / library["saturation"]["coefficient"]
    report = FitReport(
        name=name or (Path(data).stem if isinstance(data, (str, Path)) else "fitted"),
        source=source, matrix=matrix, fiber=fiber, fiber_volume_fraction=fiber_volume_fraction,
        specimens=specimens, specimen_fits=[fit_fickian([s], in_plane) for s in specimens],
        conditions=conditions, anomalies=anomalies,
        arrhenius=across.arrhenius(conditions, library["diffusivity"]["activation_energy"]),
        saturation=across.saturation_law(conditions, library["saturation"].get("exponent", 1.0)),
        diffusivity_factor=f22, moisture_factor=moisture_factor, in_plane=in_plane)
    report.notes.extend(_notes(report))
    return report


def _notes(report: FitReport) -> list[str]:
    notes = []
    if report.arrhenius.second_from == "library":
        notes.append(f"one temperature only: activation energy {report.arrhenius.second.value / 1e3:.4g} "
                     f"kJ/mol taken from the library ({report.matrix})")
    if report.saturation.second_from == "library":
        notes.append(f"one humidity only: exponent {report.saturation.second.value:.4g} taken from "
                     f"the library ({report.matrix})")
    for c in report.conditions:
        if c.extrapolated and c.fraction_reached < NEAR_EQUILIBRIUM:
            notes.append(f"{c.label}: D5229 equilibrium not reached (fitted M/Mm at the last "
                         f"weighing {c.fraction_reached:.3f}): Mm extrapolated by the fit")
        elif c.extrapolated:
            notes.append(f"{c.label}: D5229 criterion (change < 0.020 % over two 7-day periods) not met "
                         f"although the fit reaches M/Mm = {c.fraction_reached:.3f}: weighing scatter "
                         "exceeds the criterion")
    for c in report.specimen_fits + report.conditions:
        if not (c.diffusivity.high < UNDETERMINED * c.diffusivity.low
                and c.saturation.high - c.saturation.low < c.saturation.value):
            notes.append(f"{c.label}: D and Mm are NOT determined by these weighings (95 % intervals "
                         f"D [{c.diffusivity.low:.3g}, {c.diffusivity.high:.3g}] m^2/s, Mm "
                         f"[{c.saturation.low:.3g}, {c.saturation.high:.3g}] %): weigh longer")
    for label in report.non_fickian:
        notes.append(f"{label}: NOT Fickian (systematic residuals removed by the two-phase model, both tests "
                     "at 1 %): see the two-phase (Langmuir) fit; the laws across conditions use its "
                     "apparent Fickian D and Mm")
    if report.fiber:
        notes.append(f"composite: coupon (ply) values; matrix overrides = ply D0 / {report.diffusivity_factor:.4g} "
                     f"(D22/Dm), ply a / {report.moisture_factor:.4g} (M_ply/M_matrix, Chamis 1983)")
    return notes


__all__ = ["FitReport", "fit_weight_gain", "condition_label"]
