"""The lines a DNV-ST-0111 Level 1 or 2 output gives about its inputs: the hull
(:func:`hull_note`), each thruster (:func:`thruster_note`) and each power source
(:func:`source_note`)."""

from __future__ import annotations

import math
from collections.abc import Mapping

from .inputs.particulars import Particulars
from .standard.loads import C_WL_AFT_RANGE, TZ_FROM_TP
from .standard.power_balance import usable
from .standard.thrust import ThrusterData


def hull_note(particulars: Particulars) -> str:
    """The hull in the standard's frame, the body origin and the Tz-Tp relation [3.3.3]."""
    hull, frame = particulars.hull, particulars.frame
    c_wl = hull.waterplane_coefficient_aft
    clipped = not C_WL_AFT_RANGE[0] <= c_wl <= C_WL_AFT_RANGE[1]
    return (f"Hull (standard's frame, x from Lpp/2): Lpp {hull.lpp:g} m, B {hull.beam:g} m, T {hull.draught:g} m, "
            f"Los {hull.los:g} m at x {hull.los_centre_x:g} m, bow angle {math.degrees(hull.bow_angle):g} deg, "
            f"A_WLaft {hull.waterplane_area_aft:g} m^2 (C_WLaft {c_wl:.3f}"
            + (f", clipped to [{C_WL_AFT_RANGE[0]:g}, {C_WL_AFT_RANGE[1]:g}] by [3.7]" if clipped else "")
            + f"), wind areas {hull.wind_area_frontal:g} and {hull.wind_area_lateral:g} m^2 "
            f"(centre x {hull.wind_centre_x:g} m), A_L,current {hull.current_area_lateral:g} m^2 "
            f"(centre x {hull.current_centre_x:g} m); the vehicle file's body origin at x {frame.origin_x:g} m, "
            f"{frame.origin_height:g} m above the keel; Tz = Tp / {TZ_FROM_TP}.")


def thruster_note(data: ThrusterData, forward: float, reverse: float, x: float, submergence: float) -> str:
    """One thruster: type, D, P_B, nominal thrust [N] each way, x from Lpp/2 and submergence [m]."""
    return (f"{data.name} {data.kind} D {data.diameter:g} m P_B {data.power:g} kW: {forward / 1e3:.1f} / "
            f"{reverse / 1e3:.1f}, x {x:g}, {submergence:g}")


def source_note(source: str, capacity: float, demands: Mapping[str, float]) -> str:
    """One power source: capacity, usable power after the reserve of [3.12.3], and per case
    (``demands``: case -> kW its working thrusters draw at full thrust) whether it can bind."""
    limit = usable(capacity)
    return (f"{source} {capacity:g} kW, {limit:g} kW usable: "
            + ", ".join(f"{case} {value:.1f} kW at full thrust"
                        + (" (can limit the balance)" if value > limit else "") for case, value in demands.items()))
