"""Scene schema of one entry under ``materials:``."""
from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import (AfterValidator, BeforeValidator, Field, NonNegativeFloat, PositiveFloat,
                      model_validator)

from ..quantities.types import (
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
    """D = pre_exponential exp(-activation_energy / (R T)) (Shen & Springer 1976).

    Parameters
    ----------
    pre_exponential : float
        D0 [m^2/s].
    activation_energy : float
        Ea [J/mol].

    References
    ----------
    Shen, C.-H. & Springer, G. S. (1976). Moisture absorption and desorption of composite
    materials. Journal of Composite Materials 10(1), 2-20.
    """

    pre_exponential: Diffusivity = Field(description="D0 of D = D0 exp(-Ea/(R T)) [m^2/s]")
    activation_energy: MolarEnergy = Field(
        description="Activation energy Ea of the diffusivity [J/mol]")


class RateSpec(StrictModel):
    """rate = pre_exponential exp(-activation_energy / (R T)), 1/s; a plain rate is constant.

    Parameters
    ----------
    pre_exponential : float
        The rate's pre-exponential factor [1/s].
    activation_energy : float
        Ea [J/mol]; 0: a constant rate.
    """

    pre_exponential: NonNegativeRate = Field(description="Pre-exponential factor of the rate [1/s]")
    activation_energy: MolarEnergy = Field(
        0.0, description="Activation energy of the rate; 0 for a constant rate [J/mol]")


def _plain_rate(value):
    return value if isinstance(value, dict) else {"pre_exponential": value}


ArrheniusRate = Annotated[RateSpec, BeforeValidator(_plain_rate)]


class DiffusivityTable(StrictModel):
    """D/D(T) (``diffusivity_ratio``) against c/Mm (``moisture_ratio``, increasing).

    Parameters
    ----------
    moisture_ratio : list of float
        c/Mm, increasing [-].
    diffusivity_ratio : list of float
        D/D(T) at each [-].
    """

    moisture_ratio: list[NonNegativeFloat] = Field(
        description="Moisture over equilibrium moisture c/Mm, increasing [1]")
    diffusivity_ratio: list[PositiveFloat] = Field(
        description="Diffusivity over D(T) at each moisture ratio [1]")

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
    ``table``: D/D(T) against c/Mm, Mm the saturation at 100 % RH).

    Parameters
    ----------
    model : {"fickian", "langmuir", "concentration_dependent"}
        The sorption model.
    binding_rate, release_rate : RateSpec, optional
        gamma and beta of ``langmuir`` [1/s].
    exponent : float, optional
        k of D = D(T) exp(k c/Mm) [-].
    table : DiffusivityTable, optional
        D/D(T) against c/Mm.

    References
    ----------
    Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture
    diffusion in composite resins. Journal of Composite Materials 12(2), 118-131.
    """

    model: Literal["fickian", "langmuir", "concentration_dependent"] = Field(
        description="The sorption model")
    binding_rate: ArrheniusRate | None = Field(
        None, description="langmuir: rate gamma at which free water is bound [1/s]")
    release_rate: ArrheniusRate | None = Field(
        None, description="langmuir: rate beta at which bound water is released [1/s]")
    exponent: float | None = Field(
        None, description="concentration_dependent: k of D = D(T) exp(k c/Mm) [1]")
    table: DiffusivityTable | None = Field(
        None, description="concentration_dependent: D/D(T) tabulated against c/Mm")

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
    """Mm = coefficient (RH/100)^exponent, weight %.

    Parameters
    ----------
    coefficient : float
        Mm at 100 % RH [weight %].
    exponent : float
        The exponent [-].
    """

    coefficient: NonNegativePercent = Field(
        description="Equilibrium moisture at 100 % RH, a of Mm = a (RH/100)^b [weight %]")
    exponent: PositiveFloat = Field(1.0, description="Exponent b of Mm = a (RH/100)^b [1]")


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
    """95 % intervals (low, high) of the fitted values.

    Parameters
    ----------
    pre_exponential : tuple of float, optional
        Of D0 [m^2/s].
    activation_energy : tuple of float, optional
        Of Ea [J/mol].
    coefficient : tuple of float, optional
        Of the saturation coefficient [weight %].
    exponent : tuple of float, optional
        Of the saturation exponent [-].
    """

    pre_exponential: tuple[Diffusivity, Diffusivity] | None = Field(
        None, description="95 % interval of the diffusivity's D0 [m^2/s]")
    activation_energy: tuple[SignedMolarEnergy, SignedMolarEnergy] | None = Field(
        None, description="95 % interval of the diffusivity's activation energy [J/mol]")
    coefficient: tuple[SignedPercent, SignedPercent] | None = Field(
        None, description="95 % interval of the saturation coefficient [weight %]")
    exponent: tuple[float, float] | None = Field(
        None, description="95 % interval of the saturation exponent [1]")


class FitCovariance(StrictModel):
    """``diffusivity``: covariance of (ln pre_exponential, activation_energy [J/mol]);
    ``saturation``: of (coefficient [%], exponent). SI numbers.

    Parameters
    ----------
    diffusivity : tuple of tuple, optional
        2 x 2 covariance of (ln D0 [-], Ea [J/mol]).
    saturation : tuple of tuple, optional
        2 x 2 covariance of (coefficient [weight %], exponent [-]).
    """

    diffusivity: Covariance | None = Field(
        None, description="2 x 2 covariance of (ln D0 [1], Ea [J/mol])")
    saturation: Covariance | None = Field(
        None, description="2 x 2 covariance of (coefficient [weight %], exponent [1])")


class PlyValues(StrictModel):
    """What composite coupons gave before the map to the matrix overrides.

    Parameters
    ----------
    pre_exponential : float
        The ply's D0 [m^2/s].
    coefficient : float
        The ply's saturation coefficient [weight %].
    diffusivity_factor : float
        D22/Dm [-].
    moisture_factor : float
        M_ply/M_matrix [-].
    """

    pre_exponential: Diffusivity = Field(description="The ply's D0 [m^2/s]")
    coefficient: NonNegativePercent = Field(
        description="The ply's saturation coefficient [weight %]")
    diffusivity_factor: PositiveFloat = Field(
        description="Ply transverse diffusivity over matrix diffusivity, D22/Dm [1]")
    moisture_factor: PositiveFloat = Field(
        description="Ply moisture over matrix moisture, M_ply/M_matrix [1]")


class NonFickianCondition(StrictModel):
    """A condition whose weighings Fick does not describe, and its two-phase fit.

    Parameters
    ----------
    condition : str
        The condition's label.
    p_value : float
        p-value of the F test against Fick [-].
    diffusivity : float
        Free-water diffusivity [m^2/s].
    binding_rate, release_rate : float
        gamma and beta [1/s].
    """

    condition: str = Field(description="The condition's label (its temperature and humidity)")
    p_value: float = Field(
        description="p-value of the F test of the two-phase model against Fick [1]")
    diffusivity: Diffusivity = Field(description="Diffusivity of the free water [m^2/s]")
    binding_rate: Rate = Field(description="Rate gamma at which free water is bound [1/s]")
    release_rate: Rate = Field(description="Rate beta at which bound water is released [1/s]")


class FitRecord(StrictModel):
    """``materials.NAME.fit``: written by ``fickcam fit`` beside the values it found;
    validated, not used by a run (a Monte Carlo sweep may draw from ``covariance``).

    Parameters
    ----------
    source : str
        The weight-gain file fitted.
    interval_95 : FitIntervals, optional
        95 % intervals of the values.
    covariance : FitCovariance, optional
        Their covariances.
    activation_energy_from, exponent_from : {"data", "library"}
        Where Ea and the saturation exponent came from.
    ply : PlyValues, optional
        The composite coupons' own values.
    non_fickian : list of NonFickianCondition
        Conditions Fick does not describe.
    """

    source: str = Field(description="The weight-gain file that was fitted")
    interval_95: FitIntervals | None = Field(
        None, description="95 % confidence intervals of the fitted values")
    covariance: FitCovariance | None = Field(None, description="Covariances of the fitted values")
    activation_energy_from: Literal["data", "library"] = Field(
        "data", description="Whether the activation energy came from the data or the library")
    exponent_from: Literal["data", "library"] = Field(
        "data", description="Whether the saturation exponent came from the data or the library")
    ply: PlyValues | None = Field(None, description="The composite coupons' own fitted values")
    non_fickian: list[NonFickianCondition] = Field(
        [], description="Conditions whose uptake Fick's law does not describe")


class MatrixProperties(StrictModel):
    """Overrides of an isotropic material (neat resin, matrix, plastic, metal).

    Parameters
    ----------
    youngs_modulus : float, optional
        E [Pa].
    poisson_ratio : float, optional
        nu [-].
    density : float, optional
        rho [kg/m^3].
    dry_glass_transition_temperature : float, optional
        Tgd [K].
    thermal_expansion : float, optional
        alpha [1/K].
    moisture_expansion : float, optional
        beta [1/weight %].
    conductivity : float, optional
        K [W/(m K)].
    diffusivity : DiffusivitySpec, optional
        D(T).
    saturation : SaturationSpec, optional
        Mm(RH).
    melting_temperature : float, optional
        Melting point of a semicrystalline thermoplastic [K]: a climate at or above it is
        refused.
    service_temperature : float, optional
        Maximum continuous service temperature [K]: a climate above it is warned.
    heat_deflection_temperature : float, optional
        Heat deflection temperature at 1.80 MPa [K]: the service limit where no
        ``service_temperature`` is given.
    """

    youngs_modulus: Pressure | None = Field(
        None, description="Young's modulus E, replacing the library value [Pa]")
    poisson_ratio: float | None = Field(
        None, description="Poisson's ratio, replacing the library value [1]")
    density: Density | None = Field(
        None, description="Density, replacing the library value [kg/m^3]")
    dry_glass_transition_temperature: Temperature | None = Field(
        None, description="Glass transition temperature when dry [K]")
    thermal_expansion: ExpansionCoefficient | None = Field(
        None, description="Coefficient of thermal expansion [1/K]")
    moisture_expansion: float | None = Field(
        None, description="Swelling strain per weight % of moisture [1/weight %]")
    conductivity: PositiveFloat | None = Field(None, description="Thermal conductivity [W/(m K)]")
    diffusivity: DiffusivitySpec | None = Field(
        None, description="Moisture diffusivity D(T), Arrhenius in temperature [m^2/s]")
    saturation: SaturationSpec | None = Field(
        None, description="Equilibrium moisture content Mm(RH) [weight %]")
    melting_temperature: Temperature | None = Field(
        None, description="Melting point of a semicrystalline thermoplastic; a climate at or "
                          "above it is refused [K]")
    service_temperature: Temperature | None = Field(
        None, description="Maximum continuous service temperature; a climate above it is warned [K]")
    heat_deflection_temperature: Temperature | None = Field(
        None, description="Heat deflection temperature at 1.80 MPa (ISO 75); the service limit "
                          "where service_temperature is not given [K]")


class FiberProperties(StrictModel):
    """Overrides of a (transversely isotropic) fibre.

    Parameters
    ----------
    longitudinal_modulus, transverse_modulus : float, optional
        E11 and E22 [Pa].
    shear_modulus, transverse_shear_modulus : float, optional
        G12 and G23 [Pa].
    poisson_ratio : float, optional
        nu12 [-].
    density : float, optional
        rho [kg/m^3].
    thermal_expansion_longitudinal, thermal_expansion_transverse : float, optional
        alpha11 and alpha22 [1/K].
    conductivity_longitudinal, conductivity_transverse : float, optional
        K11 and K22 [W/(m K)].
    """

    longitudinal_modulus: Pressure | None = Field(
        None, description="Fibre modulus along the fibre, E11 [Pa]")
    transverse_modulus: Pressure | None = Field(
        None, description="Fibre modulus across the fibre, E22 [Pa]")
    shear_modulus: Pressure | None = Field(
        None, description="Fibre in-plane shear modulus, G12 [Pa]")
    transverse_shear_modulus: Pressure | None = Field(
        None, description="Fibre transverse shear modulus, G23 [Pa]")
    poisson_ratio: float | None = Field(None, description="Fibre Poisson's ratio nu12 [1]")
    density: Density | None = Field(None, description="Fibre density [kg/m^3]")
    thermal_expansion_longitudinal: ExpansionCoefficient | None = Field(
        None, description="Fibre thermal expansion along the fibre, alpha11 [1/K]")
    thermal_expansion_transverse: ExpansionCoefficient | None = Field(
        None, description="Fibre thermal expansion across the fibre, alpha22 [1/K]")
    conductivity_longitudinal: PositiveFloat | None = Field(
        None, description="Fibre thermal conductivity along the fibre, K11 [W/(m K)]")
    conductivity_transverse: PositiveFloat | None = Field(
        None, description="Fibre thermal conductivity across the fibre, K22 [W/(m K)]")


class MaterialSpec(MatrixProperties):
    """One material of a scene. Exactly one of: ``fiber`` + ``matrix`` (composite),
    ``matrix`` alone (neat resin), ``plastic``, ``metal``.

    Top-level property keys override the library values of a neat resin, plastic or
    metal. For a composite they override the MATRIX (the ply follows by Chamis
    micromechanics); ``matrix_properties`` is the same thing spelled explicitly and
    ``fiber_properties`` overrides the fibre.

    Parameters
    ----------
    youngs_modulus, density, dry_glass_transition_temperature : float, optional
        Overrides [Pa], [kg/m^3], [K] (see :class:`MatrixProperties`).
    thermal_expansion, moisture_expansion, conductivity : float, optional
        Overrides [1/K], [1/weight %], [W/(m K)].
    poisson_ratio : float, optional
        Override of nu [-].
    diffusivity, saturation : optional
        Overrides of D(T) [m^2/s] and Mm(RH) [weight %].
    melting_temperature, service_temperature, heat_deflection_temperature : float, optional
        Temperature limits [K] (see :class:`MatrixProperties`).
    fiber, matrix, plastic, metal : str, optional
        Library names (or aliases).
    fiber_volume_fraction, fiber_weight_fraction : float, optional
        Fibre fraction of a composite [-] (one of them).
    void_volume_fraction : float
        Void fraction [-].
    layup : {"unidirectional", "quasi_isotropic"}
        The composite's layup.
    transverse_diffusivity_model : {"chamis", "shen_springer"}
        Micromechanics of the transverse diffusivity.
    wet_tg_scale : {"celsius", "fahrenheit", "kelvin"}
        Temperature scale of the wet Tg formula.
    matrix_properties : MatrixProperties, optional
        Overrides of a composite's matrix.
    fiber_properties : FiberProperties, optional
        Overrides of its fibre.
    fit : FitRecord, optional
        What ``fickcam fit`` found.
    sorption : SorptionSpec, optional
        A non-Fickian sorption model.

    References
    ----------
    Chamis (1983); in full in :mod:`fickcam.materials`.
    """

    fiber: LibraryName | None = Field(
        None, description="Library fibre of a composite (needs matrix)")
    matrix: LibraryName | None = Field(
        None, description="Library resin: the matrix of a composite, or a neat resin alone")
    plastic: LibraryName | None = Field(None, description="Library plastic (e.g. nylon, POM)")
    metal: LibraryName | None = Field(None, description="Library metal, which absorbs no moisture")
    fiber_volume_fraction: Fraction | None = Field(
        None, description="Fibre volume fraction of a composite [1]")
    fiber_weight_fraction: Fraction | None = Field(
        None, description="Fibre weight fraction of a composite, instead of the volume fraction [1]")
    void_volume_fraction: Fraction = Field(
        0.0, description="Void volume fraction of a composite [1]")
    layup: Literal["unidirectional", "quasi_isotropic"] = Field(
        "unidirectional", description="Ply layup of the composite")
    transverse_diffusivity_model: Literal["chamis", "shen_springer"] = Field(
        "chamis", description="Micromechanics model of the composite's transverse diffusivity")
    wet_tg_scale: Literal["celsius", "fahrenheit", "kelvin"] = Field(
        "celsius", description="Temperature scale the wet glass transition formula is applied in")
    matrix_properties: MatrixProperties | None = Field(
        None, description="Properties replacing the library values of the composite's matrix")
    fiber_properties: FiberProperties | None = Field(
        None, description="Properties replacing the library values of the composite's fibre")
    fit: FitRecord | None = Field(
        None, description="What fickcam fit found from weight-gain data (written by fickcam fit)")
    sorption: SorptionSpec | None = Field(
        None, description="A non-Fickian sorption model of the material")

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
