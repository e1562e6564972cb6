"""``python -m persson_fast.cli``: the ``persson-fast`` command."""
from .main import run

if __name__ == "__main__":
    run()
