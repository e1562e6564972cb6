"""Compiled kernels of the corrected area theories without walls (yp08, wm17, xu24).

Everything here is dimensionless. With y = p / sqrt(2 Vc) = p / (2 sqrt G) (the argument of
the original theory, A = erf(y)) every theory of :mod:`persson_fast.theories` gives the area
as A = erf(x(y)) with a single function x(y) per theory and gamma. The kernels tabulate
L(s) = ln x on a uniform grid in s = ln y, with the exact slope dL/ds at each node, and
integrate W = L - s = ln(x/y) (bounded, so rounding does not grow with |s|):

* yp08, wm17 (an ODE in the uncorrected variance): dL/ds = S(erf e^L) e^(2 (L - s)), i.e.
  dW/ds = S(erf e^(s + W)) e^(2 W) - 1,
  integrated downward from s = ln 6 (where x = y to double precision) by classical
  Runge-Kutta (4th order) with ``RK_SUBSTEPS`` steps per table interval;
* xu24 (algebraic): x = y / sqrt(gamma + (1 - gamma) erf x), solved at each node by a
  safeguarded Newton iteration; dL/ds = 1 / (1 + (1 - gamma) x erf'(x) / (2 M)),
  M = gamma + (1 - gamma) erf x.

From W the kernels tabulate ln A = ln erf(y e^W) with its exact slope and interpolate it
by cubic Hermite polynomials: a look-up costs one exp, and the interpolation error of ln A is
the relative error of A (~4e-13 at the default spacing, 1/512 in ln y).

Below the table (y < e^s_lo, areas below ~1e-8) the small-contact limit is used: x = y r0
with r0 = e^W at the first node for the ODE theories (relative error ~ x^2 ln x), two
fixed-point steps of the algebraic relation for xu24 (relative error ~ A^2). Above it
(y >= 6) x >= 6 and erf x == 1.0 in double precision.

Theory codes: ``YP08``, ``WM17``, ``XU24`` (0 is the original theory, handled elsewhere).
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial
from .status import BAD_INPUT, NONFINITE, OK

YP08 = 1
WM17 = 2
XU24 = 3

#: table spacing in s = ln y (cubic Hermite interpolation of ln A: relative error of A ~4e-13)
TABLE_STEP = 1.0 / 512.0
#: Runge-Kutta steps per table interval (yp08, wm17)
RK_SUBSTEPS = 2
#: upper end of the table: y = 6, where erf(x) == 1.0 for every x >= y
Y_HIGH = 6.0
#: lower end of the table: y = 1e-8 (areas ~1e-8 and below use the small-contact limit)
Y_LOW = 1e-8

_TWO_OVER_SQRT_PI = 2.0 / math.sqrt(math.pi)


@njit_serial
def correction_factor(code, gamma, area):
    """S(A), the factor of the corrected diffusion dV/dVc = S(A) (yp08, wm17). [-]

    yp08: S = gamma + (1 - gamma) A^2; wm17: S = gamma - (2/9) A^2 + (11/9 - gamma) A^4;
    any other code: 1 (the original theory). S(1) = 1 for both, S(0) = gamma.
    """
    a2 = area * area
    if code == YP08:
        return gamma + (1.0 - gamma) * a2
    if code == WM17:
        return gamma - (2.0 / 9.0) * a2 + (11.0 / 9.0 - gamma) * a2 * a2
    return 1.0


@njit_serial
def _ode_slope(code, gamma, s, w):
    """dW/ds = S(erf e^(s + W)) e^(2 W) - 1 of the ODE theories, s = ln y, W = ln(x / y)."""
    return correction_factor(code, gamma, math.erf(math.exp(s + w))) * math.exp(2.0 * w) - 1.0


@njit_serial
def _xu24_node(gamma, y, area_guess):
    """(ln(x / y), dW/ds, area) of x = y / sqrt(gamma + (1 - gamma) erf x) at one y > 0.

    Safeguarded Newton on h(A) = A - erf(y / sqrt(gamma + (1 - gamma) A)) over A in [0, 1]:
    h is increasing (its second term decreases with A), h(0) < 0 < h(1), one root.
    """
    lo, hi = 0.0, 1.0
    a = min(max(area_guess, 0.0), 1.0)
    for _ in range(200):
        m = gamma + (1.0 - gamma) * a
        z = y / math.sqrt(m)
        h = a - math.erf(z)
        if h < 0.0:
            lo = a
        else:
            hi = a
        dh = 1.0 + _TWO_OVER_SQRT_PI * math.exp(-z * z) * z * (1.0 - gamma) / (2.0 * m)
        a_new = a - h / dh
        if not (lo < a_new < hi):
            a_new = 0.5 * (lo + hi)
        if abs(a_new - a) <= 1e-16 * a_new or hi - lo <= 1e-17 * hi:
            a = a_new
            break
        a = a_new
    m = gamma + (1.0 - gamma) * a
    x = y / math.sqrt(m)
    c = (1.0 - gamma) * x * _TWO_OVER_SQRT_PI * math.exp(-x * x) / (2.0 * m)
    return -0.5 * math.log(m), -c / (1.0 + c), a


@njit_serial
def build_table(code, gamma, s_low, step, substeps, L, D):
    """Fill L[k] = W = ln(x / y) and D[k] = dW/ds at s_k = s_low + k step, k = 0 .. n-1.

    Parameters
    ----------
    code : int -- YP08, WM17 or XU24.
    gamma : float -- the theory's parameter (S(0) = gamma > 0). [-]
    s_low : float -- ln y of the first node; the last, s_low + (n-1) step, must be >= ln 6.
    step : float -- node spacing in ln y. [-]
    substeps : int -- Runge-Kutta steps per interval (ODE theories). [-]
    L, D : (n,) float64 -- outputs.

    Returns
    -------
    int -- status: 0 ok, BAD_INPUT (unknown code, n < 2, table not reaching ln 6),
    NONFINITE.
    """
    n = L.size
    if n < 2 or D.size != n or not (code == YP08 or code == WM17 or code == XU24):
        return BAD_INPUT
    s_top = s_low + (n - 1) * step
    if s_top < math.log(Y_HIGH) - 1e-12 or not gamma > 0.0:
        return BAD_INPUT
    if code == XU24:
        a = 1.0
        for k in range(n - 1, -1, -1):
            y = math.exp(s_low + k * step)
            L[k], D[k], a = _xu24_node(gamma, y, a)
    else:
        # start at y >= 6: S(erf x) = 1 to double precision there, so x = y
        Lk = 0.0
        L[n - 1] = Lk
        D[n - 1] = _ode_slope(code, gamma, s_top, Lk)
        h = -step / substeps
        for k in range(n - 1, 0, -1):
            s = s_low + k * step
            for j in range(substeps):
                s0 = s + j * h
                k1 = _ode_slope(code, gamma, s0, Lk)
                k2 = _ode_slope(code, gamma, s0 + 0.5 * h, Lk + 0.5 * h * k1)
                k3 = _ode_slope(code, gamma, s0 + 0.5 * h, Lk + 0.5 * h * k2)
                k4 = _ode_slope(code, gamma, s0 + h, Lk + h * k3)
                Lk = Lk + h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0
            L[k - 1] = Lk
            D[k - 1] = _ode_slope(code, gamma, s_low + (k - 1) * step, Lk)
    for k in range(n):
        if not (math.isfinite(L[k]) and math.isfinite(D[k])):
            return NONFINITE
    return OK


@njit_serial
def area_table(W, D, s_low, step, LA, DA):
    """Fill LA[k] = ln A and DA[k] = d ln A / ds from the W table (A = erf(y e^W)).

    d ln A / ds = erf'(x) x (1 + dW/ds) / A. ln A is what the sweep interpolates: one exp per
    look-up, and its interpolation error is the relative error of A.
    """
    n = W.size
    for k in range(n):
        x = math.exp(s_low + k * step + W[k])
        a = math.erf(x)
        LA[k] = math.log(a)
        DA[k] = _TWO_OVER_SQRT_PI * math.exp(-x * x) * x * (1.0 + D[k]) / a
    return OK


@njit_serial
def table_area(code, gamma, s, w0, LA, DA, s_low, inv_step):
    """A at s = ln y from the ln A table (cubic Hermite), with the limits outside it.

    Parameters
    ----------
    code, gamma : the theory and its parameter.
    s : float -- ln y, y = p / (2 sqrt G). [-]
    w0 : float -- W = ln(x / y) at the first node (the small-contact ratio). [-]
    LA, DA : (n,) -- the table of :func:`area_table`.
    s_low, inv_step : first node and 1 / spacing. [-]
    """
    t = (s - s_low) * inv_step
    n = LA.size
    if t >= n - 1:
        return 1.0                              # y >= 6: x >= 6 and erf x == 1.0
    if t < 0.0:
        y = math.exp(s)
        if code == XU24:                        # two fixed-point steps, relative error ~A^2
            x = y / math.sqrt(gamma)
            for _ in range(2):
                x = y / math.sqrt(gamma + (1.0 - gamma) * math.erf(x))
            return math.erf(x)
        return math.erf(y * math.exp(w0))       # x / y constant, relative error ~x^2 ln x
    k = int(t)
    u = t - k
    h = 1.0 / inv_step
    u2 = u * u
    u3 = u2 * u
    la = ((2.0 * u3 - 3.0 * u2 + 1.0) * LA[k] + (u3 - 2.0 * u2 + u) * h * DA[k]
          + (3.0 * u2 - 2.0 * u3) * LA[k + 1] + (u3 - u2) * h * DA[k + 1])
    return math.exp(la)


@njit_serial
def theory_area_sweep(code, gamma, pressure, G, w0, LA, DA, s_low, inv_step, log_scale, area,
                      status):
    """A(zeta)/A0 for every pressure and diffusion time, without walls.

    Parameters
    ----------
    code, gamma : the theory and its parameter.
    pressure : (n_p,) -- nominal pressures, >= 0 (any unit u). [u]
    G : (n_z,) -- non-decreasing diffusion times, >= 0. [u^2]
    w0, LA, DA, s_low, inv_step : the tables (see :func:`table_area`).
    log_scale : (n_z,) -- scratch, ln(2 sqrt G).
    area : (n_p, n_z) -- output, A/A0. [-]
    status : (n_p,) int64 -- output, 0 ok or NONFINITE.

    Notes
    -----
    y = p / (2 sqrt G); ln y = ln p - ln(2 sqrt G) is formed from one logarithm per pressure
    and one per diffusion time. G = 0 gives A = 1 for p > 0 (the delta start), p = 0 gives 0;
    y >= 6 gives 1.0 (erf x rounds to 1 for x >= 6, and x >= y).
    """
    n_p = pressure.size
    n_z = G.size
    for j in range(n_z):
        log_scale[j] = math.log(2.0 * math.sqrt(G[j])) if G[j] > 0.0 else -math.inf
    for i in range(n_p):
        p = pressure[i]
        status[i] = OK
        if p == 0.0:
            for j in range(n_z):
                area[i, j] = 0.0
            continue
        lp = math.log(p)
        for j in range(n_z):
            a = table_area(code, gamma, lp - log_scale[j], w0, LA, DA, s_low, inv_step)
            if not math.isfinite(a):
                status[i] = NONFINITE
            area[i, j] = a
    return 0


@njit_serial
def theory_area_one(code, gamma, y, w0, LA, DA, s_low, inv_step):
    """A = erf(x(y)) at one y = p / (2 sqrt G) >= 0 (inf: A = 1). [-]"""
    if y <= 0.0:
        return 0.0
    if not y < math.inf:
        return 1.0
    return table_area(code, gamma, math.log(y), w0, LA, DA, s_low, inv_step)


def table_nodes(step: float = TABLE_STEP) -> tuple[float, int]:
    """(s_low, n): the table's first node and its size for a given step."""
    s_top = math.log(Y_HIGH)
    n = int(math.ceil((s_top - math.log(Y_LOW)) / step)) + 1
    return s_top - (n - 1) * step, n


def new_table(code: int, gamma: float, step: float = TABLE_STEP,
              substeps: int = RK_SUBSTEPS):
    """Allocate and fill the tables: (w0, LA, DA, s_low, inv_step, status, W, D).

    ``(w0, LA, DA, s_low, inv_step)`` are the arguments of :func:`table_area` and the sweep.
    """
    s_low, n = table_nodes(step)
    W = np.empty(n)
    D = np.empty(n)
    st = build_table(code, gamma, s_low, step, substeps, W, D)
    LA = np.empty(n)
    DA = np.empty(n)
    if st == OK:
        area_table(W, D, s_low, step, LA, DA)
        if not (np.all(np.isfinite(LA)) and np.all(np.isfinite(DA))):
            st = NONFINITE
    return float(W[0]), LA, DA, s_low, 1.0 / step, st, W, D
