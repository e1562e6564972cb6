import pytest

import persson_fast as pf


@pytest.fixture(scope="session", autouse=True)
def _warm_kernels():
    """Compile the kernels once, before any test, so hypothesis deadlines never include it."""
    pf.warmup()
