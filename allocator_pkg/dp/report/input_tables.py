"""The input tables of a DNV-ST-0111 Level 1 report (App. A.3) in the standard's layout, as the
transcription lists their fields (Tables A-2 to A-5, pages 71-73).

- :func:`table_a2`: the hull data, one row per quantity (``quantity``, ``symbol``, ``value``,
  ``unit``), positions x [m] forward of Lpp/2;
- :func:`table_a3`: one row per actuator: its position ([3.8.3]) in the frame of [2.8.2] (x
  forward of Lpp/2, y to port, z above the keel), type, D, P_B, pitch, duct, contra-rotation,
  permanent magnet, tunnel inlet, and the nominal thrust of [3.9.2] each way;
- :func:`table_a4`: one row per rudder behind a shaft line ([3.10]): the propeller, profile, A_r,
  k1 (Table 3-5), k2 (Table 3-6), the largest angle [3.10.1] uses (the vehicle file's, at most
  30 deg) and the side force there at the propeller's forward T_nominal [3.9.2],
  T_nominal C_Y alpha_max;
- :func:`table_a5`: what each thruster can consume from each switchboard or prime mover: one row
  per thruster, per source its share [%] and that share of P_B [kW]; then each source's available
  power and what is usable after the reserve of [3.12.3].

Everything comes from the vehicle file (positions, feeds, capacities) and the particulars file
(hull, thruster data), converted to the standard's frame. Not verified by DNV.
"""

from __future__ import annotations

import math

from ..level1 import Level1
from ..standard.power_balance import usable
from ..standard.rudders import K1, K2_FIXED_NOZZLE, RUDDER_ANGLE_CAP_DEG

NOT_GIVEN = "not given"
A2_COLUMNS = ("quantity", "symbol", "value", "unit")
A3_COLUMNS = ("thruster", "type", "x_m", "y_m", "z_m", "diameter_m", "p_b_kw", "pitch", "ducted", "contra_rotating",
              "permanent_magnet", "tunnel_inlet", "t_nominal_kn", "t_nominal_reversed_kn")
A4_COLUMNS = ("rudder", "propeller", "profile", "a_r_m2", "k1", "k2", "max_angle_deg", "max_side_force_kn")
AVAILABLE, USABLE = "available power [kW]", "usable after the 10 % reserve [kW]"


def table_a2(analysis: Level1) -> list[tuple]:
    """(quantity, symbol, value, unit) of Table A-2; x from Lpp/2, forward positive, y to port. Loa and
    A_F,current are not inputs of this Level 1 and say so; the aft most point of each skeg ([3.11.5]) is
    two rows, x and y (none given: one row saying so)."""
    hull, frame = analysis.particulars.hull, analysis.particulars.frame
    skegs = [row for k, skeg in enumerate(analysis.particulars.skegs, 1)
             for row in ((f"aft most point of skeg {k}, x from Lpp/2", f"x_skeg,{k}", frame.standard_x(skeg.x), "m"),
                         (f"aft most point of skeg {k}, y (to port)", f"y_skeg,{k}", 0.0 - skeg.y, "m"))]
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
        *(skegs or [("aft most point of each skeg", "skegs", "none given (no [3.11.5] loss)", "m")]),
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


def table_a4(analysis: Level1) -> list[tuple]:
    """One row per rudder behind a shaft line of Table A-4 (:data:`A4_COLUMNS`): the rudder, its
    propeller, profile, A_r [m^2], k1, k2, the largest angle [deg] of [3.10.1] and the side force
    [kN] there at the propeller's forward T_nominal."""
    rows = []
    for propeller, pair in analysis.rudders.items():
        data = analysis.particulars.rudders[pair.rudder]
        angle = min(pair.fan.max_angle_deg, RUDDER_ANGLE_CAP_DEG)
        rows.append((pair.rudder, propeller, data.profile, data.area, K1[data.profile],
                     K2_FIXED_NOZZLE if data.behind_fixed_nozzle else 1.0, angle,
                     analysis.actuators[propeller].forward * pair.fan.c_y * angle / 1e3))
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
