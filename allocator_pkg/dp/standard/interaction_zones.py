"""Forbidden zones of DNV-ST-0111 Level 1 [3.11.3]: no thruster may flush a working thruster.

Thruster i flushes thruster j when the angle between i's thrust direction and the vector from j
to i is less than arctan(0.1 + D / s), D the diameter of i and s the horizontal distance between
them: pushing away from j sends i's race onto j. This is not allowed closer than 15 D unless j
is a tunnel thruster (flushed tunnels are exempt). So each such pair gives i a forbidden sector
of that half-angle around the direction from j to i (the sector's edges allowed: "less than").

The zones are geometry only: computed among the thrusters that work in a failure case, a zone
lifts with the thruster it protects. Angles here are thrust angles in the body frame (FRD):
0 forward, pi/2 to starboard, the angle of a rotatable thruster; the sector of the standard's
Figure A-4 / Table A-6 mirrored (y to port there).

The geometry is the effectiveness layer's (:mod:`allocator_pkg.effectiveness.flushing`), which
the allocator's runtime zones use too. After the public transcription of [3.11.3] in the
repository WilliamBoland1/Prosjektoppgave_Collab
(``dp_capability/models/Descriptions/forbidden_zones.md``); not verified by DNV.
"""

from ...effectiveness.flushing import FLUSHING_DISTANCE, Unit, Zone, flushing_zones, half_angle

__all__ = ["FLUSHING_DISTANCE", "Unit", "Zone", "flushing_zones", "half_angle"]
