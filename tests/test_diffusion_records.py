"""Long climate records on the exact paths: the tabulated Duhamel sum
(diffusion/superposition/tabulated.py) against Duhamel's panels over the closed-form step
responses, and a solid disc under a week
of Greensboro's TMY3 year against an independent modal solution (each mode advanced
exactly; tau from a fine trapezoid rule)."""
import numpy as np
import pytest

from fickcam.cli.checkout import benchmark
from fickcam.diffusion import Bar, Diffusivity, Disc, Exposure, Sheet, plan, solve
from fickcam.diffusion.models.analytic import exact_history, record_history

DAY = 86400.0
RECORDS = benchmark("climate_records")  # the modal reference of benchmarks/
modal_disc_mean = RECORDS.modal_disc_mean
ARRHENIUS = Diffusivity((2e-5, 2e-5, 1e-5), 40e3)


def mixed_history():
    """Held steps and ramps, with the temperature ramping 300 -> 330 K in a day."""
    edges = np.array([0, 2, 3, 5, 6, 9, 10, 14]) * DAY
    temperatures = [300, 330, 330, 310, 320, 300, 340.0]
    moisture = [1.0, 2.0, 0.5, 0.5, 1.5, 0.2, 1.8]
    ramp = np.array([0, 1, 0, 1, 0, 1, 1], bool)
    return Exposure.piecewise(edges, temperatures, moisture, 0.1, ramp), edges


@pytest.mark.parametrize("geometry", [Sheet(2e-3), Disc(0.02, 0.005), Bar(0.01, 0.008, 0.003)],
                         ids=["sheet", "disc", "bar"])
def test_tabulated_sum_matches_duhamel_on_steps_and_ramps_within_its_estimate(geometry):
    history, edges = mixed_history()
    times = np.sort(np.concatenate([np.linspace(0, 14 * DAY, 29), edges[1:-1] + 60.0]))
    swing = 1.7  # largest |Ms - M0|
    reference = exact_history(geometry, ARRHENIUS, history, times)
    result, estimate, _ = record_history(geometry, ARRHENIUS, history, times, 3e-4)
    assert estimate <= 3e-4
    for key in ("mean", "surface"):
        assert np.max(np.abs(result[key] - reference[key])) <= estimate * swing


def test_steps_stay_exact_just_after_they_happen():
    """A step reads the tabulated step response itself (short-time law below the table):
    a second and a minute after each step the mean and the layer still match Duhamel."""
    history, edges = mixed_history()
    times = np.concatenate([[0.0], edges[[2, 4]] + 1.0, edges[[2, 4]] + 60.0])
    reference = exact_history(Sheet(2e-3), ARRHENIUS, history, times)
    result, estimate, _ = record_history(Sheet(2e-3), ARRHENIUS, history, times, 1e-5)
    assert np.max(np.abs(result["surface"] - reference["surface"])) <= estimate * 1.7


def greensboro_weeks(weeks, initial_moisture=0.0):
    pytest.importorskip("pvlib")
    return RECORDS.greensboro(24 * 7 * weeks + 1, initial_moisture)


def nylon_moisture(temperature, humidity):
    return RECORDS.isotherm(temperature, humidity)


def record_swing(environment) -> float:
    """The largest |Ms - M0| over the record's rows: what ``accuracy`` is relative to."""
    edges = environment.change_times
    values = nylon_moisture(environment.temperature(edges), environment.relative_humidity(edges))
    return float(np.max(np.abs(values - environment.initial_moisture)))


def test_solid_disc_under_a_week_of_a_tmy3_record_matches_an_independent_modal_solution():
    first = greensboro_weeks(1)
    start = float(nylon_moisture(first.temperature(0.0), first.relative_humidity(0.0)))
    environment = greensboro_weeks(1, start)
    # a disc that follows the weather within days, so that the reference's modes suffice
    disc, diffusivity = Disc(0.01, 0.004), Diffusivity((4e-2,) * 3, 50e3)
    exposure = environment.exposure(nylon_moisture)
    times = np.linspace(0.0, environment.end, 15)
    chosen = plan(disc, diffusivity, exposure, times, accuracy=1e-4)
    assert chosen.model == "analytic" and "linear in the rows" in chosen.reason
    result = solve(disc, diffusivity, exposure, times, accuracy=1e-4)
    reference = modal_disc_mean(disc, diffusivity, environment, times)
    assert result.error_estimate <= 1e-4
    # the reference errs by about 3e-6 of the swing (against 120 x 60 modes, 64 sub-steps)
    assert np.max(np.abs(result.mean - reference)) <= 1e-4 * record_swing(environment)


def test_record_cost_grows_linearly_with_its_rows():
    """Eight times the rows costs well under 16 times (the table is set by the accuracy, not
    by the length; the sum is one pass over the rows)."""
    import time

    def cost(weeks):
        environment = greensboro_weeks(weeks)
        exposure = environment.exposure(nylon_moisture)
        start = time.process_time()
        record_history(Disc(0.023, 0.01), Diffusivity((3.85e-4,) * 3, 50e3), exposure,
                       np.linspace(0, environment.end, 12), 1e-3)
        return time.process_time() - start

    cost(1)  # warm-up
    assert cost(8) < 16 * cost(1)


def circular_plate(radius, thickness):
    from fickcam.diffusion import CamPlate

    angle = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
    return CamPlate(radius * np.cos(angle), radius * np.sin(angle), thickness)


def test_plane_model_under_three_weeks_of_a_tmy3_record_matches_the_exact_modal_disc():
    """The plane path (planform mesh x exact sheet, superposed by the tabulated sum) on a
    CamPlate that is a full circle, against the finite cylinder's modes advanced exactly
    through the record (``modal_disc_mean`` of ``benchmarks/climate_records.py``: errs by a
    few 1e-6)."""
    first = greensboro_weeks(3)
    start = float(nylon_moisture(first.temperature(0.0), first.relative_humidity(0.0)))
    environment = greensboro_weeks(3, start)
    # saturates within days: the planform response reaches the mesh (not the expansion alone)
    disc, diffusivity = Disc(0.01, 0.004), Diffusivity((0.4,) * 3, 50e3)
    exposure = environment.exposure(nylon_moisture)
    times = np.linspace(0.0, environment.end, 15)
    result = solve(circular_plate(0.01, 0.004), diffusivity, exposure, times, accuracy=1e-4)
    reference = modal_disc_mean(disc, diffusivity, environment, times)
    assert result.model == "plane" and result.cells > 0
    assert result.error_estimate <= 1e-4
    assert np.max(np.abs(result.mean - reference)) <= 1e-4 * record_swing(environment)


def test_fields_on_a_record_take_the_tabulated_sum_and_match_duhamel():
    """Exact fields of a sheet over 33 hourly rows: the tabulated sum (one table, one matrix
    product) against Duhamel's panels, within the requested accuracy of the swing."""
    from fickcam.diffusion.models.analytic import exact_history_field

    week, rows = greensboro_weeks(1), 34
    edges = week.change_times[:rows]
    environment = type(week).from_samples(edges, week.temperature(edges),
                                          week.relative_humidity(edges), 296.15, 0.0)
    sheet, diffusivity = Sheet(0.004), Diffusivity((0.4,) * 3, 50e3)
    exposure = environment.exposure(nylon_moisture)
    times = np.linspace(0.0, environment.end, 4)
    result = solve(sheet, diffusivity, exposure, times, accuracy=1e-3, store_fields=True)
    reference = exact_history_field(sheet, diffusivity, exposure, times,
                                    {"z": result.cell_coordinates["z"]})
    swing = float(np.max(nylon_moisture(0, environment.relative_humidity(edges))))
    assert np.max(np.abs(result.fields - reference)) <= 1e-3 * swing


def test_a_plane_solve_repeated_on_a_record_reuses_its_tables_and_a_thicker_part_does_not():
    """A limit search re-solves a part at more ageing times: the step-response tables of a
    record are taken from the first solve of the run (same results to the last bit, nothing
    tabulated again); a part of another thickness never reads them."""
    from fickcam.diffusion import RunCache

    environment = greensboro_weeks(1)
    diffusivity = Diffusivity((0.4,) * 3, 50e3)
    exposure = environment.exposure(nylon_moisture)
    times = np.linspace(0.0, environment.end, 6)
    cache = RunCache()

    def tables():
        return {key for key in cache.keys() if key[0] == "duhamel table"}
    first = solve(circular_plate(0.01, 0.004), diffusivity, exposure, times, accuracy=1e-3,
                  cache=cache)
    kept = tables()
    assert kept  # the record's mean and contact-layer tables
    again = solve(circular_plate(0.01, 0.004), diffusivity, exposure, times, accuracy=1e-3,
                  cache=cache)
    assert np.array_equal(first.mean, again.mean) and np.array_equal(first.surface, again.surface)
    assert tables() == kept
    thicker = solve(circular_plate(0.01, 0.005), diffusivity, exposure, times, accuracy=1e-3,
                    cache=cache)
    assert tables() - kept  # its own tables
    alone = solve(circular_plate(0.01, 0.005), diffusivity, exposure, times, accuracy=1e-3)
    assert np.array_equal(thicker.mean, alone.mean)  # as if no thinner tables were kept


def test_a_plane_result_extended_to_new_times_equals_a_solve_at_both_sets_of_times():
    """The limit search's ``extend``: the stored solve read at new times inside its span
    (nodes gained, tables and plan kept) gives what a solve at the stored and the new
    times together gives there, to round-off; the stored rows are kept as they were."""
    environment = greensboro_weeks(1)
    diffusivity = Diffusivity((0.4,) * 3, 50e3)
    exposure = environment.exposure(nylon_moisture)
    plate, times = circular_plate(0.01, 0.004), np.linspace(0.0, environment.end, 6)
    stored = solve(plate, diffusivity, exposure, times, accuracy=1e-3)
    new = np.array([0.37, 2.51, 4.9]) * 86400.0
    both = np.union1d(times, new)
    extended = stored.extend(both)
    together = solve(plate, diffusivity, exposure, both, accuracy=1e-3)
    rows = np.searchsorted(both, new)
    assert np.array_equal(extended.times, both)
    scale = float(np.max(np.abs(together.mean)))
    for name in ("mean", "surface"):
        assert np.allclose(getattr(extended, name)[rows], getattr(together, name)[rows],
                           rtol=0, atol=64 * np.finfo(float).eps * scale)
        kept = np.searchsorted(both, times)
        assert np.array_equal(getattr(extended, name)[kept], getattr(stored, name))


def bins_ends_of_every_age(change, outputs, ramp):
    """The least and the largest distinct age of each 1/64-decade bin of every output's
    ages to every source (a step's start, 17 points across a ramp): the definition."""
    from fickcam.diffusion.stepping.step_plans import AGES_PER_DECADE

    edges = np.unique(np.concatenate(
        [change[:1], change[1:-1][~ramp[1:]], change[-1:]]
        + [np.linspace(a, b, 17) for a, b, r in zip(change[1:-1], change[2:], ramp[1:]) if r]))
    ages = np.unique((outputs[:, None] - edges[None, :]).ravel())
    ages = ages[ages > 0]
    bins = np.floor(np.log10(ages) * AGES_PER_DECADE)
    return np.unique(np.concatenate([ages[bins == b][[0, -1]] for b in np.unique(bins)]))


def test_output_ages_of_a_long_record_are_its_ages_least_and_largest_per_bin():
    """Thinned row by row (no sort of every output x source age), the output ages are still
    exactly the least and the largest distinct age of each 1/64-decade bin of all of them."""
    from fickcam.diffusion.stepping.step_plans import output_ages

    rng = np.random.default_rng(7)
    change = np.concatenate([[0.0], np.cumsum(rng.uniform(0.2, 1.0, 3000) * 1e-3)])
    ramp, outputs = rng.random(3000) < 0.8, np.linspace(0.0, change[-1], 9)
    assert np.array_equal(output_ages(change, outputs, ramp),
                          bins_ends_of_every_age(change, outputs, ramp))


def test_output_ages_keep_each_bins_least_and_largest_age_with_clustered_sources():
    """Sources in tight clusters (many bins' edges between two neighbours, and many
    sources within one bin) and 60 outputs: still the least and the largest distinct age
    of every 1/64-decade bin of all the outputs' ages (each output's bins' ends found by
    bisection, the bins read only either side of each edge)."""
    from fickcam.diffusion.stepping.step_plans import output_ages

    rng = np.random.default_rng(11)
    centres = np.sort(rng.uniform(0.0, 50.0, 120))
    change = np.unique(np.concatenate(
        [[0.0], (centres[:, None] + rng.uniform(0.0, 1e-6, (120, 30))).ravel(), [50.0]]))
    ramp = rng.random(change.size - 1) < 0.5
    outputs = np.linspace(0.0, 50.0, 60)
    assert np.array_equal(output_ages(change, outputs, ramp),
                          bins_ends_of_every_age(change, outputs, ramp))
