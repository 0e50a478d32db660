"""A body that ages (:class:`~fickcam.mechanisms.part.Part`): what a mechanism tells the run
of each of its parts."""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True, eq=False)  # a part is itself: compared and hashed by identity
class Part:
    """One body that ages: its name, material, diffusion geometry and dry mass.

    Parameters
    ----------
    name : str
        The part (``cam``, ``follower``, ``crank``...), unique in its scene.
    material_name : str
        Its scene material's name.
    material : fickcam.materials.Material
        The resolved material.
    geometry : object or None
        Its diffusion geometry (:mod:`fickcam.diffusion`, dimensions [m]); None when its
        material does not absorb.
    dry_mass : float, optional
        Its dry mass [kg]; None when not known.
    """

    name: str
    material_name: str
    material: object = field(repr=False)  # its name says which
    geometry: object | None  # diffusion geometry (None: the part does not absorb)
    dry_mass: float | None = None

    @classmethod
    def made(cls, name: str, material_name: str, materials: dict, geometry,
             dry_mass: float | None) -> "Part":
        """The part of ``geometry`` in the scene material ``material_name``: without a
        diffusion geometry when that material does not absorb.

        Parameters
        ----------
        name : str
            The part's name.
        material_name : str
            Its scene material's name.
        materials : dict of str to Material
            The scene's resolved materials by name.
        geometry : object
            Its diffusion geometry (dimensions [m]).
        dry_mass : float or None
            Its dry mass [kg].

        Returns
        -------
        Part
            The part.
        """
        material = materials[material_name]
        return cls(name, material_name, material,
                   geometry if getattr(material, "absorbs", False) else None, dry_mass)
