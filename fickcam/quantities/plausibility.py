"""Plausibility of bare numbers: the one place that knows which values without units are
almost certainly unit slips.

A bare number is read in the SI unit of its key (``thickness: 12`` is 12 m). When that
reading cannot be what was meant and another common unit gives a sensible value, the value
is refused with the likely unit (``12 m is an implausible cam thickness (its base circle
radius is 19 mm): did you mean '12 mm'?``); a reading that is possible but unusual, where
another unit gives an ordinary value, is warned about. A value with units is never judged:
writing the unit is always the way to keep an unusual value.

Each value is judged against its own part, not one global bound:

- temperature, relative humidity and angles alone (a polymer part is not aged below 150 K;
  a bare RH is in percent, so 0.9 meant 90 %; an angle beyond a turn meant degrees), and a
  climate record's length in a history file whose header gives no unit;
- a cam's lengths against its base circle (or disc) radius, a four-bar's against its other
  bars; the base circle and the bars themselves against the size of a moulded or machined
  mechanism part;
- a rotational speed never: a bare one is refused whatever its size, since rad/s and rpm
  are both common and a factor of 9.55 apart (``speed: 200`` meant '200 rpm');
- a climate history's length by how far water gets into the parts over it (Fickian uptake
  of a plate, Crank, *The Mathematics of Diffusion*, 2nd ed., 1975, eq. 4.20: a history in
  which the parts take up almost nothing ages nothing), and an output time against the
  history it samples;
- a bound of ``limits:`` on a mechanism's length as that mechanism's own lengths (a bare
  bound on a speed is refused as any bare speed is).

The bounds are fickcam's judgement of what a polymer mechanism part can be; they only
decide when to ask for a unit, never change a value.
"""
from __future__ import annotations

import math
import statistics
from dataclasses import dataclass
from enum import IntEnum
from typing import Callable

from ..errors import Problem
from ..schema import VARIABLES
from .parsing import is_bare_number, to_si


class Verdict(IntEnum):
    """How a bare value reads: plausible, unusual (warned about) or implausible (refused).

    A worse verdict is larger (:class:`enum.IntEnum`).

    Attributes
    ----------
    PLAUSIBLE : int
        0: the value reads as meant.
    UNUSUAL : int
        1: possible but unusual, while another unit gives an ordinary value: warned about.
    IMPLAUSIBLE : int
        2: almost certainly a unit slip: refused.
    """
    PLAUSIBLE = 0
    UNUSUAL = 1
    IMPLAUSIBLE = 2


@dataclass(frozen=True)
class Band:
    """Plausible values in [``low``, ``high``], unusual ones in [``least``, ``most``].

    The rest are implausible.

    Parameters
    ----------
    low, high : float
        The plausible range [SI unit of the value, or multiples of a reference length when
        used through :meth:`times`].
    least, most : float
        The wider range of unusual values [same unit].
    """

    low: float
    high: float
    least: float = 0.0
    most: float = math.inf

    def verdict(self, value: float) -> Verdict:
        """The verdict of ``value``: plausible, unusual or implausible.

        Parameters
        ----------
        value : float
            The value [the band's unit].

        Returns
        -------
        Verdict
            PLAUSIBLE inside [low, high], UNUSUAL inside [least, most], else IMPLAUSIBLE.
        """
        if self.low <= value <= self.high:
            return Verdict.PLAUSIBLE
        if self.least <= value <= self.most:
            return Verdict.UNUSUAL
        return Verdict.IMPLAUSIBLE

    def times(self, scale: float) -> "Band":
        """This band of ratios as values: every bound multiplied by ``scale``.

        Parameters
        ----------
        scale : float
            The reference value [SI unit].

        Returns
        -------
        Band
            The band in that unit.
        """
        return Band(self.low * scale, self.high * scale, self.least * scale, self.most * scale)


@dataclass(frozen=True)
class Reading:
    """How a bare value of one key is judged.

    Parameters
    ----------
    what : str
        What it is, in messages (``"cam thickness"``).
    dimension : str
        Its dimension (a key of ``fickcam.quantities.parsing.SI_UNITS``).
    unit : str
        The SI unit a bare number is read in (``"m"``).
    verdict : callable
        ``verdict(value [SI]) -> Verdict``.
    alternatives : tuple of (str, float)
        (unit, factor on the number) a slip most likely meant, in order; the first plausible
        one is suggested.
    context : str
        What the verdict was judged against, for messages.
    """

    what: str
    dimension: str
    unit: str
    verdict: Callable[[float], Verdict]
    alternatives: tuple[tuple[str, float], ...]
    context: str = ""


def _alternatives(number: float, reading: Reading) -> list[tuple[Verdict, str, str]]:
    """(verdict, text, unit) of each alternative reading of ``number``, best first (stable:
    the readings' own order among equals)."""
    found = []
    for unit, factor in reading.alternatives:
        text = f"{number * factor:g} {unit}"
        found.append((reading.verdict(to_si(text, reading.dimension)), text, unit))
    return sorted(found, key=lambda item: item[0])


def plausible_units(number: float, reading: Reading) -> list[str]:
    """The units that read a bare ``number`` plausibly, in the reading's order.

    Parameters
    ----------
    number : float
        The bare number [``reading.unit``].
    reading : Reading
        How values of its key are judged.

    Returns
    -------
    list of str
        The alternative units that give a plausible value.
    """
    return [unit for verdict, _, unit in _alternatives(number, reading)
            if verdict is Verdict.PLAUSIBLE]


def bare_judgement(number: float, reading: Reading) -> tuple[Verdict, str] | None:
    """Judge a number given without units.

    An implausible value is always refused, an unusual one only warned about when another
    unit gives a plausible value. The reason suggests the first alternative that reads
    better, and names the others that read as well.

    Parameters
    ----------
    number : float
        The bare number, which is the value in the SI unit of its key [``reading.unit``].
    reading : Reading
        How values of this key are judged.

    Returns
    -------
    tuple of (Verdict, str) or None
        (IMPLAUSIBLE or UNUSUAL, reason), or None when the number reads well.
    """
    verdict = reading.verdict(number)
    if verdict is Verdict.PLAUSIBLE:
        return None
    found = _alternatives(number, reading)
    best = found[0][0] if found else verdict
    if verdict is Verdict.UNUSUAL and best is not Verdict.PLAUSIBLE:
        return None
    given = f"{number:g} {reading.unit}".strip()
    adjective = "an implausible" if verdict is Verdict.IMPLAUSIBLE else "an unusual"
    context = f" ({reading.context})" if reading.context else ""
    reason = f"{given} is {adjective} {reading.what}{context}"
    if best < verdict:
        meant = [text for v, text, _ in found if v is best]
        others = " or ".join(f"'{text}'" for text in meant[1:])
        also = f" ({others} would read as well)" if others else ""
        reason += (f": did you mean '{meant[0]}'?{also} Bare numbers are {reading.unit}: give "
                   f"the unit ('{meant[0]}' or '{given}')")
    else:
        reason += f"; bare numbers are {reading.unit}: give the unit to keep it ('{given}')"
    return verdict, reason


def refusal(value, reading: Reading) -> str | None:
    """Why a bare scene value is refused on its own (no context), or None.

    Parameters
    ----------
    value : object
        The scene value as written; values with units are never judged.
    reading : Reading
        How values of its key are judged.

    Returns
    -------
    str or None
        The one-line reason with the likely unit, when the value is implausible.
    """
    if not is_bare_number(value):
        return None
    judged = bare_judgement(float(value), reading)
    return judged[1] if judged and judged[0] is Verdict.IMPLAUSIBLE else None


# ---------------------------------------------------------------- values judged alone

#: a bare temperature below this (K) is almost certainly degC or degF written without unit
COLDEST_PLAUSIBLE_TEMPERATURE = 150.0

TEMPERATURE = Reading(
    "temperature", "temperature", "K",
    Band(COLDEST_PLAUSIBLE_TEMPERATURE, math.inf, COLDEST_PLAUSIBLE_TEMPERATURE).verdict,
    (("degC", 1.0), ("degF", 1.0)), "polymer parts are not aged below 150 K")


def _humidity_verdict(percent: float) -> Verdict:
    return Verdict.IMPLAUSIBLE if 0.0 < percent <= 1.0 else Verdict.PLAUSIBLE


RELATIVE_HUMIDITY = Reading(
    "relative humidity", "percent", "%", _humidity_verdict, (("%", 100.0),),
    "1 % or less is drier than any service climate")


def _angle_verdict(radians: float) -> Verdict:
    return Verdict.PLAUSIBLE if abs(radians) <= 2.0 * math.pi else Verdict.IMPLAUSIBLE


ANGLE = Reading("angle", "angle", "rad", _angle_verdict, (("deg", 1.0),),
                "more than a turn either way")

#: readings of values judged on their own, by the name ``units.quantity(bare=...)`` gives
BARE_READINGS = {"temperature": TEMPERATURE, "relative_humidity": RELATIVE_HUMIDITY,
                 "angle": ANGLE}

#: dimensions whose bare numbers are refused whatever their size: no reading of them is
#: safe. A rotational speed in rad/s and in rpm differ by a factor of 9.55 and both are
#: common in machine design: (the units a bare number may have meant, the first suggested)
AMBIGUOUS = {"angular_speed": ("rpm", "rad/s")}
#: on the command line an angle is ambiguous too: the results, the reports and every
#: example give angles in degrees, so a bare ``--cam-angle 5`` means 5 deg as often as 5 rad
OPTION_AMBIGUOUS = {**AMBIGUOUS, "angle": ("deg", "rad")}
_AMBIGUOUS_WHAT = {"angular_speed": "a rotational speed", "angle": "an angle"}


def ambiguity(value, dimension: str, among: dict = AMBIGUOUS) -> str | None:
    """Why a bare value of an ambiguous dimension (:data:`AMBIGUOUS`) is refused, or None.

    Zero needs no unit; values with units are never refused here.

    Parameters
    ----------
    value : object
        The value as written (a number, or a string with or without a unit).
    dimension : str
        Its dimension (a key of ``fickcam.quantities.parsing.SI_UNITS``).
    among : dict
        The ambiguous dimensions: :data:`AMBIGUOUS` in a scene, :data:`OPTION_AMBIGUOUS`
        on the command line.

    Returns
    -------
    str or None
        The one-line reason, suggesting the likely unit (``did you mean '200 rpm'?``).
    """
    if dimension not in among or not is_bare_number(value) or float(value) == 0:
        return None
    number = f"{float(value):g}"
    meant, other = among[dimension]
    return (f"{number} without a unit is ambiguous for {_AMBIGUOUS_WHAT[dimension]} ({meant} "
            f"or {other}): did you mean '{number} {meant}'? Give the unit ('{number} {meant}' "
            f"or '{number} {other}')")


#: a climate record's length in s: a record shorter than a day is not an ageing history
RECORD_LENGTH = Reading("climate record length", "time", "s",
                        Band(86400.0, math.inf, 86400.0).verdict,
                        (("d", 1.0), ("h", 1.0), ("min", 1.0)),
                        "a climate record shorter than a day ages no polymer part")

# ------------------------------------------------------------ values judged by their part

#: lengths a slip most likely meant: millimetres, then inches
LENGTH_ALTERNATIVES = (("mm", 1.0), ("in", 1.0))
#: history lengths: days, then hours; a standard test's: hours first (its durations are
#: specified in hours, e.g. 1000 h at 85 degC / 85 % RH)
HISTORY_ALTERNATIVES = (("d", 1.0), ("h", 1.0))
TEST_ALTERNATIVES = (("h", 1.0), ("d", 1.0))

#: the radius of a cam's base circle (or disc), m: moulded and machined cams
CAM_RADIUS = Band(2e-3, 0.5, 0.5e-3, 2.0)
#: a four-bar's bar length, m
BAR_LENGTH = Band(10e-3, 2.0, 2e-3, 10.0)


@dataclass(frozen=True)
class Member:
    """A length of a mechanism judged as a multiple of its reference length.

    Parameters
    ----------
    path : tuple of str
        Its keys below the mechanism's section.
    what : str
        What it is, in messages.
    ratio : Band
        The plausible and unusual values, as multiples of the reference length [-].
    """

    path: tuple
    what: str
    ratio: Band


#: cam lengths as multiples of the base circle (or disc) radius
CAM_MEMBERS = (
    Member(("thickness",), "cam thickness", Band(0.02, 5.0, 0.0, 25.0)),
    Member(("follower", "roller_radius"), "roller radius", Band(0.02, 2.0, 0.0, 10.0)),
    Member(("follower", "width"), "follower contact width", Band(0.02, 5.0, 0.0, 25.0)),
    Member(("follower", "guide", "overhang"), "guide overhang", Band(0.0, 10.0, 0.0, 50.0)),
    Member(("follower", "guide", "length"), "guide bush length", Band(0.0, 10.0, 0.0, 50.0)),
    Member(("follower", "guide", "diameter"), "follower stem diameter", Band(0.0, 2.0, 0.0, 10.0)),
    Member(("follower", "arm", "length"), "arm length", Band(0.0, 20.0, 0.0, 100.0)),
)
#: a four-bar's other lengths as multiples of its (median) bar length
LINKAGE_MEMBERS = (
    Member(("coupler_point", "distance"), "coupler point distance", Band(0.0, 5.0, 0.0, 25.0)),
    Member(("section", "width"), "link width", Band(0.0, 1.0, 0.0, 5.0)),
    Member(("section", "thickness"), "link thickness", Band(0.0, 1.0, 0.0, 5.0)),
    Member(("section", "boss_outer_radius"), "boss radius", Band(0.0, 1.0, 0.0, 5.0)),
    Member(("section", "boss_inner_radius"), "boss hole radius", Band(0.0, 1.0, 0.0, 5.0)),
)
BARS = ("crank", "coupler", "rocker", "frame")
#: a bar as a multiple of the other bars' median
BAR_RATIO = Band(0.05, 20.0, 0.0, 100.0)
#: a rise or return as a multiple of the base circle radius
LIFT = Band(0.0, 3.0, 0.0, 15.0)
#: a swinging arm's rise or return, rad: arms swing by degrees to tens of degrees
SWING = Band(0.0, math.radians(60.0), 0.0, math.radians(90.0))


def raw_value(data, path: tuple):
    """The value at ``path`` in the YAML data, None where the path does not lead.

    Parameters
    ----------
    data : dict
        The scene as read from YAML.
    path : tuple of str or int
        The keys.

    Returns
    -------
    object or None
        The value as written.
    """
    for key in path:
        if isinstance(data, dict):
            data = data.get(key)
        elif isinstance(data, list) and isinstance(key, int) and 0 <= key < len(data):
            data = data[key]
        else:
            return None
    return data


def si_value(value, dimension: str) -> float | None:
    """``value`` in SI, None when it cannot be read (validation says why elsewhere).

    Parameters
    ----------
    value : object
        A scene value as written.
    dimension : str
        Its dimension (a key of ``fickcam.quantities.parsing.SI_UNITS``).

    Returns
    -------
    float or None
        The value [SI unit of ``dimension``].
    """
    try:
        return to_si(value, dimension)
    except ValueError:
        return None


@dataclass
class Findings:
    """Problems with bare values: ``errors`` refuse the scene, ``warnings`` are told.

    Parameters
    ----------
    errors : list of fickcam.errors.Problem
        Implausible values.
    warnings : list of fickcam.errors.Problem
        Unusual values.
    """

    errors: list[Problem]
    warnings: list[Problem]

    def judge(self, doc, path: tuple, reading: Reading) -> bool:
        """Judge the bare value at ``path``; True when it was refused.

        Only positive values are judged: zero and negative ones are left to the section's own
        checks.

        Parameters
        ----------
        doc : fickcam.scene.yamldoc.YamlDocument
            The scene file (for the problem's line).
        path : tuple of str or int
            The value's keys.
        reading : Reading
            How it is judged.

        Returns
        -------
        bool
            True when the value was refused (added to ``errors``).
        """
        value = raw_value(doc.data, path)
        if not is_bare_number(value) or not float(value) > 0:
            return False
        judged = bare_judgement(float(value), reading)
        if judged is None:
            return False
        verdict, reason = judged
        (self.errors if verdict is Verdict.IMPLAUSIBLE else self.warnings).append(
            doc.problem(path, reason))
        return verdict is Verdict.IMPLAUSIBLE

    def refuse_ambiguous(self, doc, path: tuple, dimension: str) -> bool:
        """Refuse the value at ``path`` when it is a bare number of an ambiguous dimension
        (:func:`ambiguity`).

        Parameters
        ----------
        doc, path
            The scene file and the value's keys, as :meth:`judge` takes them.
        dimension : str
            Its dimension (a key of :data:`AMBIGUOUS` to be refused).

        Returns
        -------
        bool
            True when refused (added to ``errors``).
        """
        reason = ambiguity(raw_value(doc.data, path), dimension)
        if reason:
            self.errors.append(doc.problem(path, reason))
        return reason is not None


@dataclass(frozen=True)
class Scale:
    """A mechanism's size, that its lengths are judged against.

    Parameters
    ----------
    length : float
        The reference length [m]: the cam's base circle or disc radius, a four-bar's median
        bar.
    context : str
        Words that say so, for messages.
    """

    length: float
    context: str


#: a limit's bare length bound as a multiple of its mechanism's reference length: a
#: deviation (a tolerance band), or a max / min (a dimension)
LIMIT_DEVIATION = Band(0.0, 0.5, 0.0, 2.0)
LIMIT_BOUND = Band(0.0, 5.0, 0.0, 25.0)


def _limit_findings(doc, findings: Findings, scales: dict[str, Scale]) -> None:
    """Bare bounds of ``limits:`` on a mechanism's lengths (m) judged as the mechanism's own
    lengths; bare bounds on its speeds (rpm variables) refused as any bare speed is."""
    for name, spec in doc.data["limits"].items():
        var = VARIABLES.get(name)
        if var is None or not isinstance(spec, dict):
            continue
        scale = scales.get(var.section)
        for key in ("deviation", "max", "min"):
            if var.units == "rpm":
                findings.refuse_ambiguous(doc, ("limits", name, key), "angular_speed")
            elif var.units == "m" and scale is not None:
                band = LIMIT_DEVIATION if key == "deviation" else LIMIT_BOUND
                findings.judge(doc, ("limits", name, key),
                               _length(f"{name} {key}", band.times(scale.length), scale.context))


def _length(what: str, band: Band, context: str) -> Reading:
    return Reading(what, "length", "m", band.verdict, LENGTH_ALTERNATIVES, context)


def cam_length_reading(what: str, data: dict) -> Reading | None:
    """How a bare length bound on a cam (``fickcam size --radius-of-curvature``) is judged:
    as a ``limits:`` bound on one of the cam's lengths, against its base circle (or disc)
    radius.

    Parameters
    ----------
    what : str
        What it is, in messages.
    data : dict
        The scene as read from YAML.

    Returns
    -------
    Reading or None
        None when the scene has no cam with a radius to judge against.
    """
    cam = data.get("cam")
    if not isinstance(cam, dict):
        return None
    path, radius = _cam_reference(cam)
    if radius is None or radius <= 0:
        return None
    return _length(what, LIMIT_BOUND.times(radius), _cam_context(path, radius))


def _cam_context(path: tuple, radius: float) -> str:
    """'its base circle radius is 19 mm' (or its disc's), for messages."""
    return f"its {'disc' if path[-1] == 'radius' else 'base circle'} radius is {_mm(radius)}"


def _mm(metres: float) -> str:
    return f"{metres * 1e3:.4g} mm"


def geometry_findings(doc) -> Findings:
    """Bare lengths of ``cam:`` and ``linkage:`` judged against their own mechanism, their
    bare speeds refused (:func:`ambiguity`).

    They are read from the YAML, so that a slip is named even where it also breaks a check of
    the section; bare length and speed bounds of ``limits:`` are judged likewise.

    Parameters
    ----------
    doc : fickcam.scene.yamldoc.YamlDocument
        The scene file.

    Returns
    -------
    Findings
        The refused and the unusual values.
    """
    findings = Findings([], [])
    scales = {}
    if isinstance(doc.data.get("cam"), dict):
        scales["cam"] = _cam_findings(doc, findings)
    if isinstance(doc.data.get("linkage"), dict):
        scales["linkage"] = _linkage_findings(doc, findings)
    if isinstance(doc.data.get("limits"), dict) and not findings.errors:
        _limit_findings(doc, findings, {k: v for k, v in scales.items() if v is not None})
    return findings


def _cam_reference(cam: dict) -> tuple[tuple, float | None]:
    """(key path, value in m) of the cam's base circle radius or disc radius."""
    path = ("cam", "base_circle_radius") if "base_circle_radius" in cam else \
        ("cam", "eccentric", "radius")
    return path, si_value(raw_value({"cam": cam}, path), "length")


def _cam_findings(doc, findings: Findings) -> Scale | None:
    """Judge the cam's bare lengths, refuse its bare speeds; its scale, None when it has
    none."""
    cam = doc.data["cam"]
    for key in (("speed",), ("polydyne", "speed")):
        findings.refuse_ambiguous(doc, ("cam",) + key, "angular_speed")
    path, radius = _cam_reference(cam)
    if radius is None or radius <= 0 or findings.judge(
            doc, path, _length("cam base circle radius", CAM_RADIUS, "moulded and machined "
                               "cams measure millimetres to decimetres")):
        return None
    context = _cam_context(path, radius)
    for member in CAM_MEMBERS:
        findings.judge(doc, ("cam",) + member.path,
                       _length(member.what, member.ratio.times(radius), context))
    arm = isinstance(raw_value(cam, ("follower", "arm")), dict)
    swing = Reading("arm swing", "angle", "rad", SWING.verdict, (("deg", 1.0),),
                    "a swinging arm turns by degrees to tens of degrees")
    for k, segment in _segments(cam):
        for key in ("rise", "return"):
            if key in segment:
                findings.judge(doc, ("cam", "motion", k, key), swing if arm else
                               _length(key, LIFT.times(radius), context))
    return Scale(radius, context)


def _segments(cam: dict) -> list[tuple[int, dict]]:
    """(index, segment) of the motion segments of a ``cam:`` mapping that are mappings (the
    rest is refused by the section's own checks)."""
    motion = cam.get("motion")
    return [(k, s) for k, s in enumerate(motion) if isinstance(s, dict)] \
        if isinstance(motion, list) else []


def _linkage_findings(doc, findings: Findings) -> Scale | None:
    """Judge the four-bar's bare lengths, refuse its bare speed; its scale, None when it has
    none."""
    linkage = doc.data["linkage"]
    findings.refuse_ambiguous(doc, ("linkage", "crank_speed"), "angular_speed")
    bars = {name: si_value(linkage.get(name), "length") for name in BARS}
    bars = {name: value for name, value in bars.items() if value is not None and value > 0}
    refused = False
    for name in bars:
        refused |= findings.judge(doc, ("linkage", name), _bar_reading(linkage, bars, name))
    if refused or not bars:
        return None
    reference = statistics.median(bars.values())
    context = f"its bars measure about {_mm(reference)}"
    for member in LINKAGE_MEMBERS:
        findings.judge(doc, ("linkage",) + member.path,
                       _length(member.what, member.ratio.times(reference), context))
    return Scale(reference, context)


def _bar_reading(linkage: dict, bars: dict[str, float], name: str) -> Reading:
    """A bar judged by the size of a four-bar and against the other bars (those given with
    units first), unless those are implausible themselves."""
    others = [v for other, v in bars.items() if other != name]
    trusted = [v for other, v in bars.items()
               if other != name and not is_bare_number(linkage[other])]
    reference = statistics.median(trusted or others) if others else None
    if reference is None or BAR_LENGTH.verdict(reference) is Verdict.IMPLAUSIBLE:
        return _length(f"{name} length", BAR_LENGTH, "four-bar links measure millimetres to metres")
    return _length(f"{name} length", _tighter(BAR_LENGTH, BAR_RATIO.times(reference)),
                   f"the other bars measure about {_mm(reference)}")


def _tighter(a: Band, b: Band) -> Band:
    """The band of values both ``a`` and ``b`` accept."""
    return Band(max(a.low, b.low), min(a.high, b.high), max(a.least, b.least), min(a.most, b.most))


# ------------------------------------------------------------------------ durations

#: the share of its equilibrium moisture change a part takes up over a whole climate
#: history: below 1 % nothing ages, below 5 % hardly anything
UPTAKE = Band(0.05, math.inf, 0.01)
#: how many times an output time (a step, or the last time) fits in the history
SAMPLES = Band(0.0, 1000.0, 0.0, 1e4)


def plate_uptake(diffusivity: float, time: float, half_thickness: float) -> float:
    """Fractional uptake M(t)/M(inf) of a plate exposed on both faces, by the first term of
    the early-time series (Crank 1975, eq. 4.20): 2 sqrt(D t / (pi l^2)), at most 1. The
    further terms alternate and shrink, so this bounds the exact uptake from above.

    Parameters
    ----------
    diffusivity : float
        D [m2/s].
    time : float
        t [s].
    half_thickness : float
        l, half the plate's thickness [m].

    Returns
    -------
    float
        M(t)/M(inf) [-].
    """
    return min(1.0, 2.0 * math.sqrt(max(diffusivity * time, 0.0) / math.pi) / half_thickness)


@dataclass(frozen=True)
class Absorber:
    """The part that takes up water fastest.

    Parameters
    ----------
    name : str
        The part.
    half_thickness : float
        Its half-thickness [m].
    diffusivity : float
        Its fastest diffusivity at the hottest point of the history [m^2/s].
    """

    name: str
    half_thickness: float
    diffusivity: float

    def uptake(self, time: float) -> float:
        return plate_uptake(self.diffusivity, time, self.half_thickness)


def fastest_absorber(sizes, materials: dict, temperature: float) -> Absorber | None:
    """The part that takes up water fastest, of the bodies ``sizes`` (each mechanism's
    ``absorber_sizes``: a cam by half of its thickness or radius, a roller by half of its
    width or diameter, links by half of their section's thickness or width).

    Parameters
    ----------
    sizes : list of tuple
        (part, material name, half-size [m]) per body.
    materials : dict
        Scene material name -> resolved :class:`fickcam.materials.material.Material`.
    temperature : float
        Where the diffusivities are taken [K].

    Returns
    -------
    Absorber or None
        None when no part absorbs.
    """
    found = []
    for name, material, half in sizes:
        if material in materials and materials[material].absorbs:
            d = float(max(materials[material].diffusivity_for()(temperature)))
            found.append(Absorber(name, half, d))
    return max(found, key=lambda a: a.uptake(1.0), default=None)


def _days(seconds: float) -> str:
    return f"{seconds:g} s" if seconds < 86400 else f"{seconds / 86400:.4g} d"


def history_findings(model, doc, environment, materials: dict, sizes) -> Findings:
    """Bare climate-history lengths judged by the uptake of the fastest-absorbing part.

    A history (or a segment of it) in which the parts take up almost nothing ages nothing
    (Fickian uptake of a plate); bare output times are judged against the history they
    sample.

    Parameters
    ----------
    model : fickcam.scene.sections.SceneModel
        The validated scene.
    doc : fickcam.scene.yamldoc.YamlDocument
        The scene file.
    environment : fickcam.climate.environment.Environment
        The scene's climate.
    materials : dict
        Scene material name -> resolved :class:`fickcam.materials.material.Material`.
    sizes : list of tuple
        (part, material name, half-size [m]) of the mechanisms' bodies
        (:func:`fastest_absorber`).

    Returns
    -------
    Findings
        The refused and the unusual values.

    References
    ----------
    J. Crank, *The Mathematics of Diffusion*, 2nd ed., Oxford University Press, 1975,
    eq. 4.20.
    """
    findings = Findings([], [])
    section = model.environment
    kelvin = environment.hottest()[1]
    absorber = fastest_absorber(sizes, materials, kelvin)
    if absorber is not None and section.history is not None:
        total = environment.end
        for k, segment in enumerate(section.history):
            findings.judge(doc, ("environment", "history", k, "duration"), _history_reading(
                absorber, kelvin, total - segment.duration, total, HISTORY_ALTERNATIVES))
    if absorber is not None and section.test is not None and section.duration is not None:
        findings.judge(doc, ("environment", "duration"), _history_reading(
            absorber, kelvin, 0.0, section.duration, TEST_ALTERNATIVES))
    if not findings.errors:
        _output_findings(model, doc, environment.end, findings)
    return findings


def _history_reading(absorber: Absorber, kelvin: float, rest: float, total: float,
                     alternatives) -> Reading:
    """A history length judged as part of a history of ``rest`` [s] besides it."""
    context = (f"the {absorber.name}, {absorber.half_thickness * 1e3:.3g} mm half-thickness at "
               f"D = {absorber.diffusivity:.2g} m2/s ({kelvin - 273.15:.4g} degC), would take up "
               f"{absorber.uptake(total) * 100:.2g} % of its equilibrium moisture in "
               f"{_days(total)}")
    return Reading("climate history length", "time", "s",
                   lambda t: UPTAKE.verdict(absorber.uptake(rest + t)), alternatives, context)


def _output_findings(model, doc, end: float, findings: Findings) -> None:
    """A bare ``every`` step, or the last of bare ageing times, by how many of it fit in the
    history: more than 1000 is unusual, more than 10 000 implausible."""
    times = model.outputs.ageing_times
    if isinstance(times, list):
        path, what = ("outputs", "ageing_times", len(times) - 1), "last ageing time"
    elif times is not None:
        path, what = ("outputs", "ageing_times", "every"), "ageing time step"
    else:
        return

    findings.judge(doc, path, output_time_reading(what, end))


def output_time_reading(what: str, end: float) -> Reading:
    """How a bare output time (a step, or the last ageing time) is judged: by how many of it
    fit in the history it samples.

    Parameters
    ----------
    what : str
        What it is, in messages (``"last ageing time"``).
    end : float
        The end of the history [s].

    Returns
    -------
    Reading
        More than 1000 of it in the history unusual, more than 10 000 implausible; days,
        then hours, suggested.
    """
    def fits(step: float) -> Verdict:
        return SAMPLES.verdict(end / step if step > 0 else 0.0)

    return Reading(what, "time", "s", fits, HISTORY_ALTERNATIVES, f"the history lasts {_days(end)}")
