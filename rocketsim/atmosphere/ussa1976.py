"""US Standard Atmosphere 1976, geometric height -5 km to 1 000 km.

Source: *U.S. Standard Atmosphere, 1976*, NOAA-S/T 76-1562 (NOAA, NASA,
USAF), referred to below as "the standard"; section and equation numbers are
the standard's.

- Below 86 km (section 1.2): seven layers of constant molecular-scale
  temperature gradient in geopotential height ``H = r0 Z / (r0 + Z)``; the
  kinetic temperature is the molecular-scale temperature times the standard's
  ``M/M0`` ratio between 80 and 86 km (Table 8). Pressure from eqs. 33a/33b,
  density ``p M0 / (R* T_M)``, speed of sound ``sqrt(gamma R* T_M / M0)``.
- Above 86 km (section 1.3): the standard's kinetic-temperature profile
  (eqs. 24-32) and its composition: number densities of N2, O, O2, Ar, He
  (eqs. 34-37, molecular and eddy diffusion with the vertical-flux terms) and
  H above 150 km (eqs. 38-40), from which the local mean molar mass ``M(Z)``.
  The molar mass ``M`` in the eddy-mixing term of eq. 36 is ``M0`` up to
  100 km for every species; above 100 km it is that of the gas the species
  diffuses through: N2 for N2, O and O2, the mean of N2, O and O2 for Ar and
  He. With it the densities, pressures and molar masses match the printed
  Table I from 86 to 1 000 km to 0.03 % (taking N2's ``M`` for O below
  100 km instead leaves 7 % too much O above 150 km: +3 % in density at
  200 km, +7 % at 500 km).
  The species equations are integrated on rows 25 m apart (125 m above
  150 km); the pressure at a row is ``N k T`` (eq. 33c), and between rows it
  is the hydrostatic equation ``d ln p / dZ = -g M / (R* T)`` integrated from
  the rows (Hermite form, :mod:`.hydrostatic`), never a straight
  interpolation of the rows; density ``p M / (R* T)``; speed of sound
  ``sqrt(gamma R* T / M)`` with the local ``M`` so it follows the composition.
- Viscosity: Sutherland's law (eq. 51). The standard tabulates it only below
  86 km; above, the same law is applied to the kinetic temperature.

All functions take geometric height above mean sea level in metres (scalars
or arrays) and return SI units.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from rocketsim.atmosphere.hydrostatic import hermite
from rocketsim.constants import (CELSIUS_ZERO, G0, GAS_CONSTANT_USSA, USSA_BOLTZMANN, USSA_GAMMA, USSA_M0,
                                 USSA_P0, USSA_R0, USSA_SUTHERLAND_BETA, USSA_SUTHERLAND_S,
                                 USSA_T0)

R_STAR = GAS_CONSTANT_USSA          # J/(mol K)
Z_MIN = -5_000.0                    # m, lowest height the standard defines
Z_86 = 86_000.0                     # m, top of the geopotential-layer region
Z_MAX = 1_000_000.0                 # m, top of the standard

# Table 4: geopotential base heights (m') and molecular-scale temperature gradients (K/m').
_H_BASE = np.array([0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0])
LAPSE = np.array([-0.0065, 0.0, 0.0010, 0.0028, 0.0, -0.0028, -0.0020])

# Table 8: M/M0 at geometric heights 80.0 to 86.0 km every 0.5 km (linear between).
_RATIO_Z = np.arange(80_000.0, 86_000.1, 500.0)
_RATIO = np.array([1.000000, 0.999996, 0.999989, 0.999971, 0.999941, 0.999909, 0.999870,
                   0.999829, 0.999786, 0.999741, 0.999694, 0.999641, 0.999579])

# Section 1.3: kinetic temperature above 86 km.
_T7 = 186.8673                      # K, 86-91 km isothermal
_Z8, _Z9, _Z10 = 91_000.0, 110_000.0, 120_000.0
_TC, _A_ELL, _B_ELL = 263.1905, -76.3232, -19_942.9   # eq. 27: K, K, m
_T9, _LK9 = 240.0, 0.012            # K at 110 km, K/m to 120 km
_T10, _T_INF, _LAMBDA = 360.0, 1000.0, 1.875e-5        # K, K, 1/m (eq. 31)

# Table 3: molar masses (kg/mol) of the species above 86 km.
_SPECIES = ("N2", "O", "O2", "Ar", "He", "H")
_MOLAR = {"N2": 0.0280134, "O": 0.0159994, "O2": 0.0319988, "Ar": 0.039948,
          "He": 0.0040026, "H": 0.00100797}
# Number densities at 86 km (1/m^3, section 1.3.1) and of H at 500 km.
_N86 = {"N2": 1.129794e20, "O": 8.6e16, "O2": 3.030898e19, "Ar": 1.351400e18, "He": 7.5817e14}
_N_H500 = 8.0e10
_PHI_H = 7.2e11                     # 1/(m^2 s), hydrogen vertical flux (eq. 39)
# Table 6: molecular diffusion D = a/n (T/273.15)^b (a in 1/(m s)), thermal diffusion alpha.
_DIFF_A = {"O": 6.986e20, "O2": 4.863e20, "Ar": 4.487e20, "He": 1.700e21, "H": 3.305e21}
_DIFF_B = {"O": 0.750, "O2": 0.750, "Ar": 0.870, "He": 0.691, "H": 0.500}
_ALPHA = {"O": 0.0, "O2": 0.0, "Ar": 0.0, "He": -0.40, "H": -0.25}
_K_EDDY = 120.0                     # m^2/s, eddy diffusion coefficient 86-95 km
# Table 7: vertical flux terms v/(D+K) = Q (Z-U)^2 exp(-W (Z-U)^3) [+ q (u-Z)^2 exp(-w (u-Z)^3)]
# in SI (Q, q, W, w per m^3; U, u in m); zero above 150 km.
_FLUX = {"O": (-5.809644e-13, 56_903.11, 2.706240e-14),
         "O2": (1.366212e-13, 86_000.0, 8.333333e-14),
         "Ar": (9.434079e-14, 86_000.0, 8.333333e-14),
         "He": (-2.457369e-13, 86_000.0, 6.666667e-13)}
_FLUX_O_HUMP = (-3.416248e-12, 97_000.0, 5.008765e-13)   # atomic oxygen, below 97 km only


class StandardAir(NamedTuple):
    """The air at a height: K, Pa, kg/m^3, m/s, Pa s, kg/mol."""

    temperature: np.ndarray
    pressure: np.ndarray
    density: np.ndarray
    speed_of_sound: np.ndarray
    viscosity: np.ndarray
    molar_mass: np.ndarray


def geopotential_height(z):
    """Geopotential height H (m') of geometric height z (m), eq. 18 with r0 = 6 356 766 m."""
    z = np.asarray(z, dtype=float)
    return USSA_R0 * z / (USSA_R0 + z)


def standard_gravity(z):
    """The standard's gravity (m/s^2) at geometric height z (m), eq. 17."""
    z = np.asarray(z, dtype=float)
    return G0 * (USSA_R0 / (USSA_R0 + z)) ** 2


def sutherland_viscosity(t):
    """Dynamic viscosity (Pa s) of air at kinetic temperature t (K), eq. 51."""
    t = np.asarray(t, dtype=float)
    return USSA_SUTHERLAND_BETA * t**1.5 / (t + USSA_SUTHERLAND_S)


@functools.cache
def _layer_bases():
    """Molecular-scale temperature (K) and pressure (Pa) at each layer base."""
    tb, pb = [USSA_T0], [USSA_P0]
    for i in range(len(_H_BASE) - 1):
        dh = _H_BASE[i + 1] - _H_BASE[i]
        t_top = tb[i] + LAPSE[i] * dh
        if LAPSE[i] == 0.0:
            p_top = pb[i] * np.exp(-G0 * USSA_M0 * dh / (R_STAR * tb[i]))
        else:
            p_top = pb[i] * (tb[i] / t_top) ** (G0 * USSA_M0 / (R_STAR * LAPSE[i]))
        tb.append(t_top)
        pb.append(p_top)
    return np.array(tb), np.array(pb)


def _lower(z):
    """(T_M, p) below 86 km, eqs. 23 and 33a/33b."""
    h = geopotential_height(z)
    tb, pb = _layer_bases()
    i = np.clip(np.searchsorted(_H_BASE, h, side="right") - 1, 0, len(_H_BASE) - 1)
    lapse, dh = LAPSE[i], h - _H_BASE[i]
    tm = tb[i] + lapse * dh
    k = G0 * USSA_M0 / R_STAR
    exponent = k / np.where(lapse != 0.0, lapse, 1.0)          # (unused where lapse is 0)
    p_grad = pb[i] * (tb[i] / tm) ** exponent
    p_iso = pb[i] * np.exp(-k * dh / tb[i])
    return tm, np.where(lapse == 0.0, p_iso, p_grad)


def upper_temperature(z):
    """Kinetic temperature (K) and its gradient (K/m) at 86-1000 km, eqs. 25-32."""
    z = np.asarray(z, dtype=float)
    s = np.clip((z - _Z8) / _B_ELL, -1.0, 1.0)
    root = np.sqrt(1.0 - s * s)
    xi = (z - _Z10) * (USSA_R0 + _Z10) / (USSA_R0 + z)
    expo = np.exp(-_LAMBDA * xi)
    t = np.select([z <= _Z8, z <= _Z9, z <= _Z10],
                  [np.full_like(z, _T7), _TC + _A_ELL * root, _T9 + _LK9 * (z - _Z9)],
                  _T_INF - (_T_INF - _T10) * expo)
    with np.errstate(divide="ignore", invalid="ignore"):
        ell = -_A_ELL / _B_ELL * s / root
    dt = np.select([z <= _Z8, z <= _Z9, z <= _Z10],
                   [np.zeros_like(z), ell, np.full_like(z, _LK9)],
                   _LAMBDA * (_T_INF - _T10) * ((USSA_R0 + _Z10) / (USSA_R0 + z)) ** 2 * expo)
    return t, dt


def _integral(y, x):
    """Trapezoidal cumulative integral of ``y`` along ``x`` (1-D), starting from 0.

    The operations, in their order, of scipy's ``cumulative_trapezoid(y, x,
    initial=0)`` (bit for bit the same numbers), without importing
    scipy.integrate: every Earth flight builds this table, and that import
    would cost it half a second of start-up.
    """
    return np.concatenate(([0.0], np.cumsum(np.diff(x) * (y[1:] + y[:-1]) / 2.0)))


def _flux_term(species, z):
    q, u, w = _FLUX[species]
    v = q * (z - u) ** 2 * np.exp(-w * (z - u) ** 3)
    if species == "O":
        q2, u2, w2 = _FLUX_O_HUMP
        x = np.maximum(u2 - z, 0.0)
        v = v + q2 * x * x * np.exp(-w2 * x**3)
    return np.where(z <= 150_000.0, v, 0.0)


def number_densities(z):
    """Number densities (1/m^3) of N2, O, O2, Ar, He, H on an ascending grid z (m) from 86 km.

    The standard's eqs. 34-40 integrated with the trapezoidal rule on ``z``
    (which must start at 86 km and be fine: 25 m gives 1e-6 relative).
    """
    t, dt = upper_temperature(z)
    g = standard_gravity(z)
    mixed = z <= 100_000.0
    # M of the mixed column: M0 up to 100 km, then that of the background gas
    # (N2 for N2 itself and for O and O2, whose background is N2).
    m_n2 = np.where(mixed, USSA_M0, _MOLAR["N2"])
    # eddy diffusion: 120 m^2/s to 95 km, falling to 0 at 115 km
    x = np.clip(z - 95_000.0, 0.0, 19_999.0)
    k_eddy = np.where(z < 115_000.0, _K_EDDY * np.exp(1.0 - 4e8 / (4e8 - x * x)), 0.0)
    n = {"N2": _N86["N2"] * (_T7 / t) * np.exp(-_integral(m_n2 * g / (R_STAR * t), x=z))}
    for s in ("O", "O2", "Ar", "He"):
        if s in ("O", "O2"):
            background, m_k = n["N2"], m_n2
        else:
            # Ar and He diffuse through N2 + O + O2, whose mean M carries their mixing term
            trio = ("N2", "O", "O2")
            background = sum(n[b] for b in trio)
            m_k = np.where(mixed, USSA_M0, sum(n[b] * _MOLAR[b] for b in trio) / background)
        d = _DIFF_A[s] / background * (t / CELSIUS_ZERO) ** _DIFF_B[s]
        f = (g / (R_STAR * t)) * d / (d + k_eddy) * (
            _MOLAR[s] + m_k * k_eddy / d + _ALPHA[s] * R_STAR * dt / g) + _flux_term(s, z)
        n[s] = _N86[s] * (_T7 / t) * np.exp(-_integral(f, x=z))
    # Hydrogen (eqs. 38-40): zero below 150 km, flux-limited 150-500 km, diffusive above.
    n_h = np.zeros_like(z)
    above = z >= 150_000.0
    zh, th = z[above], t[above]
    t500 = float(upper_temperature(np.array([500_000.0]))[0][0])
    tau = _integral(_MOLAR["H"] * g[above] / (R_STAR * th), x=zh)
    tau = tau - np.interp(500_000.0, zh, tau)
    bg = sum(n[s][above] for s in ("N2", "O", "O2", "Ar", "He"))
    d_h = _DIFF_A["H"] / bg * (th / CELSIUS_ZERO) ** _DIFF_B["H"]
    expo = 1.0 + _ALPHA["H"]
    integrand = _PHI_H / d_h * (th / t500) ** expo * np.exp(tau)
    from_500 = _integral(integrand, x=zh)
    from_500 = np.interp(500_000.0, zh, from_500) - from_500     # integral from z up to 500 km
    n_h[above] = (t500 / th) ** expo * np.exp(-tau) * (_N_H500 + np.where(zh <= 500_000.0,
                                                                          from_500, 0.0))
    n["H"] = n_h
    return n


@functools.cache
def _upper_rows():
    """Rows above 86 km (25 m apart to 150 km, 125 m above): heights, ln p,
    d ln p/dZ (hydrostatic, with the local mean molar mass) and mean molar mass.

    The pressure at a row is the standard's ``p = N k T`` (eq. 33c) from the
    species densities; between rows it is the hydrostatic equation integrated
    from the row (Hermite form with the hydrostatic slope at both rows).
    """
    rows = np.concatenate((np.arange(Z_86, 150_000.0, 25.0),
                           np.arange(150_000.0, Z_MAX + 1.0, 125.0)))
    n = number_densities(rows)
    total = sum(n[s] for s in _SPECIES)
    molar = sum(n[s] * _MOLAR[s] for s in _SPECIES) / total
    t, _ = upper_temperature(rows)
    rate = -standard_gravity(rows) * molar / (R_STAR * t)
    return rows, np.log(total * USSA_BOLTZMANN * t), rate, molar


def us_standard_1976(h):
    """The 1976 standard atmosphere at geometric height ``h`` (m above mean sea level).

    Vectorised; valid from -5 km to 1 000 km (ValueError outside). Returns
    :class:`StandardAir` of arrays shaped like ``h``.
    """
    z = np.atleast_1d(np.asarray(h, dtype=float))
    if np.any(~np.isfinite(z)) or np.any(z < Z_MIN) or np.any(z > Z_MAX):
        raise ValueError("the 1976 standard atmosphere is defined from -5 km to 1000 km")
    low = z <= Z_86
    zl = np.where(low, z, Z_86)
    tm, p_low = _lower(zl)
    t_low = tm * np.interp(zl, _RATIO_Z, _RATIO, left=1.0, right=_RATIO[-1])
    rho_low = p_low * USSA_M0 / (R_STAR * tm)
    a_low = np.sqrt(USSA_GAMMA * R_STAR * tm / USSA_M0)

    zu = np.where(low, Z_86, z)
    rows, log_p, rate, molar_rows = _upper_rows()
    t_up, _ = upper_temperature(zu)
    p_up = np.exp(hermite(rows, log_p, rate, zu))
    m_up = np.interp(zu, rows, molar_rows)
    rho_up = p_up * m_up / (R_STAR * t_up)
    a_up = np.sqrt(USSA_GAMMA * R_STAR * t_up / m_up)

    t = np.where(low, t_low, t_up)
    out = StandardAir(t, np.where(low, p_low, p_up), np.where(low, rho_low, rho_up),
                      np.where(low, a_low, a_up), sutherland_viscosity(t),
                      np.where(low, USSA_M0 * t_low / tm, m_up))
    if np.ndim(h) == 0:
        return StandardAir(*(float(v[0]) for v in out))
    return out
