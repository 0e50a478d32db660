"""Set-up that tests in several files share, made once per test process (each
pytest-xdist worker makes its own, so nothing is shared between processes)."""
from pathlib import Path

import pytest

import fickcam

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


def run_without_foreign_warnings(path):
    """``fickcam.run(path)``, failing on any warning a user would see but a FickcamWarning
    (numpy's ``All-NaN slice``, a RuntimeWarning, matplotlib's, tqdm's): Python's default
    filters (deprecations hidden outside ``__main__``), every occurrence recorded."""
    import warnings

    with warnings.catch_warnings(record=True) as seen:
        warnings.resetwarnings()
        warnings.simplefilter("always")
        for category in (DeprecationWarning, PendingDeprecationWarning, ImportWarning,
                         ResourceWarning):
            warnings.filterwarnings("ignore", category=category)
        result = fickcam.run(path)
    foreign = [f"{w.category.__name__}: {w.message} ({w.filename}:{w.lineno})" for w in seen
               if not issubclass(w.category, fickcam.FickcamWarning)]
    assert not foreign, foreign
    return result


@pytest.fixture(scope="session")
def example_result():
    """``configs/NAME.yaml`` run as ``fickcam.run`` runs it, once per test process: a
    function NAME -> a copy of its result (the test may change its copy)."""
    cache = {}

    def result(name: str):
        if name not in cache:
            cache[name] = run_without_foreign_warnings(CONFIGS / f"{name}.yaml")
        return cache[name].copy(deep=True)

    return result
