import os

import pytest
from hypothesis import HealthCheck, settings

# Deterministic in CI (.ci/run passes --hypothesis-profile=ci; the variable CI picks it
# too); random locally, so that new counter-examples keep turning up.
settings.register_profile("ci", derandomize=True, max_examples=60, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", max_examples=60, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci" if os.environ.get("CI") else "dev")


@pytest.hookimpl(tryfirst=True)  # before -m "not slow" deselects
def pytest_collection_modifyitems(config, items):
    """A test that asks for a longer timeout than the default takes minutes: it is slow,
    whether or not it is marked so itself."""
    default = float(config.getini("timeout") or 0.0)
    for item in items:
        marker = item.get_closest_marker("timeout")
        if marker is not None and marker.args and float(marker.args[0]) > default:
            item.add_marker(pytest.mark.slow)
