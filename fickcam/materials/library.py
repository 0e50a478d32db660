"""The built-in material library (``fickcam/data/materials.yaml``) and its listing."""
from __future__ import annotations

import copy
import functools
from importlib import resources

import yaml

GROUPS = ("fibers", "matrices", "plastics", "metals")


@functools.lru_cache(maxsize=1)
def _load() -> dict:
    text = resources.files("fickcam").joinpath("data/materials.yaml").read_text(encoding="utf-8")
    return _numbers(yaml.safe_load(text))


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
    """A deep copy of the whole library: group -> name -> values (SI)."""
    return copy.deepcopy(_load())


def known_names(group: str) -> list[str]:
    """Names in one library group (``fibers``, ``matrices``, ``plastics``, ``metals``)."""
    return sorted(_load()[group])


def entry(group: str, name: str) -> dict:
    """One library entry (a copy)."""
    return copy.deepcopy(_load()[group][name])


def _fmt(value) -> str:
    return "-" if value is None else f"{value:.4g}"


def library_rows() -> list[dict]:
    """One row per material: group, name, density, modulus, alpha, beta, Tgd, Mm(100 %), source."""
    rows = []
    for group in GROUPS:
        for name, values in sorted(_load()[group].items()):
            tg = values.get("dry_glass_transition_temperature")
            rows.append({
                "group": group, "name": name,
                "density_kg_m3": values.get("density"),
                "modulus_GPa": (values.get("youngs_modulus") or values.get("longitudinal_modulus")) / 1e9,
                "alpha_per_K": values.get("thermal_expansion", values.get("thermal_expansion_longitudinal")),
                "beta_per_pct": values.get("moisture_expansion"),
                "dry_tg_degC": None if tg is None else tg - 273.15,
                "saturation_pct": (values.get("saturation") or {}).get("coefficient"),
                "sources": " ".join(values["sources"].split()),
            })
    return rows


def library_table() -> str:
    """The library as text for ``fickcam materials``: key values, then each source."""
    head = f"{'group':<9} {'name':<10} {'rho kg/m3':>9} {'E GPa':>7} {'alpha 1/K':>10} " \
           f"{'beta 1/%':>9} {'Tgd degC':>8} {'Mm(100%)':>8}"
    lines = [head, "-" * len(head)]
    rows = library_rows()
    for r in rows:
        lines.append(f"{r['group']:<9} {r['name']:<10} {_fmt(r['density_kg_m3']):>9} "
                     f"{_fmt(r['modulus_GPa']):>7} {_fmt(r['alpha_per_K']):>10} "
                     f"{_fmt(r['beta_per_pct']):>9} {_fmt(r['dry_tg_degC']):>8} "
                     f"{_fmt(r['saturation_pct']):>8}")
    lines += ["", "Sources (ASSUMPTION = fickcam's choice, override in the scene):"]
    lines += [f"  {r['name']}: {r['sources']}" for r in rows]
    return "\n".join(lines)
