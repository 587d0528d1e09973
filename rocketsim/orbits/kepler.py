"""Two-body propagation of any conic by the universal variable.

Kepler's equation in the universal variable ``chi`` (Vallado, *Fundamentals of
Astrodynamics and Applications*, 4th ed., section 2.3 and Algorithm 8;
Curtis, *Orbital Mechanics for Engineering Students*, section 3.7):

    sqrt(mu) dt = sigma0 chi^2 C(z) + (1 - alpha r0) chi^3 S(z) + r0 chi,
    z = alpha chi^2,  alpha = 2/r0 - v0^2/mu,  sigma0 = r0.v0 / sqrt(mu)

with the Stumpff functions C, S, covers ellipses (alpha > 0), the parabola
(alpha = 0) and hyperbolas (alpha < 0) alike. It is solved by the
Laguerre-Conway iteration (Conway 1986, "An improved algorithm due to
Laguerre for the solution of Kepler's equation", Celestial Mechanics 39:199),
which converges from a crude start for every conic; the state follows from
the Lagrange coefficients f, g, fdot, gdot. Elliptic propagation first removes
whole periods, so long arcs keep the variable small and the accuracy.
Far along a hyperbola (more than one unit of hyperbolic anomaly) both
Kepler's equation and the final state are written in the hyperbolic anomaly
instead: there f r0 + g v0 would be the small difference of two large terms
(a transfer that swings close past the centre kept only 8 digits that way).

Accuracy: about 1e-12 of the distance on ellipses, parabolas and hyperbolas
alike (tests/unit/orbits/test_kepler.py against DOP853; tests/unit/transfer/test_lambert_random.py).

Units: SI (m, s, m/s, m^3/s^2), any inertial frame.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.errors import InputError
from rocketsim.orbits._broadcast import flat_rows

_MAX_ITER = 60


@njit
def stumpff(z):
    """Stumpff functions ``(C(z), S(z))``; series for |z| < 1."""
    if z > 1.0:
        sz = math.sqrt(z)
        return (1.0 - math.cos(sz)) / z, (sz - math.sin(sz)) / (sz * z)
    if z < -1.0:
        sz = math.sqrt(-z)
        return (math.cosh(sz) - 1.0) / (-z), (math.sinh(sz) - sz) / (sz * -z)
    # C = sum (-z)^k / (2k+2)!,  S = sum (-z)^k / (2k+3)!
    c = 0.0
    s = 0.0
    term_c = 0.5
    term_s = 1.0 / 6.0
    for k in range(12):
        c += term_c
        s += term_s
        term_c *= -z / ((2 * k + 3) * (2 * k + 4))
        term_s *= -z / ((2 * k + 4) * (2 * k + 5))
    return c, s


@njit
def _hyperbola_state(mu, r0, r0n, hx, hy, hz, alpha, a_plus, neg_a, dh, r_out, v_out):
    """State after a change dh of hyperbolic anomaly, without f and g.

    Far along a hyperbola that swings close past the centre, r = f r0 + g v0
    is the small difference of two large terms. Instead: the anomalies
    H0 = log(A+ / e) and H1 = H0 + dh, the true anomalies from
    tan(nu/2) = sqrt((e+1)/(e-1)) tanh(H/2), the radius
    r = |a| ((e - 1) + 2 e sinh^2(H/2)) and the velocity's radial and
    transverse parts, placed in the plane by the angle swept from r0 (the
    hyperbolic-anomaly relations of the conic; e.g. Battin, *An Introduction
    to the Mathematics and Methods of Astrodynamics*, ch. 4).
    """
    h2 = hx * hx + hy * hy + hz * hz
    h = math.sqrt(h2)
    e2_minus_1 = -alpha * h2 / mu
    e = math.sqrt(1.0 + e2_minus_1)
    e_minus_1 = e2_minus_1 / (e + 1.0)
    h0 = math.log(a_plus / e)
    h1 = h0 + dh
    k = math.sqrt((e + 1.0) / e_minus_1)
    nu0 = 2.0 * math.atan(k * math.tanh(0.5 * h0))
    nu1 = 2.0 * math.atan(k * math.tanh(0.5 * h1))
    swept = nu1 - nu0
    sh = math.sinh(0.5 * h1)
    r1 = neg_a * (e_minus_1 + 2.0 * e * sh * sh)
    ux, uy, uz = r0[0] / r0n, r0[1] / r0n, r0[2] / r0n
    nx, ny, nz = hx / h, hy / h, hz / h
    sx, sy, sz = ny * uz - nz * uy, nz * ux - nx * uz, nx * uy - ny * ux
    c = math.cos(swept)
    s = math.sin(swept)
    rhx, rhy, rhz = c * ux + s * sx, c * uy + s * sy, c * uz + s * sz
    thx, thy, thz = -s * ux + c * sx, -s * uy + c * sy, -s * uz + c * sz
    v_radial = mu / h * e * math.sin(nu1)
    v_transverse = h / r1
    r_out[0], r_out[1], r_out[2] = r1 * rhx, r1 * rhy, r1 * rhz
    v_out[0] = v_radial * rhx + v_transverse * thx
    v_out[1] = v_radial * rhy + v_transverse * thy
    v_out[2] = v_radial * rhz + v_transverse * thz


@njit
def _propagate_one(mu, r0, v0, dt, r_out, v_out):
    """Propagate one state by dt (s); returns the iteration count (-1: failed)."""
    r0n = math.sqrt(r0[0] ** 2 + r0[1] ** 2 + r0[2] ** 2)
    v0sq = v0[0] ** 2 + v0[1] ** 2 + v0[2] ** 2
    sqmu = math.sqrt(mu)
    sigma0 = (r0[0] * v0[0] + r0[1] * v0[1] + r0[2] * v0[2]) / sqmu
    alpha = 2.0 / r0n - v0sq / mu
    if alpha > 0.0:
        # Ellipse: drop whole periods (the state repeats exactly).
        period = 2.0 * math.pi / (math.sqrt(mu) * alpha ** 1.5)
        dt = dt - period * math.floor(dt / period + 0.5)
        chi = sqmu * alpha * dt
    else:
        chi = sqmu * dt / r0n
        if alpha < 0.0 and dt != 0.0:
            # Hyperbola: Vallado's start (Algorithm 8), from the asymptotic
            # growth of the hyperbolic anomaly.
            a = 1.0 / alpha
            sgn = math.copysign(1.0, dt)
            arg = (-2.0 * mu * alpha * dt
                   / (sigma0 * sqmu + sgn * math.sqrt(-mu * a) * (1.0 - r0n * alpha)))
            if arg > 0.0:
                chi = sgn * math.sqrt(-a) * math.log(arg)
    one_minus_ar0 = 1.0 - alpha * r0n
    target = sqmu * dt
    # Hyperbolas far from periapsis: the two leading terms of F cancel
    # (they grow as exp|dH| with opposite signs). In the hyperbolic anomaly
    # dH = chi / sqrt(-a), F = (-a)^(3/2) [(A+ expm1(dH) - A- expm1(-dH))/2 - dH]
    # - sqrt(mu) dt with A+- = (1 - alpha r0) +- sigma0 sqrt(-alpha) and
    # A+ A- = e^2 = 1 - alpha h^2 / mu; the smaller of A+- is taken from the
    # product, which removes the cancellation.
    neg_a = 0.0
    a_plus = 0.0
    a_minus = 0.0
    hx = r0[1] * v0[2] - r0[2] * v0[1]
    hy = r0[2] * v0[0] - r0[0] * v0[2]
    hz = r0[0] * v0[1] - r0[1] * v0[0]
    if alpha < 0.0:
        neg_a = -1.0 / alpha
        ecc2 = 1.0 - alpha * (hx * hx + hy * hy + hz * hz) / mu
        q = sigma0 * math.sqrt(-alpha)
        if q >= 0.0:
            a_plus = one_minus_ar0 + q
            a_minus = ecc2 / a_plus
        else:
            a_minus = one_minus_ar0 - q
            a_plus = ecc2 / a_minus
    root_neg_a = math.sqrt(neg_a)
    scale = neg_a * root_neg_a
    n = 5.0
    iters = -1
    # F(chi) increases monotonically (dF/dchi = r > 0): keep a bracket and
    # bisect whenever a Laguerre step would leave it.
    lo = -math.inf
    hi = math.inf
    for it in range(_MAX_ITER):
        z = alpha * chi * chi
        if z < -1.0:
            dh = chi / root_neg_a
            ep = a_plus * math.exp(dh)
            em = a_minus * math.exp(-dh)
            f = scale * (0.5 * (a_plus * math.expm1(dh) - a_minus * math.expm1(-dh)) - dh) - target
            df = neg_a * (0.5 * (ep + em) - 1.0)
            d2f = root_neg_a * 0.5 * (ep - em)
        else:
            c, s = stumpff(z)
            chi2 = chi * chi
            f = sigma0 * chi2 * c + one_minus_ar0 * chi2 * chi * s + r0n * chi - target
            df = chi2 * c + sigma0 * chi * (1.0 - z * s) + r0n * (1.0 - z * c)   # = r
            d2f = sigma0 * (1.0 - z * c) + one_minus_ar0 * chi * (1.0 - z * s)
        disc = abs((n - 1.0) ** 2 * df * df - n * (n - 1.0) * f * d2f)
        denom = df + math.copysign(math.sqrt(disc), df)
        if f == 0.0:
            iters = it + 1
            break
        delta = n * f / denom
        if f < 0.0:
            lo = max(lo, chi)
        else:
            hi = min(hi, chi)
        chi_new = chi - delta
        if not (lo <= chi_new <= hi) and math.isfinite(lo) and math.isfinite(hi):
            chi_new = 0.5 * (lo + hi)
            delta = chi - chi_new
        chi = chi_new
        if abs(delta) <= 1e-15 * max(abs(chi), 1e-300):
            iters = it + 1
            break
        if abs(delta) <= 1e-11 * max(abs(chi), 1e-300):
            # Cubic convergence: what is left is rounding; accept if the
            # iteration then stalls (iters stays at this count).
            iters = it + 1
    z = alpha * chi * chi
    if z < -1.0:
        _hyperbola_state(mu, r0, r0n, hx, hy, hz, alpha, a_plus, neg_a, chi / root_neg_a,
                         r_out, v_out)
        return iters
    c, s = stumpff(z)
    chi2 = chi * chi
    f_lag = 1.0 - chi2 * c / r0n
    g_lag = (sigma0 * chi2 * c + r0n * chi * (1.0 - z * s)) / sqmu
    rx = f_lag * r0[0] + g_lag * v0[0]
    ry = f_lag * r0[1] + g_lag * v0[1]
    rz = f_lag * r0[2] + g_lag * v0[2]
    rn = math.sqrt(rx * rx + ry * ry + rz * rz)
    fdot = sqmu / (rn * r0n) * chi * (z * s - 1.0)
    gdot = 1.0 - chi2 * c / rn
    r_out[0], r_out[1], r_out[2] = rx, ry, rz
    v_out[0] = fdot * r0[0] + gdot * v0[0]
    v_out[1] = fdot * r0[1] + gdot * v0[1]
    v_out[2] = fdot * r0[2] + gdot * v0[2]
    return iters


@njit
def _propagate_batch(mu, r0, v0, dt, r, v, iters):
    for i in range(dt.shape[0]):
        iters[i] = _propagate_one(mu[i], r0[i], v0[i], dt[i], r[i], v[i])


def propagate(mu, r0, v0, dt):
    """State after ``dt`` seconds of two-body motion from ``(r0, v0)``.

    mu in m^3/s^2, r0 in m, v0 in m/s, dt in s (may be negative: backwards).
    Arrays broadcast over leading dimensions (vectors in the last axis of
    length 3); the loop over states is compiled. Returns ``(r, v)``.
    """
    shape, (mu_b, dt_b), (r0_b, v0_b) = flat_rows((mu, dt), (r0, v0), ("r0", "v0"))
    if np.any(mu_b <= 0.0) or not np.all(np.isfinite(mu_b)):
        raise InputError("the gravitational parameter mu must be positive and finite", field="mu")
    if np.any(np.linalg.norm(r0_b, axis=-1) == 0.0):
        raise InputError("r0 is at the attracting centre (zero vector)", field="r0")
    n = dt_b.shape[0]
    r = np.empty((n, 3))
    v = np.empty((n, 3))
    iters = np.empty(n, dtype=np.int64)
    _propagate_batch(mu_b, r0_b, v0_b, dt_b, r, v, iters)
    if np.any(iters < 0):
        raise RuntimeError("universal-variable Kepler solver did not converge")
    return r.reshape(shape + (3,)), v.reshape(shape + (3,))
