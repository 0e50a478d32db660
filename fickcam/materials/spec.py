"""Scene schema of one entry under ``materials:``."""
from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import AfterValidator, BeforeValidator, NonNegativeFloat, PositiveFloat, model_validator

from ..units import (
    StrictModel,
    Density,
    Diffusivity,
    ExpansionCoefficient,
    Fraction,
    MolarEnergy,
    NonNegativeRate,
    NonNegativePercent,
    Pressure,
    Rate,
    SignedMolarEnergy,
    SignedPercent,
    Temperature,
)
from .library import aliases_of, known_names, library_name

#: scene key -> library group
KIND_GROUPS = {"fiber": "fibers", "matrix": "matrices", "plastic": "plastics", "metal": "metals"}


def _name_text(value):
    """A library name that YAML read as a number (``matrix: 3502``) back as its text, and an
    alias users know (``plastic: PA66``) as the library's name (``nylon``)."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        value = str(value)
    elif isinstance(value, float):
        value = str(int(value)) if value.is_integer() else str(value)
    return library_name(value) if isinstance(value, str) else value


LibraryName = Annotated[str, BeforeValidator(_name_text)]


def _unknown_name_reason(key: str, name: str) -> str:
    """Why ``key: name`` is refused: the name belongs to another kind, or the known names."""
    for other, group in KIND_GROUPS.items():
        if other != key and name in known_names(group):
            return (f"unknown {key} {name!r}: {name} is a {other} in the library, "
                    f"write '{other}: {name}'")
    known = [f"{entry} ({', '.join(aliases_of(entry))})" if aliases_of(entry) else entry
             for entry in known_names(KIND_GROUPS[key])]
    return f"unknown {key} {name!r} (known: {', '.join(known)})"


class DiffusivitySpec(StrictModel):
    """D = pre_exponential exp(-activation_energy / (R T)) (Shen & Springer 1976)."""

    pre_exponential: Diffusivity
    activation_energy: MolarEnergy


class RateSpec(StrictModel):
    """rate = pre_exponential exp(-activation_energy / (R T)), 1/s; a plain rate is constant."""

    pre_exponential: NonNegativeRate
    activation_energy: MolarEnergy = 0.0


def _plain_rate(value):
    return value if isinstance(value, dict) else {"pre_exponential": value}


ArrheniusRate = Annotated[RateSpec, BeforeValidator(_plain_rate)]


class DiffusivityTable(StrictModel):
    """D/D(T) (``diffusivity_ratio``) against c/Mm (``moisture_ratio``, increasing)."""

    moisture_ratio: list[NonNegativeFloat]
    diffusivity_ratio: list[PositiveFloat]

    @model_validator(mode="after")
    def _pairs(self):
        if len(self.moisture_ratio) != len(self.diffusivity_ratio) or len(self.moisture_ratio) < 2:
            raise ValueError("moisture_ratio and diffusivity_ratio need the same length, at least 2")
        if np.any(np.diff(self.moisture_ratio) <= 0):
            raise ValueError("moisture_ratio must increase")
        return self


SORPTION_KEYS = {"fickian": set(), "langmuir": {"binding_rate", "release_rate"},
                 "concentration_dependent": {"exponent", "table"}}


class SorptionSpec(StrictModel):
    """``materials.NAME.sorption``: ``fickian`` (default), ``langmuir`` (Carter & Kibler
    1978: ``binding_rate`` gamma, ``release_rate`` beta, each a rate or {pre_exponential,
    activation_energy}) or ``concentration_dependent`` (D = D(T) exp(``exponent`` c/Mm), or
    ``table``: D/D(T) against c/Mm, Mm the saturation at 100 % RH)."""

    model: Literal["fickian", "langmuir", "concentration_dependent"]
    binding_rate: ArrheniusRate | None = None
    release_rate: ArrheniusRate | None = None
    exponent: float | None = None
    table: DiffusivityTable | None = None

    @model_validator(mode="after")
    def _keys_of_the_model(self):
        given = {k for k in ("binding_rate", "release_rate", "exponent", "table")
                 if getattr(self, k) is not None}
        foreign = given - SORPTION_KEYS[self.model]
        if foreign:
            raise ValueError(f"model {self.model} takes no {', '.join(sorted(foreign))}")
        if self.model == "langmuir":
            if given != SORPTION_KEYS["langmuir"]:
                raise ValueError("langmuir needs binding_rate and release_rate")
            if self.binding_rate.pre_exponential > 0 and self.release_rate.pre_exponential == 0:
                raise ValueError("a binding_rate needs a positive release_rate (else nothing saturates)")
        if self.model == "concentration_dependent" and len(given) != 1:
            raise ValueError("concentration_dependent needs exactly one of exponent, table")
        if self.exponent is not None and not abs(self.exponent) <= 20:
            raise ValueError("exponent must lie in [-20, 20] (D varies by exp(k) over the range)")
        return self


class SaturationSpec(StrictModel):
    """Mm = coefficient (RH/100)^exponent, weight %."""

    coefficient: NonNegativePercent
    exponent: PositiveFloat = 1.0


def _covariance(matrix: tuple[tuple[float, float], tuple[float, float]]):
    """A 2x2 covariance: symmetric, positive semi-definite (to round-off)."""
    m = np.asarray(matrix, float)
    if not np.allclose(m, m.T, rtol=1e-6, atol=0.0):
        raise ValueError("a covariance matrix must be symmetric")
    if np.linalg.eigvalsh(m).min() < -1e-9 * max(abs(m).max(), 1e-300):
        raise ValueError("a covariance matrix must be positive semi-definite")
    return matrix


Covariance = Annotated[tuple[tuple[float, float], tuple[float, float]], AfterValidator(_covariance)]


class FitIntervals(StrictModel):
    """95 % intervals (low, high) of the fitted values."""

    pre_exponential: tuple[Diffusivity, Diffusivity] | None = None
    activation_energy: tuple[SignedMolarEnergy, SignedMolarEnergy] | None = None
    coefficient: tuple[SignedPercent, SignedPercent] | None = None
    exponent: tuple[float, float] | None = None


class FitCovariance(StrictModel):
    """``diffusivity``: covariance of (ln pre_exponential, activation_energy [J/mol]);
    ``saturation``: of (coefficient [%], exponent). SI numbers."""

    diffusivity: Covariance | None = None
    saturation: Covariance | None = None


class PlyValues(StrictModel):
    """What composite coupons gave before the map to the matrix overrides."""

    pre_exponential: Diffusivity
    coefficient: NonNegativePercent
    diffusivity_factor: PositiveFloat
    moisture_factor: PositiveFloat


class NonFickianCondition(StrictModel):
    condition: str
    p_value: float
    diffusivity: Diffusivity
    binding_rate: Rate
    release_rate: Rate


class FitRecord(StrictModel):
    """``materials.NAME.fit``: written by ``fickcam fit`` beside the values it found;
    validated, not used by a run (a Monte Carlo sweep may draw from ``covariance``)."""

    source: str
    interval_95: FitIntervals | None = None
    covariance: FitCovariance | None = None
    activation_energy_from: Literal["data", "library"] = "data"
    exponent_from: Literal["data", "library"] = "data"
    ply: PlyValues | None = None
    non_fickian: list[NonFickianCondition] = []


class MatrixProperties(StrictModel):
    """Overrides of an isotropic material (neat resin, matrix, plastic, metal)."""

    youngs_modulus: Pressure | None = None
    poisson_ratio: float | None = None
    density: Density | None = None
    dry_glass_transition_temperature: Temperature | None = None
    thermal_expansion: ExpansionCoefficient | None = None
    moisture_expansion: float | None = None  # strain per weight % of moisture
    conductivity: PositiveFloat | None = None  # W/(m K)
    diffusivity: DiffusivitySpec | None = None
    saturation: SaturationSpec | None = None


class FiberProperties(StrictModel):
    """Overrides of a (transversely isotropic) fibre."""

    longitudinal_modulus: Pressure | None = None
    transverse_modulus: Pressure | None = None
    shear_modulus: Pressure | None = None
    transverse_shear_modulus: Pressure | None = None
    poisson_ratio: float | None = None
    density: Density | None = None
    thermal_expansion_longitudinal: ExpansionCoefficient | None = None
    thermal_expansion_transverse: ExpansionCoefficient | None = None
    conductivity_longitudinal: PositiveFloat | None = None
    conductivity_transverse: PositiveFloat | None = None


class MaterialSpec(MatrixProperties):
    """One material of a scene. Exactly one of: ``fiber`` + ``matrix`` (composite),
    ``matrix`` alone (neat resin), ``plastic``, ``metal``.

    Top-level property keys override the library values of a neat resin, plastic or
    metal. For a composite they override the MATRIX (the ply follows by Chamis
    micromechanics); ``matrix_properties`` is the same thing spelled explicitly and
    ``fiber_properties`` overrides the fibre.
    """

    fiber: LibraryName | None = None
    matrix: LibraryName | None = None
    plastic: LibraryName | None = None
    metal: LibraryName | None = None
    fiber_volume_fraction: Fraction | None = None
    fiber_weight_fraction: Fraction | None = None
    void_volume_fraction: Fraction = 0.0
    layup: Literal["unidirectional", "quasi_isotropic"] = "unidirectional"
    transverse_diffusivity_model: Literal["chamis", "shen_springer"] = "chamis"
    wet_tg_scale: Literal["celsius", "fahrenheit", "kelvin"] = "celsius"
    matrix_properties: MatrixProperties | None = None
    fiber_properties: FiberProperties | None = None
    fit: FitRecord | None = None
    sorption: SorptionSpec | None = None

    @model_validator(mode="after")
    def _one_kind(self):
        kinds = [k for k in ("plastic", "metal") if getattr(self, k)]
        if self.matrix or self.fiber:
            kinds.append("composite" if self.fiber else "resin")
        if len(kinds) != 1:
            raise ValueError("give exactly one of fiber+matrix, matrix, plastic, metal")
        if self.fiber and not self.matrix:
            raise ValueError("a fiber needs a matrix")
        for key, group in KIND_GROUPS.items():
            name = getattr(self, key)
            if name is not None and name not in known_names(group):
                raise ValueError(_unknown_name_reason(key, name))
        composite = self.fiber is not None
        if composite:
            if (self.fiber_volume_fraction is None) == (self.fiber_weight_fraction is None):
                raise ValueError("a composite needs exactly one of fiber_volume_fraction, fiber_weight_fraction")
            if (self.fiber_volume_fraction or 0.0) + self.void_volume_fraction >= 1.0:
                raise ValueError("fiber_volume_fraction + void_volume_fraction must be below 1")
        else:
            extra = [k for k in ("fiber_volume_fraction", "fiber_weight_fraction", "fiber_properties")
                     if getattr(self, k) is not None]
            if extra or self.void_volume_fraction or self.layup != "unidirectional":
                raise ValueError("fiber fractions, voids, layup and fiber_properties need a fiber")
        if self.metal and (self.diffusivity or self.saturation or self.moisture_expansion
                           or self.dry_glass_transition_temperature or self.sorption):
            raise ValueError("metals take no moisture or Tg values")
        return self

    def kind(self) -> str:
        if self.fiber:
            return "composite"
        if self.matrix:
            return "resin"
        return "plastic" if self.plastic else "metal"

    def base_name(self) -> str:
        return self.matrix or self.plastic or self.metal

    def isotropic_overrides(self) -> dict:
        """Top-level and ``matrix_properties`` overrides merged (the latter win), SI."""
        own = {k: v for k, v in self.model_dump(include=set(MatrixProperties.model_fields)).items()
               if v is not None}
        if self.matrix_properties is not None:
            own.update(self.matrix_properties.model_dump(exclude_none=True))
        return own
