"""Sweep files: a base scene plus what to vary, by dotted path.

A sweep file names a ``base`` scene (relative to the sweep file) and either a
``grid`` (every combination of the listed values, the last key varying
fastest) or Monte Carlo draws (``samples`` cases, ``random`` distributions,
``seed``). Every varied path must exist in the base scene; list items are
addressed by their index (``environment.history.0.relative_humidity``).
Values may carry units exactly as in a scene; random draws are made in the
unit their parameters are given in and passed to the scene with that unit.
"""
from __future__ import annotations

import copy
import hashlib
import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, Union

import numpy as np
from pydantic import Field, ValidationError, field_validator, model_validator

from .._version import __version__
from ..scene.keys import short_names
from ..quantities.types import StrictModel
from ..errors import Problem, SceneError
from ..quantities.parsing import split_number_unit
from ..quantities.parsing import registry
from ..quantities.parsing import to_si
from .fitdraw import draw_fitted
from ..scene.load import SceneModel
from .fitdraw import fitted_parameters
from ..climate.records import read_record, resolve_record_path
from ..scene.load import problems_from_validation, read_yaml, validate_document

Scalar = Union[bool, int, float, str]


# --------------------------------------------------------------------------
# The sweep file model




def _number_and_unit(value: Any) -> tuple[float, str]:
    """``0.6`` → (0.6, ""), ``"65 %"`` → (65.0, "%"); ValueError if not a number."""

    if isinstance(value, bool):
        raise ValueError(f"expected a number, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value), ""
    number, unit = split_number_unit(str(value))
    return number, unit


class Distribution(StrictModel):
    """One random input of a Monte Carlo sweep.

    Exactly one of normal, uniform, lognormal (with an optional unit), or
    ``covariance: true`` on ``materials.NAME.fit`` (:mod:`fickcam.sweep.fitdraw`).

    Parameters
    ----------
    normal : tuple of (float or str, float or str), optional
        Mean and standard deviation [unit of the varied value, e.g. ``["85 degC", "2 K"]``].
    uniform : tuple of (float or str, float or str), optional
        Low and high ends [unit of the varied value]; low < high.
    lognormal : tuple of (float, float), optional
        Mean and standard deviation of ln(value) [-] (the value in ``unit``).
    covariance : True, optional
        Draw a material fit's values jointly from its covariance (takes no unit).
    unit : str, optional
        The unit of bare parameters [e.g. ``"mm"``]; not with parameters that carry one.
    """

    normal: tuple[Union[float, str], Union[float, str]] | None = None    # mean, standard deviation
    uniform: tuple[Union[float, str], Union[float, str]] | None = None   # low, high
    lognormal: tuple[float, float] | None = None                         # mu, sigma of ln(value)
    covariance: Literal[True] | None = None                              # a fit's joint draw
    unit: str | None = None                                              # unit of bare parameters

    @model_validator(mode="after")
    def _one_law(self):
        given = [name for name in LAWS if getattr(self, name) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of normal: [mean, sd], uniform: [low, high], "
                             "lognormal: [mu, sigma], covariance: true (on materials.NAME.fit)")
        if self.covariance:
            if self.unit is not None:
                raise ValueError("covariance: true takes no unit (the fit's values keep theirs)")
            return self
        first, second = self.parameters
        if self.law == "normal" and second < 0:
            raise ValueError("the standard deviation must not be negative")
        if self.law == "uniform" and not first < second:
            raise ValueError("uniform needs low < high")
        if self.law == "lognormal" and second < 0:
            raise ValueError("sigma must not be negative")
        return self

    @property
    def law(self) -> str:
        return next(name for name in LAWS if getattr(self, name) is not None)

    @property
    def draw_unit(self) -> str:
        """The unit the draws are made in ("" = bare numbers, as a scene reads them)."""
        return _common_unit(getattr(self, self.law), self.unit)

    @property
    def parameters(self) -> tuple[float, float]:
        values = getattr(self, self.law)
        return tuple(_number_and_unit(v)[0] for v in values)

    @field_validator("normal", "uniform")
    @classmethod
    def _same_unit(cls, value):
        if value is not None:
            _common_unit(value, None)
        return value

    def draw(self, rng: np.random.Generator, count: int) -> list:
        """``count`` values for the scene: floats, or strings with the draw unit.

        Parameters
        ----------
        rng : numpy.random.Generator
            The sweep's generator (seeded: reproducible).
        count : int
            The number of draws [1].

        Returns
        -------
        list of float or str
            The draws, in :attr:`draw_unit` (bare floats when it is "").
        """
        first, second = self.parameters
        if self.law == "normal":
            numbers = rng.normal(first, second, count)
        elif self.law == "uniform":
            numbers = rng.uniform(first, second, count)
        else:
            numbers = rng.lognormal(first, second, count)
        unit = self.draw_unit
        return [f"{x:.12g} {unit}" if unit else float(x) for x in numbers]


LAWS = ("normal", "uniform", "lognormal", "covariance")


def _common_unit(values, explicit: str | None) -> str:
    """The one unit of a distribution's parameters; bare numbers take ``explicit``."""
    units = set()
    for value in values:
        _, unit = _number_and_unit(value)
        if unit:
            units.add(unit)
    if len(units) > 1:
        raise ValueError(f"parameters must share one unit, got {sorted(units)}")
    if units and explicit:
        raise ValueError("give the unit either with the parameters or as unit:, not both")
    return units.pop() if units else (explicit or "")


class SweepModel(StrictModel):
    """A sweep file: a base scene and either a grid or Monte Carlo draws.

    Parameters
    ----------
    base : str
        The base scene's file, relative to the sweep file.
    grid : dict of str to list, optional
        Dotted path -> the values it takes [units as in a scene]; every combination is a case,
        the last path varying fastest.
    samples : int, optional
        The number of Monte Carlo cases [1]; with ``random`` only.
    random : dict of str to Distribution, optional
        Dotted path -> its distribution.
    seed : int
        The random generator's seed (the draws are reproducible).
    """
    base: str = Field(min_length=1)
    grid: dict[str, list[Scalar]] | None = None
    samples: int | None = Field(None, ge=1)
    random: dict[str, Distribution] | None = None
    seed: int = Field(0, ge=0)

    @field_validator("grid")
    @classmethod
    def _grid_values(cls, value):
        if value is not None:
            if not value:
                raise ValueError("the grid needs at least one dotted path")
            for path, values in value.items():
                if not values:
                    raise ValueError(f"{path}: give at least one value")
        return value

    @field_validator("random")
    @classmethod
    def _some_random(cls, value):
        if value is not None and not value:
            raise ValueError("random needs at least one dotted path")
        return value

    @model_validator(mode="after")
    def _grid_or_draws(self):
        if (self.grid is None) == (self.random is None):
            raise ValueError("give exactly one of grid (every combination) or random "
                             "(Monte Carlo draws, with samples and seed)")
        if self.random is not None and self.samples is None:
            raise ValueError("Monte Carlo draws need samples: N")
        if self.grid is not None and self.samples is not None:
            raise ValueError("samples goes with random, not with grid")
        return self


# --------------------------------------------------------------------------
# Dotted paths into the base scene


def split_path(path: str, data: dict) -> tuple:
    """The keys into ``data`` of a dotted path (``"environment.history.0.temperature"``).

    Parameters
    ----------
    path : str
        The dotted path; list items by their index.
    data : dict
        The base scene, as read from YAML.

    Returns
    -------
    tuple of str or int
        The keys, one per step.

    Raises
    ------
    ValueError
        With a one-line reason when a step is absent, an index is out of range, or the path
        names a section rather than a value.
    """
    keys: list = []
    node: Any = data
    for part in path.split("."):
        where = ".".join(str(k) for k in keys) or "the scene"
        if isinstance(node, dict):
            if part not in node:
                known = ", ".join(str(k) for k in node) or "nothing"
                raise ValueError(f"not in the base scene: {where} has no key {part!r} "
                                 f"(it has {known}); add it to the base scene to vary it")
            keys.append(part)
            node = node[part]
        elif isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise ValueError(f"not in the base scene: {where} is a list of {len(node)} "
                                 f"item(s), index it with 0..{len(node) - 1}")
            keys.append(int(part))
            node = node[int(part)]
        else:
            raise ValueError(f"not in the base scene: {where} is a value, it has no {part!r}")
    if isinstance(node, (dict, list)):
        raise ValueError("names a section, not a value: vary the values inside it")
    return tuple(keys)


def get_path(data, keys: tuple):
    """The value at ``keys`` in nested dicts/lists or pydantic models.

    Parameters
    ----------
    data : dict or pydantic.BaseModel
        The scene (as read, or validated).
    keys : tuple of str or int
        The keys (:func:`split_path`).

    Returns
    -------
    object
        The value.
    """
    node = data
    for key in keys:
        if isinstance(node, (dict, list)):
            node = node[key]
        else:
            node = getattr(node, key)
    return node


def set_path(data: dict, keys: tuple, value) -> None:
    """Set the value at ``keys`` in nested dicts/lists, in place.

    Parameters
    ----------
    data : dict
        The scene, as read from YAML.
    keys : tuple of str or int
        The keys (:func:`split_path`).
    value : object
        The new value.
    """
    node = data
    for key in keys[:-1]:
        node = node[key]
    node[keys[-1]] = value


def netcdf_name(path: str) -> str:
    """A coordinate name for a dotted path: dots become double underscores.

    Parameters
    ----------
    path : str
        The dotted path.

    Returns
    -------
    str
        ``environment__history__0__temperature``.
    """
    return path.replace(".", "__")


# --------------------------------------------------------------------------
# Units of a varied value (for the coordinate in the result)

# dimension -> (unit label in the result, factor from SI to that unit)
_LABELS = {
    "percent": ("%", 1.0), "fraction": ("1", 1.0), "angle": ("degree", 180.0 / math.pi),
    "angular_speed": ("rpm", 60.0 / (2.0 * math.pi)), "temperature": ("K", 1.0),
    "length": ("m", 1.0), "mass": ("kg", 1.0), "time": ("s", 1.0), "force": ("N", 1.0),
    "stiffness": ("N m-1", 1.0), "pressure": ("Pa", 1.0), "diffusivity": ("m2 s-1", 1.0),
    "molar_energy": ("J mol-1", 1.0), "density": ("kg m-3", 1.0),
    "inverse_temperature": ("K-1", 1.0), "acceleration": ("m s-2", 1.0),
}


def _is_angular(text: str) -> bool:
    _, unit = _number_and_unit(text)
    try:
        root = registry().Quantity(1.0, unit.replace("%", "percent")).to_root_units()
    except Exception:  # pint raises several types for unknown units
        return False
    return "radian" in str(root.units)


def infer_dimension(text: str, si_value: float) -> str | None:
    """The dimension whose SI conversion of ``text`` gives ``si_value``.

    ``si_value`` is the value the scene model made of it.

    Parameters
    ----------
    text : str
        A number with a unit, as written.
    si_value : float
        What the scene model read it as [SI unit of its dimension].

    Returns
    -------
    str or None
        The dimension (a key of ``fickcam.quantities.parsing.SI_UNITS``), or None when none
        matches.
    """

    angular = _is_angular(text)
    for dimension in _LABELS:
        if (dimension == "angle") != angular and dimension in ("angle", "percent", "fraction"):
            continue
        try:
            value = to_si(text, dimension)
        except ValueError:
            continue
        if math.isclose(value, si_value, rel_tol=1e-9, abs_tol=1e-300):
            return dimension
    return None


# --------------------------------------------------------------------------
# The loaded sweep


def _bare_number(value) -> float | None:
    """A number without units (YAML 1.1 reads ``1e-3`` as text), else None."""
    if isinstance(value, bool):
        return None
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


@dataclass(frozen=True)
class Parameter:
    """One varied scene value: its dotted path, keys into the scene, and dimension.

    Parameters
    ----------
    path : str
        The dotted path.
    keys : tuple of str or int
        Its keys (:func:`split_path`).
    dimension : str or None
        A dimension of ``fickcam.quantities.parsing.SI_UNITS``, or None for bare numbers and
        text.
    """

    path: str
    keys: tuple
    dimension: str | None  # a fickcam.quantities.types dimension, or None (bare numbers / text)

    @property
    def name(self) -> str:
        return netcdf_name(self.path)

    @property
    def units(self) -> str:
        return _LABELS[self.dimension][0] if self.dimension else "1"

    def given_unit(self, raws: list) -> str:
        """The unit the user wrote every value in (``degC``), "" if none or mixed."""
        units = set()
        for raw in raws:
            try:
                units.add(_number_and_unit(raw)[1])
            except ValueError:
                return ""
        return units.pop() if len(units) == 1 else ""

    def coordinate(self, raws: list):
        """Coordinate values for the result (SI, angles in degrees, speeds in rpm);
        NaN for a value that cannot be read (its case fails validation)."""

        if self.dimension is None:
            numbers = [_bare_number(r) for r in raws]
            if all(n is not None for n in numbers):
                return np.asarray(numbers, float)
            return np.asarray([str(r) for r in raws], dtype=object)
        factor = _LABELS[self.dimension][1]
        values = []
        for raw in raws:
            try:
                values.append(to_si(raw, self.dimension) * factor)
            except ValueError:
                values.append(math.nan)
        return np.asarray(values, float)


@dataclass(frozen=True)
class Case:
    """One scene of the sweep: its index and the raw values it sets, by dotted path.

    Parameters
    ----------
    index : int
        The case's index, from 0.
    values : dict
        Dotted path -> the value as the sweep file gives it (with its unit).
    """

    index: int
    values: dict


@dataclass
class Sweep:
    """A validated sweep file with its expanded cases.

    Parameters
    ----------
    file : str
        The sweep file's path.
    text : str
        Its text.
    model : SweepModel
        Its validated content.
    base_file : str
        The base scene's path.
    base_text : str
        Its text.
    base_dir : pathlib.Path
        Its folder (relative paths of the scene are read from there).
    base_data : dict
        The base scene as read from YAML.
    parameters : list of Parameter
        The varied values.
    cases : list of Case
        The cases, in order.
    """

    file: str
    text: str
    model: SweepModel
    base_file: str
    base_text: str
    base_dir: Path
    base_data: dict
    parameters: list[Parameter]
    cases: list[Case] = field(repr=False)

    @property
    def kind(self) -> Literal["grid", "monte_carlo"]:
        return "grid" if self.model.grid is not None else "monte_carlo"

    @property
    def identity(self) -> str:
        """Hash of what determines the results: sweep text, base text, fickcam version."""
        digest = hashlib.sha256()
        for part in (self.text, self.base_text, __version__):
            digest.update(part.encode("utf-8"))
            digest.update(b"\0")
        return digest.hexdigest()

    def scene_dict(self, case: Case) -> dict:
        """The scene of ``case``: the base scene with the case's values set, and a
        description that names them."""
        data = copy.deepcopy(self.base_data)
        for parameter in self.parameters:
            set_path(data, parameter.keys, case.values[parameter.path])
        base = str(data.get("description") or data.get("name") or "").strip()
        data["description"] = self.describe(case) + (f" (base scene: {base})" if base else "")
        return data

    def describe(self, case: Case) -> str:
        """``case 4: relative_humidity = 65 %, temperature = 85 degC`` (values as given)."""
        names = short_names([p.path for p in self.parameters])
        values = ", ".join(f"{names[p.path]} = {_as_given(case.values[p.path])}"
                           for p in self.parameters)
        return f"case {case.index}: {values}"

    def coordinates(self) -> dict[str, np.ndarray]:
        """Each parameter's coordinate values along ``case``."""
        return {p.name: p.coordinate([c.values[p.path] for c in self.cases]) for p in self.parameters}


def _as_given(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def _expand_grid(grid: dict[str, list]) -> list[Case]:
    paths = list(grid)
    return [Case(index, dict(zip(paths, combo)))
            for index, combo in enumerate(itertools.product(*(grid[p] for p in paths)))]


def _draw_cases(random: dict[str, Distribution], samples: int, seed: int,
                base_data: dict) -> list[Case]:
    """Draws in file order from one generator seeded with ``seed`` (reproducible); a
    fit's covariance draw sets each of its fitted values."""

    rng = np.random.default_rng(seed)
    columns: dict[str, list] = {}
    for path, dist in random.items():
        if dist.covariance:
            columns.update(draw_fitted(path, base_data, rng, samples))
        else:
            columns[path] = dist.draw(rng, samples)
    return [Case(index, {path: values[index] for path, values in columns.items()})
            for index in range(samples)]


def _probe_values(model: SweepModel, path: str, base_value) -> list:
    """Values of ``path`` that carry units, to learn its dimension from."""
    values = [base_value]
    if model.grid is not None:
        values += model.grid[path]
    else:
        dist = model.random[path]
        unit = dist.draw_unit
        if unit:
            values.append(f"{dist.parameters[0]:.12g} {unit}")
    return [v for v in values if isinstance(v, str)]


def _dimension_of(model: SweepModel, path: str, keys: tuple, base_data: dict) -> str | None:
    """Learn the dimension of a scene value by validating the base scene with a
    probe value at ``path`` and comparing the SI value the scene model made of it."""

    for probe in _probe_values(model, path, get_path(base_data, keys)):
        data = copy.deepcopy(base_data)
        set_path(data, keys, probe)
        try:
            si_value = get_path(SceneModel.model_validate(data), keys)
            _number_and_unit(probe)
        except (ValidationError, ValueError):
            continue
        if isinstance(si_value, float):
            dimension = infer_dimension(probe, si_value)
            if dimension is not None:
                return dimension
    return None


def _fitted_parameters(path: str, base_data: dict) -> list[Parameter]:
    """The values a fit's covariance draw sets, each as a varied parameter."""

    return [Parameter(p, split_path(p, base_data), dimension)
            for p, dimension in fitted_parameters(path, base_data)]


def _history_file_problems(model: SweepModel, doc, base_dir: Path) -> list[Problem]:
    """Each climate file a grid names, read before any case runs: a file that is missing,
    or that needs an extra this install lacks (pvlib), is refused at once at its line,
    not found by every case that uses it after the others have run."""

    problems: list[Problem] = []
    for path, values in (model.grid or {}).items():
        if path.rsplit(".", 1)[-1] != "history_file":
            continue
        for index, value in enumerate(values):
            try:
                read_record(resolve_record_path(str(value), base_dir))
            except ValueError as exc:
                problems.append(doc.problem(("grid", path, index), str(exc)))
    return problems


def load_sweep(source) -> Sweep:
    """Read and validate a sweep file; raise SceneError (one Problem per fault).

    Parameters
    ----------
    source : str or pathlib.Path
        The sweep file; its ``base`` scene is read relative to its folder.

    Returns
    -------
    Sweep
        The validated sweep with its expanded cases.

    Raises
    ------
    fickcam.errors.SceneError
        When the sweep file or its base scene does not validate (file, line and key of
        each fault).
    """

    doc = read_yaml(source, what="sweep")
    try:
        model = SweepModel.model_validate(doc.data)
    except ValidationError as exc:
        raise SceneError(problems_from_validation(exc, doc, model=SweepModel)) from None
    base_path = Path(source).resolve().parent / model.base
    if not base_path.is_file():
        raise SceneError([doc.problem(("base",), f"no such scene file: {base_path}")])
    base_doc = read_yaml(base_path)
    base_dir = base_path.parent
    validate_document(base_doc, base_dir=base_dir)  # the base must be a valid scene itself

    section = "grid" if model.grid is not None else "random"
    problems: list[Problem] = []
    parameters: list[Parameter] = []
    for path in (model.grid or model.random):
        try:
            if section == "random" and model.random[path].covariance:
                parameters += _fitted_parameters(path, base_doc.data)
                continue
            keys = split_path(path, base_doc.data)
        except ValueError as exc:
            problems.append(doc.problem((section, path), str(exc)))
            continue
        parameters.append(Parameter(path, keys, _dimension_of(model, path, keys, base_doc.data)))
    problems += _history_file_problems(model, doc, base_dir)
    if problems:
        raise SceneError(problems)
    cases = (_expand_grid(model.grid) if model.grid is not None
             else _draw_cases(model.random, model.samples, model.seed, base_doc.data))
    return Sweep(file=str(source), text=doc.text, model=model, base_file=str(base_path),
                 base_text=base_doc.text, base_dir=base_dir, base_data=base_doc.data,
                 parameters=parameters, cases=cases)
