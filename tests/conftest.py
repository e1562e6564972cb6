import pytest

import persson_fast as pf


@pytest.fixture(scope="session", autouse=True)
def _warm_kernels():
    """Compile the kernels once, before any test, so hypothesis deadlines never include it."""
    pf.warmup()


@pytest.fixture(autouse=True)
def _signal_handlers_restored():
    """Each test starts with the handlers of SIGINT and SIGTERM the session had: a test that
    runs the command line in-process through its exit path (``cli.run``: a second Ctrl-C is
    ignored while the process exits) must not leave SIGINT ignored in this process, where the
    child processes of later tests would inherit it."""
    import signal

    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    yield
    for s, handler in before.items():
        if signal.getsignal(s) is not handler:
            signal.signal(s, handler)
