"""Moisture beyond Fick's law: the two-phase (Langmuir-type) model on exact modes, on
a planform's modes and on finite-volume meshes; the concentration-dependent diffusivity
on finite volumes, and its corrected sheet x planform product on cam plates and links."""
