"""The extreme catalogue's marker: ``slow`` scenes (> ~2 s) still run in CI; ``-m "not slow"`` skips them locally."""


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: a scene of the extreme catalogue that takes more than ~2 s")
