"""The pydantic types of scene values: a value of a dimension converted to SI with bounds
(:func:`~fickcam.quantities.types.quantity`), and the strict base model of every scene section.

Parsing and conversion are in :mod:`fickcam.quantities.parsing`; bare
values that are almost certainly unit slips are refused through :mod:`fickcam.quantities.plausibility`.
"""
from __future__ import annotations

from typing import Annotated

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict

from .plausibility import BARE_READINGS, ambiguity, refusal
from .parsing import is_bare_number, temperature_difference, to_si


def quantity(dimension: str, *, positive: bool = False, nonnegative: bool = False,
             upper: float | None = None, bare: str | None = None):
    """A pydantic type: a value of ``dimension`` converted to SI, with bounds.

    Parameters
    ----------
    dimension : str
        A key of ``fickcam.quantities.parsing.SI_UNITS`` (``"length"``, ``"temperature"``...).
    positive : bool
        Refuse values that are not > 0.
    nonnegative : bool
        Refuse values < 0.
    upper : float, optional
        The largest value allowed [SI unit of ``dimension``]; None for no bound.
    bare : str, optional
        The reading of :data:`fickcam.quantities.plausibility.BARE_READINGS` that refuses implausible
        values given without units (``"temperature"``: 40 meant 40 degC, not 40 K). A bare
        value of an ambiguous dimension (a rotational speed) is refused whatever its size
        (``fickcam.quantities.plausibility.ambiguity``).

    Returns
    -------
    typing.Annotated
        ``float`` with validators that convert (:func:`fickcam.quantities.parsing.to_si`) and check;
        a value breaking a bound fails validation with a one-line reason.
    """

    def read(value):
        x = to_si(value, dimension)
        slip = ambiguity(value, dimension)  # a bare speed: rad/s or rpm?
        if slip:
            raise ValueError(slip)
        if bare is not None and is_bare_number(value):
            reason = refusal(value, BARE_READINGS[bare])
            if reason:
                raise ValueError(reason)
        return x

    def check(x: float) -> float:
        if positive and not x > 0:
            raise ValueError("must be positive")
        if nonnegative and x < 0:
            raise ValueError("must not be negative")
        if upper is not None and x > upper:
            raise ValueError(f"must not exceed {upper:g}")
        return x

    return Annotated[float, BeforeValidator(read), AfterValidator(check)]


# Convenience types used by the scene models.
Length = quantity("length", positive=True)
NonNegativeLength = quantity("length", nonnegative=True)
SignedLength = quantity("length")
Mass = quantity("mass", positive=True)
Duration = quantity("time", positive=True)
NonNegativeTime = quantity("time", nonnegative=True)
Temperature = quantity("temperature", positive=True, bare="temperature")
TemperatureRise = Annotated[float, BeforeValidator(temperature_difference)]
Angle = quantity("angle", bare="angle")
PositiveAngle = quantity("angle", positive=True, bare="angle")
AngularSpeed = quantity("angular_speed", positive=True)
Force = quantity("force")
NonNegativeForce = quantity("force", nonnegative=True)
Stiffness = quantity("stiffness", nonnegative=True)
Torque = quantity("torque")
TorsionalStiffness = quantity("torque", nonnegative=True)  # N m/rad: rad is dimensionless
MomentOfInertia = quantity("moment_of_inertia", nonnegative=True)
Pressure = quantity("pressure", positive=True)
Diffusivity = quantity("diffusivity", positive=True)
MolarEnergy = quantity("molar_energy", nonnegative=True)
Density = quantity("density", positive=True)
ExpansionCoefficient = quantity("inverse_temperature")
Fraction = quantity("fraction", nonnegative=True, upper=1.0)
RelativeHumidity = quantity("percent", nonnegative=True, upper=100.0, bare="relative_humidity")
SignedPercent = quantity("percent")
SignedMolarEnergy = quantity("molar_energy")
Rate = quantity("rate", positive=True)
NonNegativeRate = quantity("rate", nonnegative=True)
NonNegativePercent = quantity("percent", nonnegative=True)


class StrictModel(BaseModel):
    """Base of every scene/sweep section model: unknown keys are errors, values frozen.

    Each model's validator is built when it first validates (``defer_build``), not when its
    module is imported: a scene builds only the sections it has (a cam scene never builds
    the four-bar's, the sweep's or a fit record's), 0.08 CPU s of the demo run's start-up."""

    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)
