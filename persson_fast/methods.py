"""The registry of solution methods (a plain dict, as scipy's ``METHODS``)."""
from __future__ import annotations

METHODS = {
    "analytic": {
        "description": "closed form: method of images (no adhesion) or a linearly moving wall",
        "adhesion": False,
        "order": None,
    },
    "cn": {
        "description": (
            "Crank-Nicolson on a similarity-mapped grid with Rannacher damping after wall jumps, "
            "Richardson-extrapolated (h, dt) -> (h/2, dt/2)"
        ),
        "adhesion": True,
        "order": 4,
    },
    "auto": {
        "description": "the cheapest method that meets rtol for the scene (analytic where it applies)",
        "adhesion": True,
        "order": None,
    },
}


def check_method(method: str) -> str:
    """Return the canonical method name or raise a ValueError listing the valid ones."""
    if not isinstance(method, str) or method.lower() not in METHODS:
        valid = ", ".join(repr(m) for m in METHODS)
        raise ValueError(f"method must be one of {valid}; got method = {method!r}")
    return method.lower()
