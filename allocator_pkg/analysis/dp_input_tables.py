"""The input tables of a DNV-ST-0111 Level 1 report (App. A.3) in the standard's layout, as the
transcription lists their fields (Tables A-2 to A-5, pages 71-73).

- :func:`table_a2`: the hull data, one row per quantity (``quantity``, ``symbol``, ``value``,
  ``unit``), positions x [m] forward of Lpp/2;
- :func:`table_a3`: one row per actuator: its position ([3.8.3]) in the frame of [2.8.2] (x
  forward of Lpp/2, y to port, z above the keel), type, D, P_B, pitch, duct, contra-rotation,
  permanent magnet, tunnel inlet, and the nominal thrust of [3.9.2] each way;
- Table A-4, the rudder data (profile, A_r, k1, k2, maximum angle, side force): :data:`A4_COLUMNS`,
  no rows, since this Level 1 takes no rudders ([3.10] not computed);
- :func:`table_a5`: what each thruster can consume from each switchboard or prime mover: one row
  per thruster, per source its share [%] and that share of P_B [kW]; then each source's available
  power and what is usable after the reserve of [3.12.3].

Everything comes from the vehicle file (positions, feeds, capacities) and the particulars file
(hull, thruster data), converted to the standard's frame. Not verified by DNV.
"""

from __future__ import annotations

import math

from .dnv_power import usable
from .dp_capability import Level1

NOT_GIVEN = "not given"
A2_COLUMNS = ("quantity", "symbol", "value", "unit")
A3_COLUMNS = ("thruster", "type", "x_m", "y_m", "z_m", "diameter_m", "p_b_kw", "pitch", "ducted", "contra_rotating",
              "permanent_magnet", "tunnel_inlet", "t_nominal_kn", "t_nominal_reversed_kn")
A4_COLUMNS = ("thruster", "profile", "a_r_m2", "k1", "k2", "max_angle_deg", "max_side_force_kn")
AVAILABLE, USABLE = "available power [kW]", "usable after the 10 % reserve [kW]"


def table_a2(analysis: Level1) -> list[tuple]:
    """(quantity, symbol, value, unit) of Table A-2; x from Lpp/2, forward positive. Loa, A_F,current
    and the skegs are not inputs of this Level 1 and say so."""
    hull = analysis.particulars.hull
    return [
        ("length over all", "Loa", f"{NOT_GIVEN} (not used)", "m"),
        ("length between perpendiculars", "Lpp", hull.lpp, "m"),
        ("draught", "T", hull.draught, "m"),
        ("breadth at the waterline", "B", hull.beam, "m"),
        ("distance between the foremost and aftmost points under water", "Los", hull.los, "m"),
        ("x of Los/2 from Lpp/2", "x_Los", hull.los_centre_x, "m"),
        ("bow angle (Figure 3-2)", "bow angle", math.degrees(hull.bow_angle), "deg"),
        ("waterplane area aft of Lpp/2", "A_WLaft", hull.waterplane_area_aft, "m^2"),
        ("frontal projected area above water", "A_F,wind", hull.wind_area_frontal, "m^2"),
        ("longitudinal projected area above water", "A_L,wind", hull.wind_area_lateral, "m^2"),
        ("x of the centre of A_L,wind from Lpp/2", "x_L,air", hull.wind_centre_x, "m"),
        ("frontal projected area below water", "A_F,current", f"{NOT_GIVEN} ([3.6] uses B T)", "m^2"),
        ("longitudinal projected area below water", "A_L,current", hull.current_area_lateral, "m^2"),
        ("x of the centre of A_L,current from Lpp/2", "x_L,current", hull.current_centre_x, "m"),
        ("aftmost point of each skeg", "skegs", f"{NOT_GIVEN} ([3.11.5] not computed)", "m"),
    ]


def table_a3(analysis: Level1) -> list[tuple]:
    """One row per actuator of Table A-3 (:data:`A3_COLUMNS`): the vehicle file's position in the
    standard's frame, the particulars' data, T_nominal [kN] forward and reversed (0: not reversed)."""
    frame = analysis.particulars.frame
    rows = []
    for name, unit in analysis.actuators.items():
        data = analysis.particulars.thrusters[name]
        x, y, z = unit.config.position
        rows.append((name, data.kind, frame.standard_x(x), 0.0 - y, frame.height(z), data.diameter, data.power,
                     data.pitch, data.ducted, data.contra_rotating, data.permanent_magnet, data.tunnel_inlet or "",
                     unit.forward / 1e3, unit.reverse / 1e3))
    return rows


def a5_columns(analysis: Level1) -> tuple[str, ...]:
    """thruster, p_b_kw, then per source ``<source>_share_pct`` and ``<source>_kw``."""
    return ("thruster", "p_b_kw", *(f"{source}_{what}" for source in analysis.capacities
                                    for what in ("share_pct", "kw")))


def table_a5(analysis: Level1) -> list[tuple]:
    """Table A-5 (:func:`a5_columns`): per thruster its P_B and, per source, the share of it and the
    power [kW] it can consume from there; then a row of each source's available power and one of
    its usable power after the 10 % reserve [3.12.3]."""
    rows = []
    for name, unit in analysis.actuators.items():
        power = analysis.particulars.thrusters[name].power
        shares = dict(zip(unit.config.feeds, unit.config.feed_shares))
        rows.append((name, power, *(value for source in analysis.capacities
                                    for value in (100.0 * shares.get(source, 0.0), power * shares.get(source, 0.0)))))
    for label, value in ((AVAILABLE, lambda c: c), (USABLE, usable)):
        rows.append((label, "", *(cell for capacity in analysis.capacities.values() for cell in ("", value(capacity)))))
    return rows
