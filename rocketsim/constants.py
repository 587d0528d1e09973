"""Every physical constant of the simulator, once, with its source.

SI units throughout (m, kg, s, rad, K, Pa) unless a name says otherwise.
Other modules import from here; no constant is written twice.
"""

import math

# --- Mathematics and time ---------------------------------------------------
DEG = math.pi / 180.0                      # rad per degree
ARCSEC = DEG / 3600.0                      # rad per arcsecond
SECONDS_PER_DAY = 86400.0
# mean tropical year, equinox to equinox: the mean Sun's period in right ascension
# (Vallado, Fundamentals of Astrodynamics and Applications, 4th ed., 365.242 189 7 d)
TROPICAL_YEAR = 365.2421897 * SECONDS_PER_DAY     # s
J2000_JD = 2451545.0                       # Julian date of J2000.0 (TT)
DAYS_PER_JULIAN_CENTURY = 36525.0
DAYS_PER_JULIAN_MILLENNIUM = 365250.0
AU = 149_597_870_700.0                     # m, IAU 2012 Resolution B2

# --- Universal --------------------------------------------------------------
G0 = 9.80665                               # m/s^2, standard gravity (CGPM 1901)
ATMOSPHERE = 101_325.0                     # Pa, one standard atmosphere (CGPM 1954, Resolution 4)
CELSIUS_ZERO = 273.15                      # K, 0 degrees Celsius (SI Brochure, 9th ed., 2.3.1)
NAUTICAL_MILE = 1852.0                     # m, international nautical mile (IHB 1929; SI Brochure Table 8)
KNOT = NAUTICAL_MILE / 3600.0              # m/s, one nautical mile per hour
GAS_CONSTANT_USSA = 8.31432                # J/(mol K), US Standard Atmosphere 1976
STEFAN_BOLTZMANN = 5.670374419e-8          # W/(m^2 K^4), CODATA 2018

# --- Earth: WGS84 ellipsoid (NIMA TR8350.2) and EGM96 J2 --------------------
EARTH_MU = 3.986004418e14                  # m^3/s^2, WGS84 (with atmosphere)
EARTH_RADIUS_EQ = 6_378_137.0              # m, WGS84 semi-major axis a
EARTH_FLATTENING = 1.0 / 298.257223563     # WGS84 f
EARTH_E2 = EARTH_FLATTENING * (2.0 - EARTH_FLATTENING)   # first eccentricity^2
EARTH_RADIUS_POLAR = EARTH_RADIUS_EQ * (1.0 - EARTH_FLATTENING)  # m, b
EARTH_J2 = 1.08262668e-3                   # EGM96 unnormalised C20 (negated)
EARTH_OMEGA = 7.2921159e-5                 # rad/s, WGS84 rotation rate

# Somigliana normal gravity on the WGS84 ellipsoid (NIMA TR8350.2, eq. 4-1)
WGS84_GAMMA_EQ = 9.7803253359              # m/s^2 at the equator
WGS84_SOMIGLIANA_K = 0.00193185265241
WGS84_E2_SOMIGLIANA = 0.00669437999013

# --- Moon (JPL DE430, GRAIL GL0660B) ----------------------------------------
MOON_MU = 4.902800118e12                   # m^3/s^2
MOON_RADIUS = 1_737_400.0                  # m, mean sphere
MOON_J2 = 2.033053e-4

# --- Mars (JPL DE440; IAU WGCCRE 2015 shape) ---------------------------------
MARS_MU = 4.282837362e13                   # m^3/s^2
MARS_RADIUS_EQ = 3_396_190.0               # m
MARS_FLATTENING = 1.0 / 169.894
MARS_J2 = 1.95545e-3

# --- Sun (DE430) --------------------------------------------------------------
SUN_MU = 1.32712440018e20                  # m^3/s^2

# --- Integrator (docs/physics.md#integrator) ---------------------------------
STEP = 0.02                                # s, the flight model's fixed step
MAX_HEADLESS_STEP = 0.1                    # s, largest step a headless run accepts
MIN_STEP = 1e-4                            # s, smallest step: 1/200 of STEP (a shorter one is a typo
                                           # that would turn a flight into billions of steps)
MAX_DURATION = 100 * 365.25 * 86400.0      # s, longest mission time, a century (a flight's, an
                                           # fc.sleep's): step counts stay exact integers
MAX_START_DISTANCE = 1e13                  # m, farthest start from the central body (~67 au,
                                           # past Neptune): the state's squares stay finite
MAX_START_SPEED = 1e6                      # m/s, fastest start (1 000 km/s: no body of the
                                           # solar system moves a fifth as fast)
GROUND_SUBSTEP_HEIGHT = 2.0                # m, below this height the step is split
GROUND_SUBSTEPS = 4                        # sub-steps within GROUND_SUBSTEP_HEIGHT
GROUND_SUBSTEP_MAX = 0.005                 # s, longest sub-step there at any step size

# --- Atmospheres (rocketsim.atmosphere) --------------------------------------
# US Standard Atmosphere 1976 (NOAA-S/T 76-1562), section 1.2 and Table 2.
USSA_R0 = 6_356_766.0                      # m, effective Earth radius for geopotential height
USSA_M0 = 0.0289644                        # kg/mol, sea-level mean molar mass of air
USSA_T0 = 288.15                           # K, sea-level temperature
USSA_P0 = ATMOSPHERE                       # Pa, sea-level pressure
USSA_RHO0 = 1.225                          # kg/m^3, sea-level density (Table I: 1.2250)
USSA_MEAN_FREE_PATH0 = 6.6328e-8           # m, sea-level mean free path (Table I)
USSA_GAMMA = 1.40                          # ratio of specific heats of air
USSA_BOLTZMANN = 1.380622e-23              # J/K, the standard's Boltzmann constant (p = N k T)
USSA_SUTHERLAND_BETA = 1.458e-6            # kg/(m s K^0.5), viscosity law eq. 51
USSA_SUTHERLAND_S = 110.4                  # K, Sutherland's constant, eq. 51
# Moist air: ratio of the molar masses of water vapour and dry air (WMO-No. 8,
# annex 4.B: epsilon = 0.621 98).
WATER_AIR_MOLAR_RATIO = 0.62198
# Mars atmosphere, NASA Glenn Research Center engineering model
# (www.grc.nasa.gov/www/k-12/airplane/atmosmrm.html): the density formula's
# gas constant 192.1 J/(kg K) (0.1921 in kPa units) and the 273.1 offset.
MARS_GAS_CONSTANT_DENSITY = 192.1          # J/(kg K), Glenn model's density formula
MARS_GAS_CONSTANT_SOUND = 188.92           # J/(kg K), CO2: 8.314 46 / 0.044 01 (speed of sound)
MARS_CELSIUS_OFFSET = 273.1                # K, as written in the Glenn formula (not 273.15)
# Ratio of specific heats of ideal-gas CO2 at 220 K, mid-range of the Martian
# air (cp = 33.4 J/(mol K), NIST-JANAF): 1.29 at 300 K, 1.37 at 150 K, so
# +-0.04 (+-1.5 % in the speed of sound).
MARS_GAMMA = 1.33
# CO2 viscosity, Sutherland's law mu = mu0 (T/T0)^1.5 (T0 + S)/(T + S)
# (F. M. White, Viscous Fluid Flow, 3rd ed., Table 1-2).
CO2_VISCOSITY_REF = 1.370e-5               # Pa s at CO2_VISCOSITY_T0
CO2_VISCOSITY_T0 = 273.0                   # K
CO2_SUTHERLAND_S = 222.0                   # K

# --- Vehicles and engines (rocketsim.vehicle; docs/physics.md#propulsion and
# docs/physics.md#mass-properties) ---------------------------------------------
UNUSABLE_PROPELLANT = 0.01                 # fraction of each stage's load that cannot be burned
LIQUID_ROLL_INERTIA_FRACTION = 0.10        # share of a liquid column's own roll inertia counted
ENGINE_TAIL_OFF = 0.25                     # s, shutdown to zero thrust
# Summerfield criterion for free shock separation in an over-expanded nozzle:
# the flow separates where the wall pressure falls below about 0.4 of the
# ambient pressure, p_e < 0.4 p_a (M. Summerfield, C. R. Foster, W. C. Swan,
# "Flow separation in overexpanded supersonic exhaust nozzles", Jet Propulsion
# 24 (1954) 319-321; Sutton & Biblarz, Rocket Propulsion Elements, 9th ed., 3.3).
SUMMERFIELD_SEPARATION_RATIO = 0.4

# --- Rails, cruise rails, the n-body field (docs/physics.md#sleep-rails,
# docs/physics.md#cruise-rails, docs/physics.md#n-body-field) ---------------
RAILS_FLOOR = 151_000.0                    # m, a sleeping body goes on rails above this height
NBODY_HOLD = 5.0                           # s of mission time the other bodies' positions are held
CRUISE_TURN_PER_SUBSTEP = 0.02             # rad, a cruise sub-step turns the path by about this
CRUISE_MIN_SUBSTEP = 5.0                   # s, a cruise sub-step never lasts less
CRUISE_MAX_STEP = 3600.0                   # s, longest cruise step
CRUISE_MAX_TURN = 0.5 * DEG                # rad, most a cruise step may turn the path
CRUISE_CLEARANCE = 2_000_000.0             # m, clearance shell above every body's radius
SUN_RADIUS = 695_700_000.0                 # m, IAU 2015 Resolution B3 nominal solar radius
# Semi-major axes for the spheres of influence r_SOI = a (mu/mu_parent)^(2/5):
# Earth-Moon barycentre and Mars, E. M. Standish, "Keplerian Elements for
# Approximate Positions of the Major Planets" (JPL SSD), Table 1 (J2000);
# the Moon's mean distance, NASA Moon Fact Sheet (0.3844e6 km).
EARTH_ORBIT_A = 1.00000261 * AU            # m
MARS_ORBIT_A = 1.52371034 * AU             # m
MOON_ORBIT_A = 384_400_000.0               # m
# Solar radiation pressure: total solar irradiance at 1 AU, 1361 W/m^2
# (G. Kopp & J. Lean, GRL 38, L01706, 2011), over c (SI exact).
SPEED_OF_LIGHT = 299_792_458.0             # m/s
SOLAR_IRRADIANCE_1AU = 1361.0              # W/m^2

# --- Aerodynamics, heating, structure, contact (docs/physics.md#heating,
# docs/physics.md#structural-limits, docs/physics.md#ground-contact) ---------
# Sutton-Graves stagnation-point heating q = k sqrt(rho / r_n) v^3 (SI, W/m^2):
# K. Sutton & R. A. Graves, "A general stagnation-point convective heating
# equation for arbitrary gas mixtures", NASA TR R-376 (1971): the constants
# for air and for the Mars (CO2) mixture.
SUTTON_GRAVES_EARTH = 1.7415e-4            # kg^0.5 / m (SI units of the relation)
SUTTON_GRAVES_MARS = 1.9027e-4
HEAT_SHIELD_LIMIT = 2400.0                 # K, a lumped heat shield fails above this
STRUCTURE_Q_ALPHA_LIMIT = 250_000.0        # Pa deg, bending load q alpha that breaks the vehicle
STRUCTURE_AXIAL_LIMIT_G = 15.0             # axial load (in g0) that breaks the vehicle
# Specific heat of air at constant pressure for the hot-wall enthalpy ratio
# h_w / h_0 (ideal diatomic gas, 7/2 R/M with the US 1976 constants: 1004.7).
AIR_CP = 1004.7                            # J/(kg K)
CO2_CP = 846.0                             # J/(kg K), CO2 near 300 K (NIST webbook)
# Coulomb friction of a contact is regularised below this sliding speed
# (F = -mu N v_t / sqrt(v_t^2 + eps^2)): a default for legs that give none; a
# numerical choice (stability at the 5 ms sub-step), not a physical figure.
FRICTION_REGULARISATION = 0.3              # m/s
# The body's own contact springs (its ends and engine bells on the ground), unless the
# vehicle file gives them: 2e7 N/m and 2e5 N s/m, softened for a vehicle of dry mass m
# under 2 t to m r^2 and m r with r = 100 /s (a natural frequency of 100 rad/s at half
# of critical damping on one point, as at 2 t; launcher-sized springs on a 20 kg rocket
# are a mode of 1 000 rad/s, which RK4 cannot hold at the 5 ms ground sub-steps, 400 /s
# at most). Numerical choices, not physical figures.
BODY_CONTACT_STIFFNESS = 2.0e7             # N/m
BODY_CONTACT_DAMPING = 2.0e5               # N s/m
BODY_CONTACT_RATE = 100.0                  # 1/s
