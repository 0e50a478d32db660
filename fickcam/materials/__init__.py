"""Materials: library, Chamis micromechanics, hygrothermal degradation, state, bodies.

Public API (architecture.md, "Materials"): ``MaterialSpec``, ``resolve``, ``Material``,
``material_state``, ``first_invalid_index``, ``library_table``.

References
----------
Chamis, C. C. (1983). Simplified composite micromechanics equations for hygral,
    thermal and mechanical properties. NASA TM-83320.
Singh, S. & Sanyal, S. (2016). Variations in geometry, volume, mass and moment of
    inertia of link of a four bar mechanism made of neat resin under hygrothermal
    environment. International Journal of Innovative Research in Science, Engineering and
    Technology (IJIRSET) 5(12).
Singh, S. & Sanyal, S. (2017). Kinematic and dynamic variations in cam and follower
    made of composite material under hygrothermal environment. International Journal of
    Innovative Research in Science, Engineering and Technology (IJIRSET) 6(3).
"""
from .library import library_rows, library_table
from .material import Material, resolve, temperature_limit_reasons
from .spec import MaterialSpec
from .state import first_invalid_index, material_state, wet_tg_and_retention

__all__ = ["Material", "MaterialSpec", "first_invalid_index",
           "library_rows", "library_table", "material_state", "resolve", "temperature_limit_reasons",
           "wet_tg_and_retention"]
