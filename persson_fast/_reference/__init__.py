"""Slow, obvious NumPy/SciPy twins of the compiled solvers, for tests and benchmarks.

``diffusion`` (Thomas against a banded solve, a theta step, a dense Crank-Nicolson sweep),
``walls`` (kink-to-kink prescribed walls), ``yield_wall`` (two walls), ``separation``,
``gaps``, ``theories``.
"""
