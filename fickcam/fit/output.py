"""What ``fickcam fit`` writes: the scene-ready ``materials:`` block (YAML text with
comments) and the printed table of parameters with their 95 % intervals.

The ``fit:`` record under the material (validated, ignored by the run) holds:
``source`` (the data file), ``interval_95`` (low, high of each value), ``covariance``
of ``diffusivity`` = (ln pre_exponential [ln(m^2/s)], activation_energy [J/mol]) and
of ``saturation`` = (coefficient [%], exponent [1]) as 2x2 SI matrices for Monte
Carlo draws (bivariate normal), where each value came from (data or library), the
ply values of a composite, the non-Fickian conditions and their two-phase rates.
"""
from __future__ import annotations

import numpy as np

from .report import FitReport


def _g(x: float, digits: int = 4) -> str:
    return f"{x:.{digits}g}"


def _matrix(m) -> str:
    return "[" + ", ".join("[" + ", ".join(f"{v:.6g}" for v in row) + "]" for row in np.asarray(m)) + "]"


def _pair(low, high, unit="") -> str:
    unit = f" {unit}" if unit else ""
    return f"[{_g(low)}{unit}, {_g(high)}{unit}]"


def _two_phase_ratios(report: FitReport) -> tuple[float, float]:
    """(D_free / D_Fick, Mm_total / Mm_Fick) at the first non-Fickian condition ((1, 1)
    when Fickian): the two-phase fit's free water diffuses faster than the Fickian fit's
    apparent D, and its total Mm lies above the Fickian plateau."""
    flagged = report.two_phase_fits()
    if not flagged:
        return 1.0, 1.0
    condition, fit = flagged[0]
    return (fit.diffusivity.value / condition.diffusivity.value,
            fit.saturation.value / condition.saturation.value)


def _sorption_lines(report: FitReport, pre_exponential: float, coefficient: float) -> list[str]:
    flagged = report.two_phase_fits()
    if not flagged:
        return []
    condition, fit = flagged[0]
    diffusion, saturation = _two_phase_ratios(report)
    return [f"    # NOT Fickian at {', '.join(report.non_fickian)}. Two-phase (Langmuir) fit at {condition.label}:",
            f"    # free-water D {_g(fit.diffusivity.value)} m^2/s, total Mm {_g(fit.saturation.value)} % there;",
            f"    # above: the Fickian values ({_g(pre_exponential)} m^2/s pre-exponential, coefficient "
            f"{_g(coefficient)} %) times D_free/D_Fick = {_g(diffusion)} and Mm/Mm_Fick = {_g(saturation)},",
            "    # same activation energy and exponent (Carter & Kibler 1978).",
            f"    sorption: {{model: langmuir, binding_rate: {_g(fit.binding_rate.value)} 1/s, "
            f"release_rate: {_g(fit.release_rate.value)} 1/s}}"]


def _uncertainty_lines(d, s, m: dict, to_matrix_d: float, to_matrix_a: float) -> list[str]:
    """``interval_95`` and ``covariance`` of a determined fit (matrix values)."""
    return ["      interval_95:",
            f"        pre_exponential: {_pair(d.first.low * to_matrix_d, d.first.high * to_matrix_d, 'm^2/s')}",
            f"        activation_energy: {_pair(d.second.low / 1e3, d.second.high / 1e3, 'kJ/mol')}",
            f"        coefficient: {_pair(s.first.low * to_matrix_a, s.first.high * to_matrix_a, '%')}",
            f"        exponent: {_pair(s.second.low, s.second.high)}",
            "      covariance:                          # SI, for Monte Carlo draws (bivariate normal)",
            f"        diffusivity: {_matrix(m['diffusivity_covariance'])}   "
            "# (ln pre_exponential, activation_energy [J/mol])",
            f"        saturation: {_matrix(m['saturation_covariance'])}   # (coefficient [%], exponent)"]


def _fit_record(report: FitReport, m: dict) -> list[str]:
    d, s = report.arrhenius, report.saturation
    to_matrix_d, to_matrix_a = 1.0 / report.diffusivity_factor, 1.0 / report.moisture_factor
    lines = ["    fit:                                   # what fickcam fit found (checked, not used by a run)",
             f"      source: {report.source}"]
    bounds = [d.first.low, d.first.high, s.first.low, s.first.high]
    if not (np.all(np.isfinite(bounds)) and np.all(np.isfinite(m["diffusivity_covariance"]))
            and np.all(np.isfinite(m["saturation_covariance"]))):
        lines += ["      # no interval_95 or covariance: D and Mm are NOT determined by these "
                  "weighings (weigh longer)"]
    else:
        lines += _uncertainty_lines(d, s, m, to_matrix_d, to_matrix_a)
    lines += [f"      activation_energy_from: {d.second_from}",
              f"      exponent_from: {s.second_from}"]
    if report.fiber:
        lines += ["      ply:                                 # the coupon (ply) values the data gave",
                  f"        pre_exponential: {_g(d.first.value)} m^2/s",
                  f"        coefficient: {_g(s.first.value)} %",
                  f"        diffusivity_factor: {_g(report.diffusivity_factor)}   # D22 / Dm",
                  f"        moisture_factor: {_g(report.moisture_factor)}   # M_ply / M_matrix"]
    flagged = report.two_phase_fits()
    lines += ["      non_fickian:"] if flagged else []
    lines += [f"        - {{condition: {c.label}, p_value: {l.p_value:.3g}, diffusivity: {_g(l.diffusivity.value)} "
              f"m^2/s, binding_rate: {_g(l.binding_rate.value)} 1/s, release_rate: {_g(l.release_rate.value)} 1/s}}"
              for c, l in flagged]
    return lines


def materials_yaml(report: FitReport) -> str:
    """The ``materials:`` block, ready to paste into a scene.

    Parameters
    ----------
    report : FitReport
        A fit (:func:`fickcam.fit_weight_gain`).

    Returns
    -------
    str
        YAML text with comments; D0 in m^2/s, Ea in kJ/mol, the saturation
        coefficient in %.
    """
    m = report.matrix_values()
    composite = [f"    fiber: {report.fiber}", f"    fiber_volume_fraction: {report.fiber_volume_fraction:g}"] \
        if report.fiber else []
    which = "matrix values (from the ply values below)" if report.fiber else "neat resin values"
    lines = [f"# fickcam fit: {report.name} from {report.source} "
             f"({len(report.specimens)} specimens, {len(report.conditions)} conditions)",
             *[f"# NOTE {n}" for n in report.notes],
             "materials:",
             f"  {report.name}:",
             f'    matrix: "{report.matrix}"', *composite,
             f"    # {which}; D = pre_exponential exp(-activation_energy/(R T)), Mm = coefficient (RH/100)^exponent",
             f"    diffusivity: {{pre_exponential: {_g(m['pre_exponential'] * _two_phase_ratios(report)[0], 6)} m^2/s, "
             f"activation_energy: {_g(m['activation_energy'] / 1e3, 6)} kJ/mol}}",
             f"    saturation: {{coefficient: {_g(m['coefficient'] * _two_phase_ratios(report)[1], 6)} %, exponent: {_g(m['exponent'], 6)}}}",
             *_fit_record(report, m), *_sorption_lines(report, m['pre_exponential'], m['coefficient'])]
    return "\n".join(lines) + "\n"


def _row(label: str, count: int, c) -> str:
    return (f"{label:<22} {count:>3} {c.diffusivity.value:>10.4g} "
            f"{'[' + _g(c.diffusivity.low) + ', ' + _g(c.diffusivity.high) + ']':>23} "
            f"{c.initial_slope_diffusivity:>11.4g} {c.edge_corrected_diffusivity:>10.4g} "
            f"{c.saturation.value:>7.4g} {'[' + _g(c.saturation.low) + ', ' + _g(c.saturation.high) + ']':>17} "
            f"{'yes' if c.at_equilibrium else 'NO':>6}")


def parameter_table(report: FitReport) -> str:
    """Per condition (and below it each of its specimens): D (full series) with its
    interval, D5229 initial slope and edge correction, Mm with its interval and
    equilibrium, the non-Fickian test; then the laws.

    Parameters
    ----------
    report : FitReport
        The fit to print.

    Returns
    -------
    str
        The table (D in m^2/s, Mm in %), one line per row.
    """
    head = (f"{'condition':<22} {'n':>3} {'D m^2/s':>10} {'95 % interval':>23} {'D5229 slope':>11} "
            f"{'edge-corr.':>10} {'Mm %':>7} {'95 % interval':>17} {'equil.':>6} {'Fick':>5}")
    lines = [head, "-" * len(head)]
    by_name = {f.specimens[0]: f for f in report.specimen_fits}
    for c, a in zip(report.conditions, report.anomalies):
        lines.append(_row(c.label, len(c.specimens), c) + f" {'NO' if a.non_fickian else 'yes':>5}")
        if len(c.specimens) > 1:
            lines += [_row(f"  {name}", 1, by_name[name]) for name in c.specimens]
    d, s = report.arrhenius, report.saturation
    law = "law (ply values)" if report.fiber else "law"
    lines += ["", f"{law:<22} {'value':>12} {'95 % interval':>26}  from"]
    for label, estimate, scale, source in (("D0 m^2/s", d.first, 1.0, d.first_from),
                                           ("Ea kJ/mol", d.second, 1e-3, d.second_from),
                                           ("a %", s.first, 1.0, s.first_from),
                                           ("b", s.second, 1.0, s.second_from)):
        lines.append(f"{label:<22} {estimate.value * scale:>12.4g} "
                     f"{_pair(estimate.low * scale, estimate.high * scale):>26}  {source}")
    lines += [f"two-phase at {c.label}: D {_g(l.diffusivity.value)} m^2/s "
              f"{_pair(l.diffusivity.low, l.diffusivity.high)}, gamma {_g(l.binding_rate.value)} 1/s "
              f"{_pair(l.binding_rate.low, l.binding_rate.high)}, beta {_g(l.release_rate.value)} 1/s "
              f"{_pair(l.release_rate.low, l.release_rate.high)}, Mm {_g(l.saturation.value)} %"
              for c, l in report.two_phase_fits()]
    lines += [f"note: {n}" for n in report.notes]
    return "\n".join(lines)
