"""Singh & Sanyal's three four-bars shortened two ways, for the validation page.

    python benchmarks/singh2016_compensation.py    # writes benchmarks/results/singh2016_compensation.json

Singh, V. & Sanyal, S. (2016), four-bar links of neat resin under a hygrothermal
environment: R914 links at a moisture uptake of 7 % and a temperature rise of 95 K, steel
frame. Each link is made shorter so that it grows back to its design length in service:
the paper's way, L (1 - eps), and the correct one, L / (1 + eps)
(``fickcam.compensation.core.made_value``). The table gives both in mm, how short the
paper's links are in service (L eps^2) and the largest rocker angle error over a crank
turn: uncompensated, the paper's way and the correct way.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from fickcam.compensation.core import made_value
from fickcam.linkage.positions import continuous, positions

RESULT = Path(__file__).resolve().parent / "results" / "singh2016_compensation.json"
DT, DM = 95.0, 7.0                 # K, % moisture (the paper's Table 4 equilibrium)
ALPHA, BETA = 62.6e-6, 3.02e-3     # R914: wet expansion [1/K], swelling [1/%M] (Table 4)
STEEL_ALPHA = 12.0e-6              # steel frame [1/K]
STRAINS = np.array([ALPHA * DT + BETA * DM] * 3 + [STEEL_ALPHA * DT])  # crank, coupler, rocker, frame
CASES = {"case 1": (5.0, 125.0, 125.0, 120.0), "case 2": (115.0, 120.0, 120.0, 120.0),
         "figs 4-5": (100.0, 160.0, 160.0, 200.0)}  # a, b, c, d [mm] (the paper's sec. V)
CRANK = np.radians(np.arange(0.0, 360.0, 0.5))


def rocker_error(made_mm, design_mm) -> float:
    """Largest |theta4 - theta4,design| [deg] over a crank turn, the made links in service."""
    aged = positions(*(np.asarray(made_mm) * (1 + STRAINS) * 1e-3), CRANK)[1]
    dry = positions(*(np.asarray(design_mm) * 1e-3), CRANK)[1]
    return float(np.degrees(np.max(np.abs(continuous(aged - dry)))))


def row(case: str, design) -> list[str]:
    """One linkage: design, paper's and correct lengths (crank / coupler, rocker / frame)."""
    design = np.asarray(design)
    paper = design * (1 - STRAINS)
    correct = np.array([made_value(length, np.array([strain]))
                        for length, strain in zip(design, STRAINS)])
    short_um = (design - paper * (1 + STRAINS)) * 1e3
    keep = [0, 1, 3]  # the coupler and the rocker are equal in every case

    def lengths(values, form):
        return " / ".join(f"{values[k]:{form}}" for k in keep)

    errors = [rocker_error(made, design) for made in (design, paper, correct)]
    return [case, lengths(design, "g"), lengths(paper, ".5f"), lengths(correct, ".5f"),
            lengths(short_um, ".1f") + " µm",
            f"{errors[0]:.2f}° / {errors[1]:.3f}° / {errors[2]:.1e}°"]


def main() -> None:
    from stamp import write_result

    load = os.getloadavg()[0]
    table = {"columns": ["linkage", "design: crank / coupler, rocker / frame", "paper: L (1 − ε)",
                         "correct: L / (1 + ε)", "paper short in service",
                         "rocker error: uncompensated / paper / correct"],
             "rows": [row(case, design) for case, design in CASES.items()]}
    for line in table["rows"]:
        print(" | ".join(line))
    write_result(RESULT, "Singh & Sanyal's four-bars shortened the paper's way and the correct way",
                 "python benchmarks/singh2016_compensation.py", {"singh2016": table}, load)


if __name__ == "__main__":
    main()
