"""Materials: library, Chamis micromechanics, hygrothermal degradation, state, bodies.

Public API (architecture.md, "Materials"): ``MaterialSpec``, ``resolve``, ``Material``,
``material_state``, ``first_invalid_index``, ``library_table``.
"""
from .library import library, library_rows, library_table
from .material import Material, resolve
from .spec import MaterialSpec
from .state import first_invalid_index, material_state, wet_tg_and_retention

__all__ = ["Material", "MaterialSpec", "first_invalid_index", "library",
           "library_rows", "library_table", "material_state", "resolve", "wet_tg_and_retention"]
