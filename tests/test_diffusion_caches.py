"""The run's cache (``RunCache``) hands the same arrays to every caller, so they are
read-only: a caller writing into one raises instead of changing what a later plan or solve
reads, and no caller needs a defensive copy. The cache belongs to whoever runs: two runs
share nothing unless they are given the same cache."""
from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
import pytest

import fickcam
from fickcam.diffusion import (CamPlate, DiffusionProblem, Diffusivity, Exposure, Plan, RunCache,
                               solve)
from fickcam.diffusion.exact.series import ROOT_TABLE, bessel_roots, cylinder_short_coefficients
from fickcam.diffusion.forcing.clock import clock_of
from fickcam.diffusion.models.plane import planform_response
from fickcam.diffusion.planform.short_time import outline_chords
from fickcam.diffusion.problem.cache import freeze, size_of
from fickcam.diffusion.problem.sorption import Langmuir, Rate
from fickcam.diffusion.stepping.step_plans import output_ages
from test_sweep_run import small_base

PLATE = CamPlate(np.array([0.0, 12e-3, 12e-3, 0.0]), np.array([0.0, 0.0, 8e-3, 8e-3]), 3e-3)
D = (1e-12, 1e-12, 1e-12)


def assert_read_only(*arrays):
    for array in arrays:
        assert not array.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 0.0


@dataclass(frozen=True)
class Held:
    values: np.ndarray
    pair: tuple


def test_a_cached_value_is_frozen_also_inside_tuples_dicts_and_dataclasses():
    cache = RunCache()
    value = cache.get(("held",), lambda: (np.zeros(3), {"a": np.ones(2)},
                                          Held(np.arange(4.0), (np.eye(2), 1.0))))
    assert_read_only(value[0], value[1]["a"], value[2].values, value[2].pair[0])
    assert cache.get(("held",), lambda: pytest.fail("built again")) is value


def test_the_cache_drops_the_least_recently_used_past_its_budget():
    cache = RunCache(budget=3 * 800)            # three arrays of 100 doubles
    for name in "abc":
        cache.get(name, lambda: np.zeros(100))
    cache.get("a", lambda: pytest.fail("a was dropped early"))   # a is now the most recent
    cache.get("d", lambda: np.zeros(100))
    assert cache.keys() == ["c", "a", "d"] and cache.nbytes == 3 * 800
    cache.get("huge", lambda: np.zeros(10_000))   # over the budget alone: kept, the rest go
    assert cache.keys() == ["huge"]


def test_an_entry_owned_by_an_object_goes_with_it():
    cache = RunCache()

    class Owner:
        pass
    owner = Owner()
    cache.get("reading", lambda: np.zeros(5), owner=owner)
    assert len(cache) == 1
    del owner
    assert len(cache) == 0 and cache.nbytes == 0


def test_threads_asking_for_one_entry_all_get_the_first_stored():
    cache, seen = RunCache(), []
    threads = [threading.Thread(target=lambda: seen.append(cache.get("x", lambda: np.zeros(8))))
               for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(seen) == 8 and all(value is seen[0] for value in seen) and len(cache) == 1


def test_sizes_count_arrays_once_and_views_not_at_all():
    base = np.zeros(10)
    assert size_of((base, base, base[2:], {"b": base})) == 80
    assert freeze([base])[0] is base and not base.flags.writeable


def test_exact_series_tables_are_read_only():
    assert_read_only(bessel_roots(10), bessel_roots(ROOT_TABLE + 1), cylinder_short_coefficients())


def test_the_clock_outline_chords_and_output_ages_are_read_only():
    exposure = Exposure.piecewise([0.0, 86400.0, 2 * 86400.0], [300.0, 320.0], [1.0, 2.0], 0.0,
                                  ramp=[False, True])
    cache = RunCache()
    clock = clock_of(Diffusivity(D, 40e3), exposure, cache)
    assert_read_only(clock.held_rate, clock.cumulative,
                     *outline_chords(PLATE, (1.0, 1.0), 1e-3, cache),
                     output_ages(np.array([0.0, 1e-2, 2e-2]), np.array([5e-3, 3e-2]),
                                 np.array([False, True]), cache=cache))
    assert clock_of(Diffusivity(D, 40e3), exposure, cache) is clock
    assert clock_of(Diffusivity(D, 40e3), exposure, RunCache()) is not clock


def test_a_planform_step_response_is_read_only():
    problem = DiffusionProblem(PLATE, Diffusivity(D, 0.0), Exposure.piecewise([0.0, 1.0], [330.0], [1.0]),
                               [1.0])
    chosen = Plan("plane", 0, 0, "", 0.0, steps_per_doubling=4, finest=0.2, growth=1.4)
    _, response, _ = planform_response(problem, chosen, 1.0, 1e-6, RunCache())
    assert_read_only(response.nodes, response.mean, response.layer)


def test_a_two_phase_plate_result_reads_its_cached_refinement_without_a_copy():
    """The result's arrays are the cached refinement's histories, read-only."""
    rate = Rate(0.1 * np.pi ** 2 * D[0] / PLATE.thickness ** 2)
    exposure = Exposure.piecewise([0.0, 2e6], 300.0, [1.0], 0.0)
    times = np.linspace(0.0, 2e6, 5)
    result = solve(PLATE, Diffusivity(D, 0.0), exposure, times, accuracy=1e-2,
                   sorption=Langmuir(rate, rate), model="plane")
    assert_read_only(result.mean, result.surface, result.bound)


def test_two_runs_share_no_cache_unless_given_one():
    """Each run makes its own cache (nothing kept between runs by the process); runs given
    one cache share its entries, with the same numbers."""
    scene = fickcam.load_scene(__import__("yaml").safe_load(small_base()))
    shared = RunCache()
    first = fickcam.run(scene, cache=shared)
    entries, hits, misses = len(shared), shared.hits, shared.misses
    kept = set(shared.keys())
    assert entries > 0
    alone = fickcam.run(scene)           # a fresh cache: the shared one is not touched
    assert (len(shared), shared.hits, shared.misses) == (entries, hits, misses)
    again = fickcam.run(scene, cache=shared)
    assert shared.hits > hits   # (each run's climate is its own: only its clock is new)
    assert {key[0] for key in set(shared.keys()) - kept} <= {"rescaled clock"}
    for other in (alone, again):
        assert np.array_equal(other["moisture_content"], first["moisture_content"])


def test_a_run_cache_is_freed_with_its_run():
    """Entries owned by objects the cache itself holds (a record's readings) keep no
    reference to the cache from outside: a dropped cache is collected."""
    import gc
    import weakref
    from functools import partial

    cache = RunCache()

    class Owner:
        def __init__(self, cache):
            self.cache = cache
    owner = cache.get("owner", partial(Owner, cache))
    cache.get("reading", partial(np.zeros, 5), owner=owner)
    gone = weakref.ref(cache)
    del cache, owner
    gc.collect()
    assert gone() is None
