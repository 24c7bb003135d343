"""The extreme catalogue's marker: ``slow`` scenes (> ~2 s) are left out of the default run (pyproject addopts
``-m "not slow"``) and run in CI (``-m "slow or not slow"``), like the tests in tests/conftest.py's SLOW."""


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: a scene of the extreme catalogue that takes more than ~2 s")
