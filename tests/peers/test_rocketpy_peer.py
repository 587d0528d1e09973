"""A finned sounding rocket flown here and in RocketPy, a peer library used only in tests.

The rocket and both flights are built in tests/sounding_peer.py.

RocketPy (https://github.com/RocketPy-Team/RocketPy, a test-only dependency)
flies the same rocket: the same masses, the same thrust curve (our engine's
dead time, linear spool-up, constant thrust, cut-off when the usable
propellant is gone), the same drag curve against Mach on the same reference
area, the same nose and fins, vertical off a 5 m rail with no wind, in the
standard atmosphere, with Somigliana's gravity at the site's latitude (its
default). The apogees above the pad must agree within 3 %.

What differs and is not matched: RocketPy's Earth does not turn (ours does:
Coriolis and the centrifugal term are in our inertial frame), its gravity is
not J2's, and its rail replaces our pad contact; each is well under 1 % of
the apogee here.
"""

import pytest

rocketpy = pytest.importorskip("rocketpy")

from tests.sounding_peer import our_apogee, rocketpy_flight  # noqa: E402


def test_apogee_agrees_with_rocketpy_within_3_percent():
    ours, model = our_apogee()
    flight = rocketpy_flight(model)
    peer = flight.apogee - flight.z(0.0)
    print(f"\n[peer] apogee above the pad: rocketsim {ours:.1f} m, RocketPy {peer:.1f} m, "
          f"difference {100 * (ours / peer - 1):+.2f} %")
    assert ours == pytest.approx(peer, rel=0.03)
