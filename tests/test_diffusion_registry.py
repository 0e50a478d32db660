"""The registry of routes: each law's routes say for themselves whether they take a problem
(and why not, in words a user can read), and ``auto`` takes the first that does, in the
order of ``ROUTES``."""
from __future__ import annotations

import numpy as np
import pytest

from fickcam.diffusion import (Bar, CamPlate, DiffusionProblem, Diffusivity, Disc, Exposure,
                               Sheet)
from fickcam.diffusion.dispatch import BAR_CORRECTED_FROM, ROUTES, law_of, route_of
from fickcam.diffusion.problem.sorption import ConcentrationDependent, Langmuir, Rate
from fickcam.errors import InputError

D = 1e-12
PLATE = CamPlate(np.array([0.0, 12e-3, 12e-3, 0.0]), np.array([0.0, 0.0, 8e-3, 8e-3]), 3e-3)
WET = Exposure.piecewise([0.0, 2e6], 300.0, [1.5], 0.0)
TIMES = np.linspace(0.0, 2e6, 5)
TWO_PHASE = Langmuir(Rate(1e-6), Rate(1e-6))


def problem(part, sorption=None, model="auto", accuracy=1e-3) -> DiffusionProblem:
    return DiffusionProblem(part, Diffusivity((D,) * 3, 0.0), WET, TIMES, accuracy, model,
                            sorption=sorption)


def test_each_law_has_its_routes_and_fick_one():
    assert [law_of(s) for s in (None, TWO_PHASE, ConcentrationDependent(1.5, exponent=2.0))] == [
        "fick", "langmuir", "nonlinear"]
    assert [r.name for r in ROUTES["langmuir"]] == ["two-phase modes", "two-phase planform",
                                                    "two-phase mesh"]


def test_two_phase_follows_the_fickian_model_of_the_part():
    assert route_of(problem(Sheet(2e-3), TWO_PHASE)).name == "two-phase modes"
    assert route_of(problem(PLATE, TWO_PHASE)).name == "two-phase planform"
    assert route_of(problem(PLATE, TWO_PHASE, model="solid")).name == "two-phase mesh"
    assert route_of(problem(Disc(0.02, 0.004, 0.008), TWO_PHASE)).name == "two-phase mesh"
    planform = ROUTES["langmuir"][1]
    assert planform.refusal(problem(Sheet(2e-3), TWO_PHASE)) == (
        "the part's Fickian model is analytic")


def test_concentration_dependent_d_takes_fick_where_f_is_one_number_else_the_product():
    constant = ConcentrationDependent(1.5, exponent=0.0)
    varying = ConcentrationDependent(1.5, exponent=2.0)
    assert route_of(problem(PLATE, constant)).name == "Fick with D f"
    assert route_of(problem(PLATE, varying)).name == "corrected product"
    assert route_of(problem(PLATE, varying, model="solid")).name == "swept mesh"
    assert route_of(problem(Sheet(2e-3), varying)).name == "swept mesh"
    bar = problem(Bar(6e-3, 4e-3, 2e-3), varying, accuracy=3 * BAR_CORRECTED_FROM)
    assert route_of(bar).name == "swept mesh"
    assert ROUTES["nonlinear"][1].refusal(bar) == (
        f"a Bar's octant is cheaper above accuracy {BAR_CORRECTED_FROM:g}")


def test_a_route_no_law_has_says_why_in_one_line():
    with pytest.raises(InputError, match="plane has no concentration-dependent form"):
        route_of(problem(PLATE, ConcentrationDependent(1.5, exponent=2.0), model="plane"))


def test_the_model_names_are_the_registrys():
    # the scene checks ``diffusion.model`` against the light list, the solve uses the registry
    from fickcam.diffusion.dispatch import FICK_MODELS
    from fickcam.diffusion.problem.definition import MODELS

    assert MODELS == ("auto", *FICK_MODELS)


@pytest.mark.parametrize("accuracy", [0.0, -1e-3, 0.5, 1.0, float("nan")])
def test_an_accuracy_outside_the_range_is_refused_in_one_line(accuracy):
    from fickcam.diffusion import solve_problem

    with pytest.raises(InputError, match=r"^diffusion.accuracy .*must lie in \(0, 0.1\]"):
        solve_problem(problem(Sheet(1e-3), accuracy=accuracy))
