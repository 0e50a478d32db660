"""Singh & Sanyal 2016 (four-bar links of neat resin under a hygrothermal environment) end
on "compensating it by accordingly shortening overall dimension of each link i.e. crank,
coupler and rocker". Its three four-bars, R914 links at dm = 7 % (Table 4's equilibrium moisture)
and dT = 95 degC, steel frame, each link shortened two ways:

- the paper's convention: shorten by the growth of eq. 13, dL = L (alpha dT + beta dm),
  taken on the design length: L_made = L (1 - eps). (Its printed eq. 14,
  a_1 = a (alpha dT + beta dm), read literally, would have the link made a/eps, 37 times
  longer: a slip of the printed equation.)
- the correct one: the made link grows by its own strain, L_made (1 + eps) = L, so
  L_made = L / (1 + eps) (fickcam.compensation.core.made_value).

The paper's way leaves every link short by L eps^2 in service (0.073 mm on the 100 mm
crank) and the rocker off by a few hundredths of a degree."""
import numpy as np
import pytest

from fickcam.compensation.core import made_value
from fickcam.linkage.positions import continuous, positions

DT, DM = 95.0, 7.0
ALPHA, BETA = 62.6e-6, 3.02e-3   # R914, Singh & Sanyal 2016 Table 4 (wet alpha, 1/K; beta, 1/%M)
STEEL_ALPHA = 12.0e-6            # 1/K, fickcam/data/materials.yaml
RESIN_STRAIN = ALPHA * DT + BETA * DM   # eqs. 11-13
FRAME_STRAIN = STEEL_ALPHA * DT         # eq. 14, metal frame
CASES = {"case 1": (5.0, 125.0, 125.0, 120.0), "case 2": (115.0, 120.0, 120.0, 120.0),
         "figs 4-5": (100.0, 160.0, 160.0, 200.0)}  # a, b, c, d in mm (sec. V)
STRAINS = np.array([RESIN_STRAIN] * 3 + [FRAME_STRAIN])
THETA2 = np.radians(np.arange(0.0, 360.0, 0.5))


def shortened(lengths):
    """(paper's convention, correct) made lengths in mm."""
    lengths = np.asarray(lengths)
    paper = lengths * (1 - STRAINS)
    correct = np.array([made_value(L, np.array([e])) for L, e in zip(lengths, STRAINS)])
    return paper, correct


def rocker_error(made, design):
    """Largest |theta4 - theta4,design| (deg) over the crank turn, made links in service."""
    aged = positions(*(np.asarray(made) * (1 + STRAINS) * 1e-3), THETA2)[1]
    dry = positions(*(np.asarray(design) * 1e-3), THETA2)[1]
    return float(np.degrees(np.max(np.abs(continuous(aged - dry)))))


def table():
    """Rows (case, link, design, paper, correct) in mm: the side-by-side table."""
    rows = []
    for case, lengths in CASES.items():
        paper, correct = shortened(lengths)
        for link, d, p, c in zip(("crank", "coupler", "rocker", "frame"), lengths, paper, correct):
            rows.append((case, link, d, p, c))
    return rows


def test_correct_shortening_restores_every_design_length_in_service():
    for lengths in CASES.values():
        _, correct = shortened(lengths)
        assert np.allclose(correct * (1 + STRAINS), lengths, rtol=1e-14)


def test_papers_shortening_leaves_each_link_short_by_length_times_strain_squared():
    for lengths in CASES.values():
        paper, _ = shortened(lengths)
        assert np.allclose(paper * (1 + STRAINS) - lengths, -np.asarray(lengths) * STRAINS ** 2,
                           rtol=1e-12)


def test_shortened_lengths_of_the_figure_4_linkage():
    """a = 100, b = c = 160, d = 200 mm: eps = 62.6e-6 x 95 + 3.02e-3 x 7 = 0.027087."""
    assert RESIN_STRAIN == pytest.approx(0.027087, abs=1e-6)
    paper, correct = shortened(CASES["figs 4-5"])
    assert correct == pytest.approx([97.362736, 155.780377, 155.780377, 199.772260], abs=1e-6)
    assert paper == pytest.approx([97.291300, 155.666080, 155.666080, 199.772000], abs=1e-6)


@pytest.mark.parametrize("case", list(CASES))
def test_rocker_in_service_exact_when_correct_and_a_strain_fraction_off_with_the_paper(case):
    design = CASES[case]
    paper, correct = shortened(design)
    uncompensated = rocker_error(design, design)
    assert rocker_error(correct, design) < 1e-9 * max(uncompensated, 1.0)
    assert 0 < rocker_error(paper, design) < 2 * RESIN_STRAIN * uncompensated
