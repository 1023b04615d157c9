import os

import pytest
from hypothesis import HealthCheck, settings

# The same examples on every run, wherever it runs (the README's plain ``python -m pytest``
# and CI alike): a test that fails, fails again. ``--hypothesis-profile=explore`` draws new
# examples each run, so that new counter-examples keep turning up while developing.
settings.register_profile("ci", derandomize=True, database=None, max_examples=60,
                          deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", max_examples=60, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci")


@pytest.hookimpl(tryfirst=True)  # before -m "not slow" deselects
def pytest_collection_modifyitems(config, items):
    """A test that asks for a longer timeout than the default takes minutes: it is slow,
    whether or not it is marked so itself."""
    default = float(config.getini("timeout") or 0.0)
    for item in items:
        marker = item.get_closest_marker("timeout")
        if marker is not None and marker.args and float(marker.args[0]) > default:
            item.add_marker(pytest.mark.slow)


#: The BLAS libraries' thread counts, one thread each.
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def pytest_configure(config):
    """BLAS on one thread in every test process (unless the caller chose otherwise): the
    tests run one worker a core, and a worker's second BLAS thread only waits for a core
    the other worker holds, spinning. Set before the workers start (they inherit it) and
    before the tests import numpy."""
    for name in BLAS_THREADS:
        os.environ.setdefault(name, "1")
