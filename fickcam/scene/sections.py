"""The scene file's sections as pydantic models: values in SI floats after
validation, dimensional fields parsed with pint (:mod:`fickcam.quantities.types`). Checks that need
more than one section live in :mod:`fickcam.scene.load`.
"""
from __future__ import annotations

import math
from typing import Annotated, Literal, Union

from pydantic import AfterValidator, BeforeValidator, Field, field_validator, model_validator

from ..cam.spec import CamSection
from ..diffusion.accuracy.budget import accuracy_problem
from ..diffusion.problem.definition import MODELS
from .limits import LimitSpec
from ..linkage.spec import LinkageSection
from ..materials import MaterialSpec
from ..quantities.types import (
    Duration,
    Length,
    NonNegativePercent,
    NonNegativeTime,
    RelativeHumidity,
    PositiveAngle,
    StrictModel,
    Temperature,
    TemperatureRise,
)


class HistorySegment(StrictModel):
    """One segment of the climate history (held, or a linear ramp).

    Parameters
    ----------
    duration : float
        How long the segment lasts [s] (a scene gives e.g. ``"30 d"``).
    temperature : float
        The air temperature [K] (``"85 degC"``).
    relative_humidity : float
        The relative humidity [%].
    ramp : bool
        Ramp linearly from the previous segment's climate to this one's (not the first).
    """

    duration: Duration = Field(description="How long the segment lasts [s]")
    temperature: Temperature = Field(description="Air temperature during the segment [K]")
    relative_humidity: RelativeHumidity = Field(
        description="Relative humidity of the air during the segment [%]")
    ramp: bool = Field(
        False, description="Ramp linearly from the previous segment's climate instead of stepping")


class StateSpec(StrictModel):
    """A state given directly: uniform moisture and temperature in every part, no diffusion.

    Moisture is ``moisture`` (the same weight % in every absorbing part) or
    ``relative_humidity`` (each part at its material's equilibrium moisture Mm(RH), as Singh
    & Sanyal take 'maximum moisture absorption'); temperature is ``temperature`` or
    ``temperature_rise`` above the reference temperature.

    Parameters
    ----------
    time : float
        The ageing time of the state [s].
    moisture : float, optional
        The moisture content of every absorbing part [wt %].
    relative_humidity : float, optional
        The relative humidity the parts are in equilibrium with [%].
    temperature : float, optional
        The temperature [K].
    temperature_rise : float, optional
        The temperature above the reference temperature [K].

    References
    ----------
    S. Singh and S. Sanyal, "Variations in geometry, volume, mass and moment of
    inertia of link of a four bar mechanism made of neat resin under hygrothermal
    environment", International Journal of Innovative Research in Science, Engineering
    and Technology 5 (12), 2016.
    """

    time: NonNegativeTime = Field(0.0, description="Ageing time at which the state holds [s]")
    moisture: NonNegativePercent | None = Field(
        None, description="Moisture content of every absorbing part [weight %]")
    relative_humidity: RelativeHumidity | None = Field(
        None, description="Relative humidity every part is in equilibrium with [%]")
    temperature: Temperature | None = Field(None, description="Temperature of every part [K]")
    temperature_rise: TemperatureRise | None = Field(
        None, description="Temperature of every part above the reference temperature [K]")

    @model_validator(mode="after")
    def _one_of_each(self):
        if (self.moisture is None) == (self.relative_humidity is None):
            raise ValueError("a state needs exactly one of moisture, relative_humidity")
        if (self.temperature is None) == (self.temperature_rise is None):
            raise ValueError("a state needs exactly one of temperature, temperature_rise")
        return self


def _as_list(value):
    """One mapping is a list of one (``state: {...}`` or ``state: [{...}, ...]``)."""
    return [value] if isinstance(value, dict) else value


StandardTest = Literal["steady_damp_heat", "damp_heat_85_85", "cyclic_damp_heat"]


class EnvironmentSection(StrictModel):
    """``environment:``: the reference state and exactly one climate.

    The climate is segments, a record, a standard test or states given directly.

    Parameters
    ----------
    reference_temperature : float
        The temperature at which the parts are made and dry [K] (23 degC by default).
    initial_moisture : float
        The parts' moisture at t = 0 [wt %].
    history : list of HistorySegment, optional
        The climate as segments.
    history_file : str, optional
        A climate record: chamber CSV, TMY3 CSV, EPW, or ``pvlib:NAME``.
    test : {"steady_damp_heat", "damp_heat_85_85", "cyclic_damp_heat"}, optional
        A standard damp-heat test (:mod:`fickcam.climate.damp_heat`).
    cycles : int, optional
        ``cyclic_damp_heat``: the number of 24 h cycles [1].
    duration : float, optional
        Steady tests: how long [s].
    upper_temperature : float, optional
        ``cyclic_damp_heat``: the upper temperature [K] (40 or 55 degC).
    state : list of StateSpec, optional
        States given directly, no diffusion (one mapping or a list of them).
    """
    reference_temperature: Temperature = Field(
        296.15, description="Temperature at which the parts are made and dry [K]")
    initial_moisture: NonNegativePercent = Field(
        0.0, description="Moisture content of every part at time 0 [weight %]")
    history: list[HistorySegment] | None = Field(
        None, description="The climate as a list of segments, each held or ramped")
    history_file: str | None = Field(
        None, description="A climate record: chamber CSV, TMY3 CSV, EPW file, or pvlib:NAME")
    test: StandardTest | None = Field(
        None, description="A standard damp-heat test instead of a history")
    cycles: int | None = Field(
        None, gt=0, description="Number of 24 h cycles of cyclic_damp_heat [1]")
    duration: Duration | None = Field(None, description="Duration of a steady damp-heat test [s]")
    upper_temperature: Temperature | None = Field(
        None, description="Upper temperature of cyclic_damp_heat, 40 or 55 °C [K]")
    # states given directly, no diffusion: one mapping or a list of them
    state: Annotated[list[StateSpec] | None, BeforeValidator(_as_list)] = Field(
        None, description="Moisture and temperature given directly at ageing times, no diffusion")

    @model_validator(mode="after")
    def _one_history(self):
        given = [name for name in ("history", "history_file", "test", "state")
                 if getattr(self, name) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of history (segments), history_file (a record), "
                             "test (a standard damp-heat test) or state (given directly)")
        states = self.states()
        if self.state is not None and not states:
            raise ValueError("state needs at least one entry")
        if any(b.time <= a.time for a, b in zip(states, states[1:])):
            raise ValueError("the states' times must increase strictly")
        if self.history is not None:
            if not self.history:
                raise ValueError("history needs at least one segment")
            if self.history[0].ramp:
                raise ValueError("the first history segment cannot ramp: there is no previous segment")
        if self.test is None:
            extra = [name for name in ("cycles", "duration", "upper_temperature")
                     if getattr(self, name) is not None]
            if extra:
                raise ValueError(f"{', '.join(extra)} belong(s) to a standard test (environment.test)")
        return self


    def states(self) -> list[StateSpec]:
        """The given states as a list (empty without ``state``)."""
        return list(self.state or [])


def last_ageing_time(outputs) -> float | None:
    """The last ageing time an ``outputs:`` section lists (None for ``every``).

    Parameters
    ----------
    outputs : OutputsSection
        The section.

    Returns
    -------
    float or None
        The last listed ageing time [s].
    """
    times = outputs.ageing_times
    return times[-1] if isinstance(times, list) else None


def _accuracy(value: float) -> float:
    """``diffusion.accuracy`` refused outside the range every run accepts
    (``diffusion.accuracy.budget``)."""
    why = accuracy_problem(value)
    if why is not None:
        raise ValueError(why)
    return value


class DiffusionSection(StrictModel):
    # one model for every part, or per part name (parts not named: auto)
    """``diffusion:``: the model of moisture transport in the parts and its accuracy.

    Parameters
    ----------
    model : str or dict of str to str
        One model for every part, or per part name (parts not named: ``auto``); one of
        ``fickcam.diffusion.MODELS``.
    accuracy : float
        The relative accuracy asked of the mean moisture [-], in (0, 0.1].
    surface_layer_depth : float
        The depth below the surface over which the surface layer's moisture is averaged [m].
    """
    model: Union[str, dict[str, str]] = Field(
        "auto", description="Diffusion model for every part, or one per part name (others auto)")
    accuracy: Annotated[float, AfterValidator(_accuracy)] = Field(
        1e-3, description="Relative accuracy asked of the mean moisture, at most 0.1 [1]")
    surface_layer_depth: Length = Field(
        5e-4, description="Depth below the surface over which the surface moisture is averaged [m]")

    @field_validator("model")
    @classmethod
    def _model_names(cls, value):
        names = MODELS  # the diffusion package's own list
        for part, name in (value.items() if isinstance(value, dict) else [(None, value)]):
            if name not in names:
                where = f"part {part!r}: " if part is not None else ""
                raise ValueError(f"{where}{name!r} is not a model (one of {', '.join(names)})")
        return value


class EveryStep(StrictModel):
    """``ageing_times: {every: ...}``: ageing times at a fixed step to the end of the climate.

    Parameters
    ----------
    every : float
        The step [s].
    """
    every: Duration = Field(description="Step between ageing times, to the end of the climate [s]")


class OutputsSection(StrictModel):
    """``outputs:``: when and how finely the result is computed, and where it is written.

    Parameters
    ----------
    ageing_times : list of float or EveryStep, optional
        The ageing times [s], strictly increasing, or a step; None for the default times.
    angle_step : float
        The step of the cam or crank angle [rad], at most 30 deg.
    fields : bool
        Also store the moisture fields through each part.
    file : str, optional
        The result file to write.
    """
    ageing_times: Union[list[NonNegativeTime], EveryStep, None] = Field(
        None, description="Ageing times at which the mechanism is computed, a list or every: STEP [s]")
    angle_step: PositiveAngle = Field(
        math.radians(1.0), description="Step of the cam or crank angle, at most 30 deg [rad]")
    fields: bool = Field(False, description="Whether to store the moisture field through each part")
    file: str | None = Field(None, description="The result file to write")

    @field_validator("ageing_times")
    @classmethod
    def _increasing(cls, value):
        if isinstance(value, list):
            if not value:
                raise ValueError("give at least one ageing time")
            if any(b <= a for a, b in zip(value, value[1:])):
                raise ValueError("ageing times must increase strictly")
        return value

    @field_validator("angle_step")
    @classmethod
    def _divides_turn(cls, value):
        if value > math.radians(30):
            raise ValueError("angle_step must not exceed 30 deg")
        return value


class DesignSection(StrictModel):
    """``design:``: the geometry the mechanism must have in service.

    The ``cam:`` / ``linkage:`` sections then give the dimensions as made (``fickcam
    compensate`` writes it). Each entry holds only the keys that differ from the made
    section; the as-designed state (``<name>_design``, drift, limits) is computed from it.

    Parameters
    ----------
    cam : dict, optional
        The keys of ``cam:`` that differ in the design, as written [units as in ``cam:``].
    linkage : dict, optional
        The keys of ``linkage:`` that differ in the design [units as in ``linkage:``].
    """

    cam: dict | None = Field(
        None, description="The cam keys whose designed value differs from the made one, in cam's units")
    linkage: dict | None = Field(
        None, description="The linkage keys whose designed value differs from the made one, in linkage's units")


class SceneModel(StrictModel):
    """A whole scene file, validated: the climate, the materials, the mechanism and the outputs.

    Parameters
    ----------
    name : str
        The scene's name (not blank).
    description : str
        Free text.
    environment : EnvironmentSection
        The climate.
    materials : dict of str to MaterialSpec
        Scene material name -> its specification (a library name or properties).
    cam : CamSection, optional
        A cam and follower.
    linkage : LinkageSection, optional
        A four-bar linkage.
    diffusion : DiffusionSection
        The diffusion model and accuracy.
    outputs : OutputsSection
        Ageing times, angle step, fields, file.
    design : DesignSection, optional
        The in-service geometry, where the mechanism sections give it as made.
    limits : dict of str to fickcam.scene.limits.LimitSpec, optional
        Result variable -> its limit.
    """
    name: str = Field(
        min_length=1, description="The scene's name, written into the result and its plots")
    description: str = Field(
        "", description="Free text saying what the scene is, shown as the title of its page")
    environment: EnvironmentSection = Field(
        description="The climate the parts age in, and the reference state they are made in")
    materials: dict[str, MaterialSpec] = Field(
        min_length=1, description="The materials, each under a name you choose (a library name or properties)")
    cam: CamSection | None = Field(None, description="A cam and its follower")
    linkage: LinkageSection | None = Field(None, description="A four-bar linkage")
    diffusion: DiffusionSection = Field(
        DiffusionSection(), description="How moisture moves through the parts, and how accurately")
    outputs: OutputsSection = Field(
        OutputsSection(), description="When and how finely the result is computed, and where it is written")
    design: DesignSection | None = Field(
        None, description="The geometry the mechanism must have in service, when cam/linkage give it as made")
    limits: dict[str, LimitSpec] | None = Field(
        None, description="A limit per result variable (its name as the key); a result out of it fails")

    @field_validator("name")
    @classmethod
    def _printable(cls, value):
        if not value.strip():
            raise ValueError("must not be blank")
        return value
