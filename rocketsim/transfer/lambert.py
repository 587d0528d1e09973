"""Lambert's problem by Izzo's method: the orbit through two points in a given time.

Izzo (2014), "Revisiting Lambert's problem", *Celestial Mechanics and
Dynamical Astronomy* 121:1-15 (arXiv:1403.2705). Section numbers and
equation numbers below are the paper's.

The geometry (chord ``c``, semi-perimeter ``s``) reduces to one parameter
``lambda`` (``lambda**2 = 1 - c/s``, negative for transfer angles above 180
degrees), the time of flight to ``T = sqrt(2 mu / s**3) * tof``, and the
unknown orbit to one free variable ``x`` (``x = 0`` is the minimum-energy
ellipse, ``x = 1`` the parabola, ``x > 1`` hyperbolas). ``T(x)`` is inverted
by third-order Householder iterations from Izzo's initial guesses (eqs. 30,
31); the velocities follow in closed form (Algorithm 1). ``lambda`` is
continuous through zero at 180 degrees, so nothing is singular there except
the *plane*, which two antiparallel vectors do not define: for an exact
180-degree transfer the plane is taken to contain the z axis' projection
(the transfer normal closest to +z).

Units: SI (m, s, m/s, m^3/s^2); positions and velocities in any inertial
frame, "prograde" meaning a transfer whose angular momentum has a positive
z component in that frame.

The public entry :func:`lambert` broadcasts over leading dimensions and
solves every problem in one compiled loop (``rocketsim.jit.njit``).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.errors import InputError
from rocketsim.orbits._broadcast import flat_rows

# |x - 1| below which T(x) uses Battin's hypergeometric series (section 2.2):
# the closed form (eq. 18) cancels catastrophically near the parabola.
_SERIES_BAND = 0.05
# |x - 1| below which dT/dx is a central difference of the series: the
# closed-form derivatives (eq. 22) divide by 1 - x**2.
_PARABOLA_BAND = 1e-6
_FD_STEP = 1e-5
# Householder stops when the step in x falls below these (Izzo uses 1e-5 for
# zero and 1e-8 for multi-revolution; the step after a cubic-rate step
# smaller than 1e-7 leaves an error far below double precision).
_TOL_ZERO_REV = 1e-7
_TOL_MULTI_REV = 1e-10
_MAX_ITER = 15

# Status codes returned by the kernel.
OK = 0
NO_SOLUTION = 1        # time of flight shorter than the M-revolution minimum
NOT_CONVERGED = 2


@njit
def _hyp2f1_battin(z):
    """Gauss hypergeometric 2F1(3, 1; 5/2; z) for |z| < 1 by its series."""
    term = 1.0
    total = 1.0
    n = 0.0
    while n < 300.0:
        term *= (3.0 + n) / (2.5 + n) * z
        total += term
        if abs(term) < 1e-17 * abs(total):
            break
        n += 1.0
    return total


@njit
def _tof(x, lam, m):
    """Non-dimensional time of flight T(x; lambda, M) (eqs. 18, 20)."""
    one_minus_x2 = 1.0 - x * x
    y = math.sqrt(1.0 - lam * lam * one_minus_x2)
    if abs(x - 1.0) < _SERIES_BAND and m == 0:
        # Battin's form: eta = y - lambda x, S1 = (1 - lambda - x eta) / 2,
        # T = (eta^3 Q + 4 lambda eta) / 2, Q = 4/3 2F1(3, 1; 5/2; S1).
        eta = y - lam * x
        s1 = 0.5 * (1.0 - lam - x * eta)
        q = 4.0 / 3.0 * _hyp2f1_battin(s1)
        return 0.5 * (eta ** 3 * q + 4.0 * lam * eta)
    if x < 1.0:
        root = math.sqrt(one_minus_x2)
        # cos(psi) = x y + lambda (1 - x^2), sin(psi) = sqrt(1 - x^2) (y - lambda x)
        psi = math.atan2(root * (y - lam * x), x * y + lam * one_minus_x2)
        return ((psi + m * math.pi) / root - x + lam * y) / one_minus_x2
    root = math.sqrt(-one_minus_x2)
    psi = math.asinh((y - lam * x) * root)
    return (psi / root - x + lam * y) / one_minus_x2


@njit
def _tof_derivatives(x, t, lam, m):
    """dT/dx, d2T/dx2, d3T/dx3 at x where T(x) = t (eq. 22)."""
    if abs(x - 1.0) < _PARABOLA_BAND:
        # At the parabola eq. 22 is 0/0: difference the series instead and
        # let the iteration fall back to Newton's step there.
        d1 = (_tof(x + _FD_STEP, lam, m) - _tof(x - _FD_STEP, lam, m)) / (2.0 * _FD_STEP)
        return d1, 0.0, 0.0
    one_minus_x2 = 1.0 - x * x
    y = math.sqrt(1.0 - lam * lam * one_minus_x2)
    lam2 = lam * lam
    lam3 = lam2 * lam
    d1 = (3.0 * t * x - 2.0 + 2.0 * lam3 * x / y) / one_minus_x2
    d2 = (3.0 * t + 5.0 * x * d1 + 2.0 * (1.0 - lam2) * lam3 / y ** 3) / one_minus_x2
    d3 = (7.0 * x * d2 + 8.0 * d1 - 6.0 * (1.0 - lam2) * lam3 * lam2 * x / y ** 5) / one_minus_x2
    return d1, d2, d3


@njit
def _householder(t_target, x0, lam, m, tol):
    """Solve T(x) = t_target from x0; returns (x, iterations, converged)."""
    x = x0
    lower = -1.0
    upper = 1.0 if m > 0 else math.inf
    for it in range(1, _MAX_ITER + 1):
        t = _tof(x, lam, m)
        d1, d2, d3 = _tof_derivatives(x, t, lam, m)
        f = t - t_target
        d1sq = d1 * d1
        step = f * (d1sq - 0.5 * f * d2) / (d1 * (d1sq - f * d2) + d3 * f * f / 6.0)
        x_new = x - step
        # Keep the iterate inside the domain (-1, 1) or (-1, inf).
        if x_new <= lower:
            x_new = 0.5 * (x + lower)
        elif x_new >= upper:
            x_new = 0.5 * (x + upper)
        converged = abs(x_new - x) < tol
        x = x_new
        if converged:
            return x, it, True
    return x, _MAX_ITER, False


@njit
def _minimum_tof(lam, m):
    """x and T of the minimum time of flight of M revolutions (Halley on dT/dx)."""
    x = 0.0
    t = _tof(x, lam, m)
    for _ in range(30):
        d1, d2, d3 = _tof_derivatives(x, t, lam, m)
        if d1 == 0.0:
            break
        x_new = x - 2.0 * d1 * d2 / (2.0 * d2 * d2 - d1 * d3)
        if x_new <= -1.0:
            x_new = 0.5 * (x - 1.0)
        elif x_new >= 1.0:
            x_new = 0.5 * (x + 1.0)
        done = abs(x_new - x) < 1e-13
        x = x_new
        t = _tof(x, lam, m)
        if done:
            break
    return x, t


@njit
def _find_x(lam, t, m, low_path):
    """The root x of T(x) = t on the requested branch; (x, iterations, status)."""
    if m == 0:
        t00 = math.acos(lam) + lam * math.sqrt(1.0 - lam * lam)   # T(x = 0)
        t1 = 2.0 / 3.0 * (1.0 - lam ** 3)                         # T(x = 1)
        if t >= t00:
            x0 = (t00 / t) ** (2.0 / 3.0) - 1.0
        elif t < t1:
            x0 = 2.5 * t1 * (t1 - t) / (t * (1.0 - lam ** 5)) + 1.0
        else:
            # (eq. 30) x0 = (T/T00)^(log 2 / log(T1/T00)) - 1: 0 at T00, 1 at T1
            x0 = math.exp(math.log(2.0) * math.log(t / t00) / math.log(t1 / t00)) - 1.0
        x, iters, ok = _householder(t, x0, lam, 0, _TOL_ZERO_REV)
        return x, iters, OK if ok else NOT_CONVERGED

    # Multi-revolution: is there a solution at all? T(0) = T00 + M pi.
    t_at_0 = _tof(0.0, lam, m)
    x_min = 0.0
    if t < t_at_0:
        x_min, t_min = _minimum_tof(lam, m)
        if t < t_min:
            return math.nan, 0, NO_SOLUTION
    # Initial guesses (eq. 31): left branch near x = -1, right branch near 1.
    mp = m * math.pi
    a = ((mp + math.pi) / (8.0 * t)) ** (2.0 / 3.0)
    x0_left = (a - 1.0) / (a + 1.0)
    b = (8.0 * t / mp) ** (2.0 / 3.0)
    x0_right = (b - 1.0) / (b + 1.0)
    if low_path:
        x0 = max(x0_left, x0_right)
        if t < t_at_0 and x0 <= x_min:
            x0 = 0.5 * (x_min + 1.0)
    else:
        x0 = min(x0_left, x0_right)
        if t < t_at_0 and x0 >= x_min:
            x0 = 0.5 * (x_min - 1.0)
    x, iters, ok = _householder(t, x0, lam, m, _TOL_MULTI_REV)
    return x, iters, OK if ok else NOT_CONVERGED


@njit
def _solve_one(mu, r1, r2, tof, m, prograde, low_path, v1, v2):
    """One Lambert problem (Izzo, Algorithm 1); writes v1, v2; returns (iters, status)."""
    r1n = math.sqrt(r1[0] ** 2 + r1[1] ** 2 + r1[2] ** 2)
    r2n = math.sqrt(r2[0] ** 2 + r2[1] ** 2 + r2[2] ** 2)
    cx = r2[0] - r1[0]
    cy = r2[1] - r1[1]
    cz = r2[2] - r1[2]
    c = math.sqrt(cx * cx + cy * cy + cz * cz)
    s = 0.5 * (r1n + r2n + c)
    i1x, i1y, i1z = r1[0] / r1n, r1[1] / r1n, r1[2] / r1n
    i2x, i2y, i2z = r2[0] / r2n, r2[1] / r2n, r2[2] / r2n
    hx = i1y * i2z - i1z * i2y
    hy = i1z * i2x - i1x * i2z
    hz = i1x * i2y - i1y * i2x
    hn = math.sqrt(hx * hx + hy * hy + hz * hz)
    if hn > 1e-13:
        hx, hy, hz = hx / hn, hy / hn, hz / hn
    else:
        # Antiparallel (or parallel) positions: the plane is undefined. Take
        # the normal closest to +z among those perpendicular to r1.
        hx, hy, hz = -i1z * i1x, -i1z * i1y, 1.0 - i1z * i1z
        hn = math.sqrt(hx * hx + hy * hy + hz * hz)
        if hn < 1e-12:                      # r1 along z: use +x instead
            hx, hy, hz = 1.0 - i1x * i1x, -i1x * i1y, -i1x * i1z
            hn = math.sqrt(hx * hx + hy * hy + hz * hz)
        hx, hy, hz = hx / hn, hy / hn, hz / hn
    # lambda^2 = 1 - c/s loses half the digits near 180 degrees; the same
    # lambda is sqrt(r1 r2) cos(theta/2) / s with 2 cos(theta/2) = |i1 + i2|.
    # Likewise sigma = sqrt(1 - rho^2) = 2 sqrt(r1 r2) sin(theta/2) / c near 0.
    root_r1r2 = math.sqrt(r1n * r2n)
    half_sum = 0.5 * math.sqrt((i1x + i2x) ** 2 + (i1y + i2y) ** 2 + (i1z + i2z) ** 2)
    half_diff = 0.5 * math.sqrt((i2x - i1x) ** 2 + (i2y - i1y) ** 2 + (i2z - i1z) ** 2)
    lam = root_r1r2 * half_sum / s
    # Transfer normal n: +h is the short way (angle < 180 deg, lambda > 0).
    sign = 1.0
    if hz < 0.0:
        sign = -1.0
    if not prograde:
        sign = -sign
    lam *= sign
    nx, ny, nz = sign * hx, sign * hy, sign * hz
    t1x, t1y, t1z = ny * i1z - nz * i1y, nz * i1x - nx * i1z, nx * i1y - ny * i1x
    t2x, t2y, t2z = ny * i2z - nz * i2y, nz * i2x - nx * i2z, nx * i2y - ny * i2x
    n1 = math.sqrt(t1x * t1x + t1y * t1y + t1z * t1z)
    n2 = math.sqrt(t2x * t2x + t2y * t2y + t2z * t2z)
    t1x, t1y, t1z = t1x / n1, t1y / n1, t1z / n1
    t2x, t2y, t2z = t2x / n2, t2y / n2, t2z / n2

    t = math.sqrt(2.0 * mu / s ** 3) * tof
    x, iters, status = _find_x(lam, t, m, low_path)
    if status == NO_SOLUTION:
        for k in range(3):
            v1[k] = math.nan
            v2[k] = math.nan
        return iters, status
    y = math.sqrt(1.0 - lam * lam * (1.0 - x * x))
    gamma = math.sqrt(0.5 * mu * s)
    rho = (r1n - r2n) / c
    sigma = 2.0 * root_r1r2 * half_diff / c
    vr1 = gamma * ((lam * y - x) - rho * (lam * y + x)) / r1n
    vr2 = -gamma * ((lam * y - x) + rho * (lam * y + x)) / r2n
    vt = gamma * sigma * (y + lam * x)
    vt1 = vt / r1n
    vt2 = vt / r2n
    v1[0] = vr1 * i1x + vt1 * t1x
    v1[1] = vr1 * i1y + vt1 * t1y
    v1[2] = vr1 * i1z + vt1 * t1z
    v2[0] = vr2 * i2x + vt2 * t2x
    v2[1] = vr2 * i2y + vt2 * t2y
    v2[2] = vr2 * i2z + vt2 * t2z
    return iters, status


@njit
def _solve_batch(mu, r1, r2, tof, m, prograde, low_path, v1, v2, iters, status):
    """Solve N problems (rows of r1, r2; entries of mu, tof) in one loop."""
    for i in range(tof.shape[0]):
        it, st = _solve_one(mu[i], r1[i], r2[i], tof[i], m, prograde, low_path, v1[i], v2[i])
        iters[i] = it
        status[i] = st


def _check_inputs(mu, r1, r2, tof, revs):
    if not (isinstance(revs, (int, np.integer)) and revs >= 0):
        raise InputError(f"revs must be a whole number of revolutions >= 0, got {revs!r}",
                         field="revs")
    if not np.all(np.isfinite(mu)) or np.any(mu <= 0.0):
        raise InputError("the gravitational parameter mu must be positive and finite", field="mu")
    if not np.all(np.isfinite(tof)) or np.any(tof <= 0.0):
        bad = tof[~(np.isfinite(tof) & (tof > 0.0))].ravel()[0]
        raise InputError(f"time of flight must be positive and finite, got {bad!r} s", field="tof")
    for name, r in (("r1", r1), ("r2", r2)):
        if not np.all(np.isfinite(r)):
            raise InputError(f"{name} must be finite", field=name)
    n1 = np.linalg.norm(r1, axis=-1)
    n2 = np.linalg.norm(r2, axis=-1)
    if np.any(n1 == 0.0) or np.any(n2 == 0.0):
        raise InputError("a position is at the attracting centre (zero vector)", field="r1/r2")
    chord = np.linalg.norm(r2 - r1, axis=-1)
    if np.any(chord <= 1e-12 * (n1 + n2)):
        raise InputError("the two positions coincide: Lambert's problem needs distinct "
                         "end points (a whole-revolution transfer is not defined by them)",
                         field="r1/r2")


def lambert_detailed(mu, r1, r2, tof, *, revs=0, prograde=True, low_path=True):
    """Like :func:`lambert`, and also the number of Householder iterations.

    Returns ``(v1, v2, iterations)``, iterations an integer array of the
    broadcast shape.
    """
    shape, (mu_b, tof_b), (r1_b, r2_b) = flat_rows((mu, tof), (r1, r2), ("r1", "r2"))
    _check_inputs(mu_b, r1_b, r2_b, tof_b, revs)
    n = tof_b.shape[0]
    v1 = np.empty((n, 3))
    v2 = np.empty((n, 3))
    iters = np.empty(n, dtype=np.int64)
    status = np.empty(n, dtype=np.int64)
    _solve_batch(mu_b, r1_b, r2_b, tof_b, int(revs), bool(prograde), bool(low_path),
                 v1, v2, iters, status)
    if np.any(status == NO_SOLUTION):
        i = int(np.argmax(status == NO_SOLUTION))
        raise InputError(f"no {revs}-revolution transfer exists for a time of flight of "
                         f"{tof_b[i]:.6g} s between these positions (it is shorter than the "
                         f"minimum for {revs} revolutions); try fewer revolutions", field="revs")
    if np.any(status == NOT_CONVERGED):
        raise RuntimeError("Lambert solver did not converge (please report the inputs)")
    return v1.reshape(shape + (3,)), v2.reshape(shape + (3,)), iters.reshape(shape)


def lambert(mu, r1, r2, tof, *, revs=0, prograde=True, low_path=True):
    """Velocities at both ends of the conic from ``r1`` to ``r2`` in ``tof``.

    Parameters (SI; arrays broadcast over leading dimensions, positions and
    velocities carry their 3 components in the last axis):

    mu : gravitational parameter of the central body, m^3/s^2.
    r1, r2 : positions at departure and arrival, m, any inertial frame.
    tof : time of flight, s (> 0).
    revs : whole revolutions before arrival (0 = direct transfer).
    prograde : transfer angular momentum along +z (False: along -z).
    low_path : for ``revs > 0``, which of the two solutions: the right-hand
        branch of Izzo's T(x) (larger x) if True, the left-hand one if False
        (the convention of PyKEP and lamberthub).

    Returns ``(v1, v2)`` in m/s. Raises :class:`~rocketsim.errors.InputError`
    for a non-positive time of flight, coincident positions, or when no
    ``revs``-revolution solution exists for the time of flight.
    """
    v1, v2, _ = lambert_detailed(mu, r1, r2, tof, revs=revs, prograde=prograde,
                                 low_path=low_path)
    return v1, v2
