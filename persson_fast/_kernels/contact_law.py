"""Compiled evaluation of a tabulated pressure-separation law p(u), K(u) (no adhesion).

A law is the tuple ``(v, y, dy, z, dz)`` of five (n,) float64 arrays that
:func:`persson_fast.separation.contact_law.contact_law` builds: v_i = ln u_i ascending (u in m),
y_i = ln p_i (p in Pa, descending) with the exact slopes dy/dv = -u K_i/p_i, and
z_i = ln K_i (K in Pa/m) with the exact slopes dz/dv. Between nodes y(v) and z(v) are cubic
Hermite interpolants (y monotone: the builder checks the Fritsch-Carlson conditions on
every interval). ln p and ln K are smooth in ln u at both ends (ln p ~ c - u/u0 at small p,
ln u ~ -p^2/(4 G1) at large p), which they are not in u. Beyond the largest separation
(the small-pressure end) ln p and ln K continue linearly in u with the end slope -K/p:
the exact law p ~ exp(-u/u0), K = p/u0 there, to the builder's tolerance; below the
smallest separation (pressures above the table) they continue linearly in v, and the
status says ``LAW_EXTRAPOLATED``.

Status: 0 ok; ``BAD_LAW`` (the table breaks a rule of :func:`law_status`: p, K and u are
NaN); ``BAD_SEPARATION`` (u not finite or <= 0: p and K are NaN); ``LAW_EXTRAPOLATED`` (u
below the table: p and K are a continuation, not a result).

Every public function here checks the whole table first (:func:`law_status`: one pass over
the five arrays, no allocation), so a table that was cut, reversed, mixed up (any permutation
of its five arrays) or holds a NaN gives NaN and ``BAD_LAW``, never a number and never a
read past the end of an array; arrays other than 1-D float64 do not compile. The
check is O(n) per call (n nodes): for many separations at once, :func:`law_sweep` checks the
table once. The builder's own refinement loop, whose intermediate tables need not be
monotone yet, uses :func:`law_sweep_unchecked`.
"""
from __future__ import annotations

import math

import numpy as np
from numba.core import types
from numba.core.errors import TypingError
from numba.extending import overload

from .._jit import njit_serial
from .status import BAD_INPUT, BAD_LAW, BAD_PRESSURE, BAD_SEPARATION, LAW_EXTRAPOLATED, OK

#: ln u and ln p of a table lie within the logarithms of positive doubles
LOG_LOW = -746.0
LOG_HIGH = 710.0
#: relative slack of the kernel's Fritsch-Carlson test against the builder's (the two
#: forms of one inequality differ by a few roundings)
MONOTONE_SLACK = 1e-12
#: slack of the identity ln(-dy) = v + z - y (d ln p/d ln u = -u K/p), relative to
#: 1 + |v| + |y| + |z|: the builder's tables meet it to ~1e-16 (a few roundings of the
#: logarithms); a float32 rounding of any of the four arrays breaks it by ~1e-8
IDENTITY_SLACK = 1e-12
#: the identity is checked at this many nodes, evenly spread from the first to the last (a
#: logarithm each; at every node it would cost ~10 ns per node, 5x the rest of the check)
IDENTITY_NODES = 5
#: what a table's arrays must be; a compiled law_* function given anything else does not
#: compile (numba raises a TypingError with this message)
TABLE_TYPE_RULE = ("table: the contact law's table must be a tuple of five 1-D float64 arrays "
                   "(ContactLaw.table as contact_law builds it: ln u [ln m], ln p [ln Pa], "
                   "d ln p/d ln u [-], ln K [ln Pa/m], d ln K/d ln u [-])")


def table_type_problem(law) -> str | None:
    """None when ``law`` is a tuple of five 1-D float64 arrays, else what it is instead."""
    if not isinstance(law, tuple) or len(law) != 5:
        return (f"a {type(law).__name__} of length {len(law)}" if hasattr(law, "__len__")
                else f"a {type(law).__name__}")
    bad = [f"{k}: {a.dtype} of {a.ndim} dimensions" if isinstance(a, np.ndarray)
           else f"{k}: a {type(a).__name__}" for k, a in enumerate(law)
           if not (isinstance(a, np.ndarray) and a.ndim == 1 and a.dtype == np.float64)]
    return f"arrays {', '.join(bad)}" if bad else None


def _table_types(law):
    """Refuse a table that is not a tuple of five 1-D float64 arrays (TypeError).

    The plain-Python twin (``NUMBA_DISABLE_JIT=1``) of the compile-time check that the
    ``overload`` below puts into every compiled caller: there a table of another type does
    not compile (``TypingError`` with :data:`TABLE_TYPE_RULE`), so no other dtype or shape
    reaches the kernels' arithmetic.
    """
    problem = table_type_problem(law)
    if problem is not None:
        raise TypeError(f"{TABLE_TYPE_RULE}; got {problem}")


@overload(_table_types)
def _table_types_typed(law):
    if not (isinstance(law, types.BaseTuple) and len(law) == 5
            and all(isinstance(a, types.Array) and a.ndim == 1 and a.dtype == types.float64
                    for a in law.types)):
        raise TypingError(f"{TABLE_TYPE_RULE}; got {law}")
    return lambda law: None


@njit_serial
def _interval(u_nodes, u):
    """i with u_nodes[i] <= u < u_nodes[i + 1], clipped to [0, n - 2] (binary search)."""
    lo = 0
    hi = u_nodes.size - 1
    while hi - lo > 1:
        mid = (lo + hi) >> 1
        if u_nodes[mid] <= u:
            lo = mid
        else:
            hi = mid
    return lo


@njit_serial
def _hermite(v_nodes, f, df, i, v):
    """Cubic Hermite interpolant of (f, df/dv) on interval i at v."""
    h = v_nodes[i + 1] - v_nodes[i]
    t = (v - v_nodes[i]) / h
    t2 = t * t
    t3 = t2 * t
    return ((2.0 * t3 - 3.0 * t2 + 1.0) * f[i] + (3.0 * t2 - 2.0 * t3) * f[i + 1]
            + h * ((t3 - 2.0 * t2 + t) * df[i] + (t3 - t2) * df[i + 1]))


@njit_serial
def law_status(law: tuple) -> int:
    """``OK`` when ``law`` is a table that :func:`persson_fast.embed.contact_law` can have
    built, else ``BAD_LAW``.

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table``: ln u, ln p, d ln p/d ln u, ln K, d ln K/d ln u at the nodes,
        each a 1-D float64 array (another type does not compile: numba raises a
        ``TypingError`` that says so).

    Returns
    -------
    int
        ``OK`` (0) or ``BAD_LAW`` (21).

    See Also
    --------
    persson_fast.embed.law_pressure : Checks the table too, at every call.
    persson_fast.embed.law_sweep : Checks it once for many separations.
    persson_fast.embed.STATUS_MESSAGES : What each code means.

    Notes
    -----
    The rules: five arrays of one length n >= 2; v = ln u strictly increasing and y = ln p
    strictly decreasing, both within [LOG_LOW, LOG_HIGH] (logarithms of doubles); the slopes
    dy < 0; z = ln K and dz = d ln K/d ln u finite; z tied to the others by the identity the
    builder writes, ln(-dy) = v + z - y (d ln p/d ln u = -u K/p), to a relative slack of
    ``IDENTITY_SLACK`` of ``1 + |v| + |y| + |z|``, at ``IDENTITY_NODES`` (5) nodes evenly
    spread over the table, both ends included; every interval monotone by the
    Fritsch-Carlson condition the builder enforces, (dy_i^2 + dy_(i+1)^2) <= 9 secant_i^2
    (with a relative slack of ``MONOTONE_SLACK`` for rounding). Written without early exits
    (one pass, no allocation); NaN fails every comparison.

    So every permutation of the five arrays but the identity is refused: each moves an
    array into one of the four slots of the identity, and the only exchange that keeps the
    identity's value, ln u with ln K (v + z is symmetric), puts ln K where ln u must
    increase, and K falls with u (K = p/u0 in the exponential tail the builder reaches).
    What the check cannot see: a wrong ln K value at a node where the identity is not
    checked; d ln K/d ln u enters no identity (a wrong dz array of finite values passes and
    spoils K between nodes only); a table of another scene, a subset of a
    table's nodes, or a consistent change of units (ln p and ln K shifted by one constant,
    or ln u shifted and ln K shifted back) is a valid table of another law.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> embed.law_status(law.table)
    0
    >>> bad = (law.table[0][::-1].copy(),) + law.table[1:]
    >>> embed.law_status(bad)
    21
    """
    _table_types(law)
    v, y, dy, z, dz = law
    n = v.shape[0]
    if (n < 2 or y.shape[0] != n or dy.shape[0] != n or z.shape[0] != n
            or dz.shape[0] != n):
        return BAD_LAW
    ok = ((v[0] >= LOG_LOW) & (v[n - 1] <= LOG_HIGH) & (y[n - 1] >= LOG_LOW)
          & (y[0] <= LOG_HIGH) & (dy[n - 1] < 0.0) & (dy[n - 1] > -math.inf)
          & (abs(z[n - 1]) < math.inf) & (abs(dz[n - 1]) < math.inf))
    bound = 9.0 * (1.0 + MONOTONE_SLACK)
    for i in range(n - 1):
        h = v[i + 1] - v[i]
        d = y[i] - y[i + 1]
        a = dy[i]
        b = dy[i + 1]
        ok &= ((h > 0.0) & (d > 0.0) & (a < 0.0) & (abs(z[i]) < math.inf)
               & (abs(dz[i]) < math.inf) & ((a * a + b * b) * (h * h) <= bound * (d * d)))
    for k in range(IDENTITY_NODES):
        i = (k * (n - 1)) // (IDENTITY_NODES - 1)
        # dy >= 0 or NaN: gap NaN; dy = -inf: gap inf; either fails
        gap = math.log(-dy[i]) - (v[i] + z[i] - y[i]) if dy[i] < 0.0 else math.nan
        ok &= abs(gap) <= IDENTITY_SLACK * (1.0 + abs(v[i]) + abs(y[i]) + abs(z[i]))
    return OK if ok else BAD_LAW


@njit_serial
def _logs(law, u):
    """(ln p, ln K, status) of a checked law at separation u [m]."""
    v_nodes, y, dy, z, dz = law
    n = v_nodes.size
    if not (u > 0.0) or not math.isfinite(u) or n < 2:
        return math.nan, math.nan, BAD_SEPARATION
    v = math.log(u)
    if v >= v_nodes[n - 1]:
        # small pressures: ln p linear in u with the end slope -K/p, and K/p constant
        u_end = math.exp(v_nodes[n - 1])
        slope = dy[n - 1] / u_end
        shift = slope * (u - u_end)
        return y[n - 1] + shift, z[n - 1] + shift, OK
    if v < v_nodes[0]:
        return (y[0] + dy[0] * (v - v_nodes[0]), z[0] + dz[0] * (v - v_nodes[0]),
                LAW_EXTRAPOLATED)
    i = _interval(v_nodes, v)
    return _hermite(v_nodes, y, dy, i, v), _hermite(v_nodes, z, dz, i, v), OK


@njit_serial
def law_logs(law, u):
    """(ln p, ln K, status) of the law at separation u [m] (the table checked first)."""
    if law_status(law) != OK:
        return math.nan, math.nan, BAD_LAW
    return _logs(law, u)


@njit_serial
def law_pressure(law: tuple, u: float) -> tuple[float, int]:
    """(p [Pa], status) of the law at separation u [m].

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table`` of :func:`persson_fast.embed.contact_law`.
    u : float
        Mean interfacial separation, > 0 and finite. [m]

    Returns
    -------
    p : float
        The nominal pressure p(u). [Pa]
    status : int
        0 ok; ``BAD_SEPARATION`` (18, p NaN) for u not finite or <= 0;
        ``LAW_EXTRAPOLATED`` (19) below the table's smallest separation; ``BAD_LAW`` (21,
        p NaN) for a table that :func:`law_status` refuses.

    See Also
    --------
    persson_fast.embed.law_stiffness : K(u).
    persson_fast.embed.law_pressure_stiffness : p(u) and K(u).
    persson_fast.embed.law_separation : u(p), the inverse.
    persson_fast.embed.law_sweep : Many separations.
    persson_fast.embed.contact_law : Builds the table.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> u = pf.solve_separation(s, [1e6], e_star=1e9).separation[0]
    >>> p, status = embed.law_pressure(law.table, u)
    >>> print(f"{p:.5g} Pa", status)
    1e+06 Pa 0
    """
    if law_status(law) != OK:
        return math.nan, BAD_LAW
    v_nodes, y, dy, z, dz = law
    n = v_nodes.size
    if not (u > 0.0) or not math.isfinite(u) or n < 2:
        return math.nan, BAD_SEPARATION
    v = math.log(u)
    if v >= v_nodes[n - 1]:
        u_end = math.exp(v_nodes[n - 1])
        return math.exp(y[n - 1] + dy[n - 1] / u_end * (u - u_end)), OK
    if v < v_nodes[0]:
        return math.exp(y[0] + dy[0] * (v - v_nodes[0])), LAW_EXTRAPOLATED
    return math.exp(_hermite(v_nodes, y, dy, _interval(v_nodes, v), v)), OK


@njit_serial
def law_stiffness(law: tuple, u: float) -> tuple[float, int]:
    """(K = -dp/du [Pa/m], status) of the law at separation u [m].

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table`` of :func:`persson_fast.embed.contact_law`.
    u : float
        Mean interfacial separation, > 0 and finite. [m]

    Returns
    -------
    K : float
        The contact stiffness -dp/du per nominal area. [Pa/m]
    status : int
        As :func:`law_pressure`.

    See Also
    --------
    persson_fast.embed.law_pressure : p(u).
    persson_fast.embed.law_pressure_stiffness : p(u) and K(u).
    persson_fast.embed.contact_law : Builds the table.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> r = pf.solve_separation(s, [1e6], e_star=1e9)
    >>> k, status = embed.law_stiffness(law.table, r.separation[0])
    >>> print(f"{k / r.stiffness[0]:.5f}", status)
    1.00000 0
    """
    _, ln_k, status = law_logs(law, u)
    return math.exp(ln_k), status


@njit_serial
def law_pressure_stiffness(law: tuple, u: float) -> tuple[float, float, int]:
    """(p [Pa], K [Pa/m], status) of the law at separation u [m], from one look-up.

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table`` of :func:`persson_fast.embed.contact_law`.
    u : float
        Mean interfacial separation, > 0 and finite. [m]

    Returns
    -------
    p : float
        The nominal pressure p(u). [Pa]
    K : float
        The contact stiffness -dp/du per nominal area. [Pa/m]
    status : int
        As :func:`law_pressure`.

    See Also
    --------
    persson_fast.embed.law_pressure : p(u).
    persson_fast.embed.law_stiffness : K(u).
    persson_fast.embed.contact_law : Builds the table.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> u = pf.solve_separation(s, [1e6], e_star=1e9).separation[0]
    >>> p, k, status = embed.law_pressure_stiffness(law.table, u)
    >>> print(f"{p:.5g} Pa", status)
    1e+06 Pa 0
    """
    ln_p, ln_k, status = law_logs(law, u)
    return math.exp(ln_p), math.exp(ln_k), status


@njit_serial
def law_separation(law: tuple, p: float) -> tuple[float, int]:
    """(u [m], status) of the law at pressure p [Pa]: the inverse of :func:`law_pressure`.

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table`` of :func:`persson_fast.embed.contact_law`.
    p : float
        Nominal pressure, > 0 and finite. [Pa]

    Returns
    -------
    u : float
        The mean interfacial separation u(p). [m]
    status : int
        0 ok, ``LAW_EXTRAPOLATED`` above the table's pressures, ``BAD_PRESSURE`` (u NaN)
        for p not finite or <= 0.

    See Also
    --------
    persson_fast.embed.law_pressure : p(u), the inverse.
    persson_fast.solve_separation : u(p) from Python.

    Notes
    -----
    On a table interval the monotone cubic ln p(ln u) is inverted by Newton's method
    safeguarded by bisection (to rounding), so law_pressure(law, u) returns p to rounding;
    below the table's pressures the exponential tail is inverted exactly; above them the
    continuation is, with status ``LAW_EXTRAPOLATED``. p not finite or <= 0: NaN,
    ``BAD_PRESSURE``; a table that breaks a rule of :func:`law_status`: NaN, ``BAD_LAW``.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> u, status = embed.law_separation(law.table, 1e6)
    >>> u_ref = pf.solve_separation(s, [1e6], e_star=1e9).separation[0]
    >>> print(f"{u / u_ref:.5f}", status)
    1.00000 0
    """
    if law_status(law) != OK:
        return math.nan, BAD_LAW
    v_nodes, y, dy, z, dz = law
    n = v_nodes.size
    if not (p > 0.0) or not math.isfinite(p) or n < 2:
        return math.nan, BAD_PRESSURE
    target = math.log(p)
    if target <= y[n - 1]:                       # small pressures: the exponential tail
        u_end = math.exp(v_nodes[n - 1])
        return u_end + (target - y[n - 1]) * u_end / dy[n - 1], OK
    if target > y[0]:
        return math.exp(v_nodes[0] + (target - y[0]) / dy[0]), LAW_EXTRAPOLATED
    # y descends: the interval i with y[i] >= target > y[i + 1]
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) >> 1
        if y[mid] >= target:
            lo = mid
        else:
            hi = mid
    a = v_nodes[lo]
    b = v_nodes[lo + 1]
    v = a + (b - a) * (y[lo] - target) / (y[lo] - y[lo + 1])
    for _ in range(60):
        f = _hermite(v_nodes, y, dy, lo, v) - target
        if f > 0.0:
            a = v
        else:
            b = v
        h = v_nodes[lo + 1] - v_nodes[lo]
        t = (v - v_nodes[lo]) / h
        slope = ((6.0 * t * t - 6.0 * t) * (y[lo] - y[lo + 1]) / h
                 + (3.0 * t * t - 4.0 * t + 1.0) * dy[lo] + (3.0 * t * t - 2.0 * t) * dy[lo + 1])
        if f == 0.0:
            break
        step = f / slope if slope < 0.0 else math.nan
        v_new = v - step
        if not (a <= v_new <= b):               # also for NaN: bisect
            v_new = 0.5 * (a + b)
        if abs(v_new - v) <= 4e-16 * abs(v):
            v = v_new
            break
        v = v_new
    return math.exp(v), OK


@njit_serial
def law_sweep_unchecked(law, u, out_p, out_k, out_status):
    """The law at every separation of ``u``, the table not checked (the builder's loop, whose
    intermediate tables need not pass :func:`law_status` yet)."""
    for i in range(u.size):
        ln_p, ln_k, out_status[i] = _logs(law, u[i])
        out_p[i] = math.exp(ln_p)
        out_k[i] = math.exp(ln_k)


@njit_serial
def law_sweep(law: tuple, u: np.ndarray, out_p: np.ndarray, out_k: np.ndarray,
              out_status: np.ndarray) -> None:
    """The law at every separation of ``u``, the table checked once.

    Parameters
    ----------
    law : tuple of five numpy.ndarray
        ``ContactLaw.table`` of :func:`persson_fast.embed.contact_law`.
    u : numpy.ndarray
        Mean interfacial separations, 1-D. [m]
    out_p, out_k : numpy.ndarray
        Outputs of u's length: the pressure p(u) [Pa] and the stiffness K(u) [Pa/m].
    out_status : numpy.ndarray of int64
        Output of u's length: the status per separation (as :func:`law_pressure`).

    Returns
    -------
    None
        The results are written into ``out_p``, ``out_k`` and ``out_status`` in place.

    See Also
    --------
    persson_fast.embed.law_pressure_stiffness : One separation.
    persson_fast.embed.law_status : The table's check alone.
    persson_fast.embed.contact_law : Builds the table.

    Notes
    -----
    A bad table fills every output with NaN and ``BAD_LAW``; outputs of another length than
    ``u``, with NaN and ``BAD_INPUT``.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> u = pf.solve_separation(s, [1e5, 1e6], e_star=1e9).separation
    >>> out_p, out_k = np.empty(2), np.empty(2)
    >>> out_status = np.empty(2, dtype=np.int64)
    >>> embed.law_sweep(law.table, u, out_p, out_k, out_status)
    >>> print(np.round(out_p), out_status)
    [ 100000. 1000000.] [0 0]
    """
    n = u.shape[0]
    s = law_status(law)
    if out_p.shape[0] != n or out_k.shape[0] != n or out_status.shape[0] != n:
        s = BAD_INPUT
    if s != OK:
        out_p[:] = math.nan
        out_k[:] = math.nan
        out_status[:] = s
        return
    law_sweep_unchecked(law, u, out_p, out_k, out_status)
