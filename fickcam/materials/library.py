"""The built-in material library (``fickcam/data/materials.yaml``) and its listing."""
from __future__ import annotations

import copy
import math
import textwrap
import functools
from importlib import resources

import yaml

GROUPS = ("fibers", "matrices", "plastics", "metals")

#: names users know for library entries -> the entry (only entries the library holds):
#: the nylon entry holds PA66 values, acetal POM values, polyimide Vespel-type values
ALIASES = {"PA66": "nylon", "PA6": "nylon", "POM": "acetal", "PI": "polyimide"}
#: what a user of an alias must know when the entry is close to, not the same as, the
#: material the alias names
ALIAS_NOTES = {"PA6": "PA6 is read as the library's nylon, whose values are typical of "
                      "dry-as-moulded PA66; PA6 takes up more water than PA66: override "
                      "saturation and diffusivity with PA6 data where you have them"}


@functools.lru_cache(maxsize=1)
def _load() -> dict:
    text = resources.files("fickcam").joinpath("data/materials.yaml").read_text(encoding="utf-8")
    # libyaml's safe loader where PyYAML has it: the same data, 7 x faster than the
    # Python one (0.02 CPU s of every run that reads a material)
    return _numbers(yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader)))


def _numbers(node):
    """PyYAML (YAML 1.1) reads '3.45e9' as text: turn numeric strings into floats."""
    if isinstance(node, dict):
        return {k: _numbers(v) for k, v in node.items()}
    if isinstance(node, str):
        try:
            return float(node)
        except ValueError:
            return node
    return node


def library() -> dict:
    """A deep copy of the whole library: group -> name -> values (SI).

    Returns
    -------
    dict
        group -> name -> values (SI; moisture in weight %).
    """
    return copy.deepcopy(_load())


def library_name(name) -> str:
    """The library name that ``name`` means: itself, an alias (``PA66`` -> ``nylon``), or
    either written in another case; ``name`` unchanged when it means none.

    Parameters
    ----------
    name : str
        A name as a user writes it.

    Returns
    -------
    str
        The library name.
    """
    text = str(name)
    folded = text.casefold()
    names = {str(key).casefold(): str(key) for group in GROUPS for key in _load()[group]}
    names.update({alias.casefold(): entry for alias, entry in ALIASES.items()})
    return names.get(folded, text) if text not in names.values() else text


def aliases_of(name: str) -> list[str]:
    """The aliases of a library name, in :data:`ALIASES` order.

    Parameters
    ----------
    name : str
        A library name.

    Returns
    -------
    list of str
        Its aliases.
    """
    return [alias for alias, entry in ALIASES.items() if entry == name]


def known_names(group: str) -> list[str]:
    """Names in one library group (``fibers``, ``matrices``, ``plastics``, ``metals``).

    Parameters
    ----------
    group : str
        The group.

    Returns
    -------
    list of str
        Its names, sorted.
    """
    return sorted(_load()[group])


def entry(group: str, name: str) -> dict:
    """One library entry (a copy).

    Parameters
    ----------
    group : str
        The group.
    name : str
        The library name.

    Returns
    -------
    dict
        Its values (SI).

    Raises
    ------
    KeyError
        When the group or the name is not in the library.
    """
    return copy.deepcopy(_load()[group][name])


def _fmt(value) -> str:
    return "-" if value is None else f"{value:.4g}"


def _celsius(kelvin) -> float | None:
    return None if kelvin is None else kelvin - 273.15


def library_rows() -> list[dict]:
    """One row per material: group, name, density, modulus, alpha, beta, Tgd, melting point,
    service limit, Mm(100 %), source.

    Returns
    -------
    list of dict
        Rows with density_kg_m3 [kg/m^3], modulus_GPa [GPa], alpha_per_K [1/K],
        beta_per_pct [1/weight %], dry_tg_degC [degC], melting_degC [degC], service_degC
        [degC] (the maximum continuous service temperature, else the heat deflection
        temperature), saturation_pct [weight %], aliases and sources.
    """
    rows = []
    for group in GROUPS:
        for name, values in sorted(_load()[group].items()):
            service = values.get("service_temperature", values.get("heat_deflection_temperature"))
            rows.append({
                "group": group, "name": name,
                "density_kg_m3": values.get("density"),
                "modulus_GPa": (values.get("youngs_modulus") or values.get("longitudinal_modulus")) / 1e9,
                "alpha_per_K": values.get("thermal_expansion", values.get("thermal_expansion_longitudinal")),
                "beta_per_pct": values.get("moisture_expansion"),
                "dry_tg_degC": _celsius(values.get("dry_glass_transition_temperature")),
                "melting_degC": _celsius(values.get("melting_temperature")),
                "service_degC": _celsius(service),
                "saturation_pct": (values.get("saturation") or {}).get("coefficient"),
                "aliases": aliases_of(name),
                "sources": " ".join(values["sources"].split()),
            })
    return rows


def library_table() -> str:
    """The library as text for ``fickcam materials``: key values, then each source.

    Returns
    -------
    str
        The table.
    """
    head = f"{'group':<9} {'name':<10} {'rho kg/m3':>9} {'E GPa':>7} {'alpha 1/K':>10} " \
           f"{'beta 1/%':>9} {'Tgd degC':>8} {'Tm degC':>7} {'Tmax degC':>9} {'Mm(100%)':>8}"
    lines = [head, "-" * len(head)]
    rows = library_rows()
    for r in rows:
        lines.append(f"{r['group']:<9} {r['name']:<10} {_fmt(r['density_kg_m3']):>9} "
                     f"{_fmt(r['modulus_GPa']):>7} {_fmt(r['alpha_per_K']):>10} "
                     f"{_fmt(r['beta_per_pct']):>9} {_fmt(r['dry_tg_degC']):>8} "
                     f"{_fmt(r['melting_degC']):>7} {_fmt(r['service_degC']):>9} "
                     f"{_fmt(r['saturation_pct']):>8}")
    known = [f"{', '.join(r['aliases'])} = {r['name']}" for r in rows if r["aliases"]]
    lines += ["", f"Also known as: {'; '.join(known)}"]
    lines += ["", "Tm: melting point; Tmax: maximum continuous service temperature, else heat "
                  "deflection temperature at 1.80 MPa; '-': none (metals, fibres) or not known"]
    lines += ["", "Sources (ASSUMPTION = fickcam's choice, override in the scene):"]
    lines += [f"  {r['name']}: {r['sources']}" for r in rows]
    return "\n".join(lines)


#: library key -> (label, unit shown, factor from SI, offset)
_SHOWN = {
    "density": ("density", "kg/m3", 1.0, 0.0),
    "youngs_modulus": ("Young's modulus", "GPa", 1e-9, 0.0),
    "longitudinal_modulus": ("longitudinal modulus E11", "GPa", 1e-9, 0.0),
    "transverse_modulus": ("transverse modulus E22", "GPa", 1e-9, 0.0),
    "shear_modulus": ("shear modulus G12", "GPa", 1e-9, 0.0),
    "transverse_shear_modulus": ("transverse shear modulus G23", "GPa", 1e-9, 0.0),
    "poisson_ratio": ("Poisson ratio", "", 1.0, 0.0),
    "dry_glass_transition_temperature": ("dry glass transition temperature", "degC", 1.0, -273.15),
    "melting_temperature": ("melting point", "degC", 1.0, -273.15),
    "service_temperature": ("maximum continuous service temperature", "degC", 1.0, -273.15),
    "heat_deflection_temperature": ("heat deflection temp. (1.80 MPa)", "degC", 1.0, -273.15),
    "glass_transition_dry": ("glass transition (DSC), dry", "degC", 1.0, -273.15),
    "glass_transition_wet": ("glass transition (DSC), wet", "degC", 1.0, -273.15),
    "thermal_expansion": ("thermal expansion", "1/K", 1.0, 0.0),
    "thermal_expansion_wet": ("thermal expansion, wet", "1/K", 1.0, 0.0),
    "thermal_expansion_longitudinal": ("thermal expansion, longitudinal", "1/K", 1.0, 0.0),
    "thermal_expansion_transverse": ("thermal expansion, transverse", "1/K", 1.0, 0.0),
    "moisture_expansion": ("moisture expansion", "1/%", 1.0, 0.0),
    "conductivity": ("thermal conductivity", "W/(m K)", 1.0, 0.0),
    "conductivity_longitudinal": ("thermal conductivity, longitudinal", "W/(m K)", 1.0, 0.0),
    "conductivity_transverse": ("thermal conductivity, transverse", "W/(m K)", 1.0, 0.0),
    "tensile_strength": ("tensile strength", "MPa", 1e-6, 0.0),
    "compressive_strength": ("compressive strength", "MPa", 1e-6, 0.0),
    "shear_strength": ("shear strength", "MPa", 1e-6, 0.0),
}
#: where the strengths come from, per group (the library file's header says the same)
STRENGTH_SOURCES = {
    "fibers": "typical of Chamis (1984, NASA TM-83696, Table 1), ASSUMPTION",
    "matrices": "typical of Chamis (1984, NASA TM-83696, Table 1), ASSUMPTION",
    "plastics": "typical data-sheet value, ASSUMPTION",
}
_GAS_CONSTANT = 8.314462618  # J/(mol K)


def find_entry(name: str) -> tuple[str, dict]:
    """(group, entry) of a library name or alias, matched without regard to case; KeyError
    if none.

    Parameters
    ----------
    name : str
        A library name or alias, in any case.

    Returns
    -------
    tuple
        (group, a copy of the entry (SI)).

    Raises
    ------
    KeyError
        When the name is not in the library.
    """
    name = library_name(name)
    for group in GROUPS:
        if name in _load()[group]:
            return group, copy.deepcopy(_load()[group][name])
    raise KeyError(name)


def _diffusivity_lines(law: dict) -> list[str]:
    """D = D0 exp(-Ea / (R T)), with D at 23 and 80 degC for a feel of the scale."""
    d0, ea = float(law["pre_exponential"]), float(law["activation_energy"])
    at = ", ".join(f"{d0 * math.exp(-ea / (_GAS_CONSTANT * (c + 273.15))):.3g} m2/s at {c} degC"
                   for c in (23, 80))
    return [f"  diffusivity          D = D0 exp(-Ea/(R T)): D0 = {d0:.4g} m2/s, "
            f"Ea = {ea / 1e3:.4g} kJ/mol ({at})"]


def _saturation_lines(law: dict) -> list[str]:
    """Mm = a (RH/100)^b, with its value at 50 and 100 % RH."""
    a, b = float(law["coefficient"]), float(law.get("exponent", 1.0))
    return [f"  saturation moisture  Mm = a (RH/100)^b: a = {a:.4g} %, b = {b:.4g} "
            f"({a * 0.5 ** b:.3g} % at 50 % RH, {a:.3g} % at 100 % RH)"]


def _retention_line(table: dict) -> str:
    """The moisture-modulus table: the share of the dry modulus kept at each moisture."""
    pairs = ", ".join(f"{r:.4g} at {m:.4g} %" for m, r in zip(table["moisture"], table["retention"]))
    return f"  {'modulus retention with moisture':<36} {pairs} (linear between, held beyond)"


def entry_text(name: str) -> str:
    """One library entry for ``fickcam materials NAME``: every value with its unit, the
    diffusivity and saturation laws, and the sources.

    Parameters
    ----------
    name : str
        A library name or alias.

    Returns
    -------
    str
        The text.

    Raises
    ------
    KeyError
        When the name is not in the library.
    """
    group, values = find_entry(name)
    name = library_name(name)
    also = ", ".join(aliases_of(name))
    lines = [f"{name} ({group[:-1] if group != 'matrices' else 'matrix'}"
             f"{'; also ' + also if also else ''})"]
    for key, value in values.items():
        if key in _SHOWN:
            label, unit, factor, offset = _SHOWN[key]
            shown = "none" if value is None else f"{value * factor + offset:.4g} {unit}"
            if value is None and key == "dry_glass_transition_temperature":
                shown = "none (Chamis' wet-Tg law not applied)"
            if key.endswith("_strength") and group in STRENGTH_SOURCES:
                shown = f"{shown:<12} ({STRENGTH_SOURCES[group]})"
            lines.append(f"  {label:<36} {shown}".rstrip())
    if "moisture_modulus" in values:
        lines.append(_retention_line(values["moisture_modulus"]))
    if "diffusivity" in values:
        lines += _diffusivity_lines(values["diffusivity"])
    if "saturation" in values:
        lines += _saturation_lines(values["saturation"])
    if "diffusivity" not in values and "saturation" not in values:
        lines.append("  takes up no moisture" if group == "metals" else
                     "  moisture: set by the matrix it is combined with")
    others = [k for k in values if k not in _SHOWN and k not in ("diffusivity", "saturation",
                                                               "sources", "moisture_modulus")]
    lines += [f"  {k:<36} {values[k]}" for k in others]
    lines += textwrap.wrap(" ".join(str(values.get("sources", "-")).split()), width=92,
                           initial_indent="  sources: ", subsequent_indent="    ")
    return "\n".join(lines)
