"""A resolved, SI material: library entry + scene overrides, with its ply properties."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..diffusion.problem.exposure import Diffusivity
from ..diffusion.problem.sorption import ConcentrationDependent, Langmuir, Rate
from . import micromechanics as mm
from .hygrothermal import KELVIN_OFFSET, thermal_property_factor
from .library import entry

PER_PERCENT_TO_PER_FRACTION = 100.0  # beta per weight % -> per unit weight fraction


@dataclass(frozen=True)
class Material:
    """Everything the state and diffusion need, in SI (moisture in weight %).

    ``matrix`` holds the isotropic constituent (matrix, neat resin, plastic or metal),
    ``fiber`` the fibre of a composite (else None). Plain data only: picklable.

    Parameters
    ----------
    name : str
        The material's name.
    kind : str
        ``"composite"``, ``"resin"``, ``"plastic"`` or ``"metal"``.
    matrix : dict
        The isotropic constituent's values (SI; moisture in weight %).
    fiber : dict or None
        The fibre's values (SI); None but for a composite.
    fiber_ratio : float
        Fibre volume fraction kf [-].
    void_ratio : float
        Void volume fraction kv [-].
    layup : str
        ``"unidirectional"`` or ``"quasi_isotropic"``.
    transverse_diffusivity_model : str
        ``"chamis"`` or ``"shen_springer"``.
    wet_tg_scale : str
        Temperature scale of the wet Tg formula: ``"celsius"``, ``"fahrenheit"`` or
        ``"kelvin"``.
    sources : tuple of str
        Where the values come from.
    sorption : dict or None
        The scene's ``sorption`` (SI); None: Fickian.

    References
    ----------
    Chamis (1983); in full in :mod:`fickcam.materials`.
    """

    name: str
    kind: str  # composite | resin | plastic | metal
    matrix: dict
    fiber: dict | None = None
    fiber_ratio: float = 0.0
    void_ratio: float = 0.0
    layup: str = "unidirectional"
    transverse_diffusivity_model: str = "chamis"
    wet_tg_scale: str = "celsius"
    sources: tuple[str, ...] = field(default=())
    sorption: dict | None = None  # the scene's ``sorption`` (SI), None: Fickian

    # ---------------------------------------------------------------- basics
    @property
    def absorbs(self) -> bool:
        return self.kind != "metal" and self.matrix.get("saturation", {}).get("coefficient", 0.0) > 0.0

    @property
    def matrix_ratio(self) -> float:
        return float(mm.matrix_volume_ratio(self.fiber_ratio, self.void_ratio)) if self.fiber else 1.0

    @property
    def dry_density(self) -> float:
        if self.fiber is None:
            return self.matrix["density"]
        return float(mm.ply_density(self.fiber_ratio, self.matrix_ratio, self.fiber["density"],
                                    self.matrix["density"]))

    @property
    def dry_glass_transition_temperature(self) -> float | None:
        return self.matrix.get("dry_glass_transition_temperature")

    @property
    def melting_temperature(self) -> float | None:
        return self.matrix.get("melting_temperature")

    @property
    def service_limit(self) -> tuple[float, str] | None:
        """(temperature [K], what it is) above which the part is warned: the maximum
        continuous service temperature, else the heat deflection temperature; None: neither
        is known."""
        if self.matrix.get("service_temperature") is not None:
            return self.matrix["service_temperature"], "maximum continuous service temperature"
        if self.matrix.get("heat_deflection_temperature") is not None:
            return self.matrix["heat_deflection_temperature"], "heat deflection temperature (1.80 MPa)"
        return None

    @property
    def _beta_fraction(self) -> float:
        return self.matrix.get("moisture_expansion", 0.0) * PER_PERCENT_TO_PER_FRACTION

    # ---------------------------------------------------------------- moisture
    def matrix_moisture(self, ply_moisture):
        """Matrix moisture (weight %) from the part's (ply) moisture via Chamis' relation.

        Parameters
        ----------
        ply_moisture : float or array_like
            The part's (ply) moisture [weight %].

        Returns
        -------
        numpy.ndarray
            The matrix moisture [weight %] (the same for a neat resin).
        """
        if self.fiber is None:
            return np.asarray(ply_moisture, float)
        return mm.matrix_moisture(ply_moisture, self._beta_fraction, self.matrix_ratio,
                                  self.void_ratio, self.matrix["density"], self.dry_density)

    def saturation_moisture(self, temperature, relative_humidity_percent):
        """Saturation moisture of the part (weight %) at T (K) and RH (%): matrix
        Mm = a (RH/100)^b (temperature-independent, Shen & Springer 1976; Chamis 1983 with
        b = 1), carried to the ply by Chamis' M_l relation for composites.

        Parameters
        ----------
        temperature : float or array_like
            The temperature [K] (the law does not depend on it; it sets the shape).
        relative_humidity_percent : float or array_like
            The relative humidity [%].

        Returns
        -------
        numpy.ndarray
            The saturation moisture of the part [weight %]; 0 for a material that does
            not absorb.

        References
        ----------
        C.-H. Shen and G. S. Springer, "Moisture absorption and desorption of composite
        materials", *Journal of Composite Materials* 10(1), 2-20, 1976,
        doi:10.1177/002199837601000101.
        """
        rh = np.asarray(relative_humidity_percent, float) + 0.0 * np.asarray(temperature, float)
        if not self.absorbs:
            return np.zeros_like(rh)
        sat = self.matrix["saturation"]
        matrix_value = sat["coefficient"] * np.clip(rh / 100.0, 0.0, None) ** sat.get("exponent", 1.0)
        if self.fiber is None:
            return matrix_value
        return mm.ply_moisture(matrix_value, self._beta_fraction, self.matrix_ratio, self.void_ratio,
                               self.matrix["density"], self.dry_density)

    def principal_diffusivity_factors(self) -> tuple[float, float]:
        """(D11/Dm, D22/Dm) of the ply (Chamis 1983 / Shen & Springer 1976); (1, 1) if isotropic."""
        if self.fiber is None:
            return 1.0, 1.0
        return (float(mm.longitudinal_diffusivity(self.fiber_ratio, 1.0)),
                float(mm.transverse_diffusivity(self.fiber_ratio, 1.0, self.transverse_diffusivity_model)))

    def diffusivity_for(self, part_axes=None) -> Diffusivity:
        """Arrhenius diffusivity along the part axes (x, y in-plane, z thickness).

        UD: fibres along x: (D11, D22, D22). Quasi-isotropic: in-plane mean (D11 + D22)/2
        (rotational average of a 2nd-order tensor), D22 through the thickness. A ``Disc``
        part (x = y = radial) of a UD ply takes the in-plane mean for its radial value.
        Resins and plastics: isotropic. Metals: zero.
        """
        if not self.absorbs:
            return Diffusivity((0.0, 0.0, 0.0), 0.0)
        d = self.matrix["diffusivity"]
        d0, ea = d["pre_exponential"], d["activation_energy"]
        f11, f22 = self.principal_diffusivity_factors()
        radial = type(part_axes).__name__ == "Disc"
        if self.layup == "quasi_isotropic" or (radial and self.fiber is not None):
            mean = 0.5 * (f11 + f22)
            return Diffusivity((d0 * mean, d0 * mean, d0 * f22), ea)
        return Diffusivity((d0 * f11, d0 * f22, d0 * f22), ea)

    def sorption_law(self):
        """The part's sorption law (``diffusion.sorption``), None when Fickian. The
        two-phase rates are the matrix's local exchange rates, the same in a ply; the
        concentration-dependent law is relative to the ply's Mm at 100 % RH."""
        spec = self.sorption
        if not self.absorbs or spec is None or spec["model"] == "fickian":
            return None
        if spec["model"] == "langmuir":
            return Langmuir(Rate(**spec["binding_rate"]), Rate(**spec["release_rate"]))
        reference = float(self.saturation_moisture(np.array(300.0), np.array(100.0)))
        if spec.get("exponent") is not None:
            return ConcentrationDependent(reference, exponent=float(spec["exponent"]))
        table = spec["table"]
        return ConcentrationDependent(reference, ratios=tuple(table["moisture_ratio"]),
                                      factors=tuple(table["diffusivity_ratio"]))

    # ---------------------------------------------------------------- properties
    def ply_properties(self, retention, thermal_factor=None) -> dict[str, np.ndarray]:
        """Principal properties at a matrix retention P/P0 (array): Chamis 1983 degradation
        applied to the matrix (Em, Gm times P/P0; alpha_m, K_m times P0/P; nu_m, beta_m
        unchanged), then micromechanics (UD) and laminate averaging (quasi-isotropic).
        ``thermal_factor`` replaces P0/P on the thermal matrix properties (e.g. the secant
        factor for free thermal strain). Metals ignore both. Keys: e11, e22, g12, g23, nu12, nu23, alpha11,
        alpha22, beta11, beta22, k11, k22 (ply axes; for QI 1 = 2 = in-plane)."""
        r = np.asarray(retention, float)
        m = self.matrix
        if self.kind == "metal":
            r = np.ones_like(r)
        em = m["youngs_modulus"] * r
        gm = mm.matrix_shear_modulus(em, m["poisson_ratio"])
        thermal = thermal_property_factor(r) if thermal_factor is None else np.asarray(thermal_factor, float)
        if self.kind == "metal":
            thermal = np.ones_like(r)
        am = m.get("thermal_expansion", 0.0) * thermal
        km_cond = m.get("conductivity", np.nan) * thermal
        bm = m.get("moisture_expansion", 0.0) + 0.0 * r
        if self.fiber is None:
            return {"e11": em, "e22": em, "g12": gm, "g23": gm, "nu12": m["poisson_ratio"] + 0 * r,
                    "nu23": m["poisson_ratio"] + 0 * r, "alpha11": am, "alpha22": am,
                    "beta11": bm, "beta22": bm, "k11": km_cond, "k22": km_cond}
        f, kf, kmr = self.fiber, self.fiber_ratio, self.matrix_ratio
        e11 = mm.rule_of_mixtures(kf, kmr, f["longitudinal_modulus"], em)
        e22 = mm.transverse_inverse_mixture(kf, em, f["transverse_modulus"])
        g12 = mm.transverse_inverse_mixture(kf, gm, f["shear_modulus"])
        g23 = mm.transverse_inverse_mixture(kf, gm, f["transverse_shear_modulus"])
        nu12 = mm.rule_of_mixtures(kf, kmr, f["poisson_ratio"], m["poisson_ratio"]) + 0 * r
        props = {
            "e11": e11, "e22": e22, "g12": g12, "g23": g23, "nu12": nu12,
            "nu23": mm.transverse_poisson_ratio(e22, g23),
            "alpha11": mm.longitudinal_expansion(kf, kmr, f["thermal_expansion_longitudinal"],
                                                 f["longitudinal_modulus"], am, em, e11),
            "alpha22": mm.transverse_expansion(kf, f["thermal_expansion_transverse"], am,
                                               m["poisson_ratio"], f["longitudinal_modulus"], e11),
            "beta11": mm.longitudinal_moisture_expansion(kmr, bm, em, e11),
            "beta22": mm.transverse_moisture_expansion(kf, bm, em, e22),
            "k11": mm.rule_of_mixtures(kf, kmr, f["conductivity_longitudinal"], km_cond),
            "k22": mm.transverse_conductivity(kf, f["conductivity_transverse"], km_cond),
        }
        if self.layup == "quasi_isotropic":
            props = _quasi_isotropic(props)
        return props


def temperature_limit_reasons(material: Material, name: str, temperature: float) -> tuple[list[str], list[str]]:
    """Why a climate at ``temperature`` is refused (at or above the dry Tg of a thermoset or
    the melting point of a thermoplastic) or warned (above the service limit), for material
    ``name``.

    Parameters
    ----------
    material : Material
        The material.
    name : str
        Its name, as the user wrote it.
    temperature : float
        The hottest temperature of the climate [K].

    Returns
    -------
    tuple of list of str
        (reasons to refuse, reasons to warn), each one line.
    """
    def celsius(kelvin: float) -> str:
        return f"{kelvin - KELVIN_OFFSET:.1f} degC"

    refusals, warnings = [], []
    tg = material.dry_glass_transition_temperature
    if tg is not None and temperature >= tg:
        refusals.append(f"{celsius(temperature)} is at or above the dry Tg of material {name!r} "
                        f"({celsius(tg)})")
    melting = material.melting_temperature
    if melting is not None and temperature >= melting:
        refusals.append(f"{celsius(temperature)} is at or above the melting point of material "
                        f"{name!r} ({celsius(melting)})")
    limit = material.service_limit
    if not refusals and limit is not None and temperature > limit[0]:
        warnings.append(f"{celsius(temperature)} is above the {limit[1]} of material {name!r} "
                        f"({celsius(limit[0])}): the part may soften, creep or deform, which "
                        f"fickcam does not model")
    return refusals, warnings


def _quasi_isotropic(p: dict) -> dict:
    """In-plane isotropic values of a quasi-isotropic laminate (Tsai & Hahn 1980 ch. 7);
    through-thickness values stay the ply's transverse ones."""
    q = dict(p)
    e, g, nu = mm.quasi_isotropic_elastic(p["e11"], p["e22"], p["g12"], p["nu12"])
    alpha = mm.quasi_isotropic_expansion(p["e11"], p["e22"], p["g12"], p["nu12"], p["alpha11"], p["alpha22"])
    beta = mm.quasi_isotropic_expansion(p["e11"], p["e22"], p["g12"], p["nu12"], p["beta11"], p["beta22"])
    k = 0.5 * (p["k11"] + p["k22"])
    q.update(e11=e, e22=e, g12=g, nu12=nu, alpha11=alpha, beta11=beta, k11=k)
    q["alpha_in_plane"], q["beta_in_plane"] = alpha, beta
    return q


def _merge(base: dict, overrides: dict) -> dict:
    merged = dict(base)
    merged.update({k: v for k, v in overrides.items() if v is not None})
    return merged


def resolve(name: str, spec, library=None) -> Material:
    """Build the SI :class:`Material` of scene entry ``name`` from its ``MaterialSpec``.

    ``library`` (optional) is a dict shaped like ``fickcam/data/materials.yaml``
    (group -> name -> values) to use instead of the built-in one.

    Parameters
    ----------
    name : str
        The scene's name for the material (messages, the result's ``material``).
    spec : MaterialSpec
        The validated scene entry: a library name and overrides (values in SI).
    library : dict, optional
        A library to use instead of the built-in one.

    Returns
    -------
    Material
        The material, every value in SI (moisture in weight %).
    """
    def lookup(group: str, key: str) -> dict:
        if library is not None:
            return dict(library[group][key])
        return entry(group, key)

    kind = spec.kind()
    group = {"composite": "matrices", "resin": "matrices", "plastic": "plastics", "metal": "metals"}[kind]
    base = lookup(group, spec.base_name())
    sources = [f"{spec.base_name()}: {' '.join(str(base.pop('sources', '')).split())}"]
    matrix = _merge(base, spec.isotropic_overrides())
    fiber = None
    kf = kv = 0.0
    if kind == "composite":
        fiber_base = lookup("fibers", spec.fiber)
        sources.insert(0, f"{spec.fiber}: {' '.join(str(fiber_base.pop('sources', '')).split())}")
        fiber = _merge(fiber_base, spec.fiber_properties.model_dump() if spec.fiber_properties else {})
        kv = spec.void_volume_fraction
        kf = spec.fiber_volume_fraction
        if kf is None:
            kf = float(mm.fiber_volume_ratio(spec.fiber_weight_fraction, fiber["density"],
                                             matrix["density"], kv))
    overridden = sorted(spec.isotropic_overrides())
    if overridden:
        sources.append(f"overridden in the scene: {', '.join(overridden)}")
    return Material(name=name, kind=kind, matrix=matrix, fiber=fiber, fiber_ratio=float(kf),
                    void_ratio=float(kv), layup=spec.layup,
                    transverse_diffusivity_model=spec.transverse_diffusivity_model,
                    wet_tg_scale=spec.wet_tg_scale, sources=tuple(sources),
                    sorption=spec.sorption.model_dump() if spec.sorption is not None else None)
