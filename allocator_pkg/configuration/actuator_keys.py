"""The per-actuator keys of the configuration schema (:mod:`.schema`), ``actuators.<name>.<key>``:
geometry, thrust range and rate, force-to-command map, power feeds, flushing, rotation and
control-surface keys, each with the actuator types it applies to."""

from __future__ import annotations

import math

from ..vehicle.config import (
    ACTUATOR_TYPES,
    COMMAND_MAPS,
    FIN,
    FIXED,
    FLOW_MODELS,
    ROTATABLE_TYPES,
    RUDDER,
    SURFACE_TYPES,
    THRUSTER_TYPES,
)
from .key import BOOL, FLOAT, FLOAT_LIST, STR, STR_LIST, Key

_ALL = ACTUATOR_TYPES
_THR = THRUSTER_TYPES
_ROT = ROTATABLE_TYPES
_SURF = SURFACE_TYPES
_DIRECTED = (FIXED, RUDDER, FIN)

ACTUATOR_KEYS: tuple[Key, ...] = (
    Key("type", STR, "Actuator type.", required=True, choices=ACTUATOR_TYPES, applies_to=_ALL, read_only=True),
    Key("position", FLOAT_LIST, "Point where the force acts, body frame x forward, y starboard, z down (FRD, "
        "whatever `frame` is). With geometry_source robot_description it comes from the URDF and must not be "
        "set.", required=True, length=3, applies_to=_ALL, unit="m"),
    Key("direction", FLOAT_LIST, "Force direction of a fixed thruster, lift direction per positive deflection "
        "of a control surface (FRD); normalised. A fixed thruster's comes from the URDF with geometry_source "
        "robot_description and must not be set then.", length=3, applies_to=_DIRECTED,
        default_doc="required for fixed; [0, 1, 0] rudder, [0, 0, 1] fin", constraint="not the zero vector",
        type_defaults={RUDDER: [0.0, 1.0, 0.0], FIN: [0.0, 0.0, 1.0]}),
    Key("link", STR, "URDF link of this actuator (geometry_source robot_description): the child link of a "
        "revolute or continuous joint at the point where the force acts. A fixed thruster's force is along "
        "that joint's axis (Gazebo's Thruster system); a rotatable thruster's joint turns it, about z "
        "(azimuth) or y (azimuth_vertical).", applies_to=_ALL, default_doc="the actuator's name",
        read_only=True, constraint="a link below base_frame through fixed joints"),
    Key("weight", FLOAT, "W_ii: weight of this actuator's squared force (1.24), (1.35).",
        minimum=0.0, exclusive_minimum=True, applies_to=_ALL, default_doc="1.0 thrusters, 0.1 control surfaces",
        type_defaults={**dict.fromkeys(_THR, 1.0), **dict.fromkeys(_SURF, 0.1)}),
    Key("power_coefficient", FLOAT, "P_i in the power estimate sum P_i |f_i|^(3/2) (1.44).",
        minimum=0.0, applies_to=_ALL, default_doc="1.0 thrusters, 0.0 control surfaces",
        type_defaults={**dict.fromkeys(_THR, 1.0), **dict.fromkeys(_SURF, 0.0)}),
    Key("reverse_power_coefficient", FLOAT, "P_i for negative thrust (a propeller backing draws another power "
        "than ahead): the drive draws P_rev |f_i|^(3/2) while f_i < 0 (docs/power.md).", minimum=0.0,
        applies_to=_THR, default_doc="power_coefficient", unit="W/N^1.5"),
    Key("drive_limit", FLOAT, "Largest power the thruster's drive may draw (its motor or frequency converter "
        "rating): its thrust is kept within (drive_limit / P)^(2/3), forward with power_coefficient and reverse "
        "with reverse_power_coefficient, a DEGRADED thruster's P counted on its set-point (docs/power.md).",
        minimum=0.0, exclusive_minimum=True, applies_to=_THR, default_doc="none", unit="kW"),
    Key("thrust_max", FLOAT, "Largest force along the actuator axis.", required=True, minimum=0.0,
        exclusive_minimum=True, applies_to=_THR, unit="N"),
    Key("thrust_min", FLOAT, "Most negative force along the axis (<= 0).", maximum=0.0, applies_to=_THR,
        default_doc="-thrust_max (fixed, or reversible rotatable); 0 otherwise", unit="N"),
    Key("thrust_rate_max", FLOAT, "Largest force change per second (0: unlimited).", default=0.0, minimum=0.0,
        applies_to=_THR, unit="N/s"),
    Key("command_map", STR, "Force-to-command map: `linear` F = k u (1.3), `quadratic` F = k|u|u (1.4), "
        "`table` from measured pairs.", default="linear", choices=COMMAND_MAPS, applies_to=_THR),
    Key("gain", FLOAT, "k of the linear or quadratic map for positive force.", default=1.0, minimum=0.0,
        exclusive_minimum=True, applies_to=_THR),
    Key("gain_reverse", FLOAT, "k for negative force (asymmetric propellers).", minimum=0.0,
        exclusive_minimum=True, applies_to=_THR, default_doc="gain"),
    Key("command_min", FLOAT, "Smallest actuator set-point; limits the force too.", applies_to=_THR,
        default_doc="no limit", constraint="below command_max, at or below the set-point of zero force"),
    Key("command_max", FLOAT, "Largest actuator set-point; limits the force too.", applies_to=_THR,
        default_doc="no limit", constraint="above command_min, at or above the set-point of zero force"),
    Key("table_command", FLOAT_LIST, "Measured set-points, strictly increasing (`table` map).", applies_to=_THR,
        default_doc="required for table", constraint="at least 2, strictly increasing"),
    Key("table_thrust", FLOAT_LIST, "Measured force at each set-point (`table` map); with table_voltage one such "
        "row per voltage, row after row (ROS parameters cannot nest lists).",
        applies_to=_THR, default_doc="required for table", unit="N",
        constraint="one per table_command (per voltage), each row non-decreasing and spanning 0"),
    Key("table_voltage", FLOAT_LIST, "Supply voltages at which the rows of table_thrust were measured: the curve in "
        "use is interpolated between the two around the battery voltage, and the thrust limits follow it.",
        applies_to=_THR, default_doc="none (one curve)", unit="V",
        constraint="strictly increasing, positive; only with command_map table"),
    Key("command_deadband", FLOAT, "Smallest command magnitude that turns the propeller (`linear` and `quadratic` "
        "maps; a table's flat stretch is its own dead band): a force that would need less is commanded as zero "
        "or as the band's edge, whichever is nearer (docs/theory.md).", default=0.0, minimum=0.0,
        applies_to=_THR, constraint="below command_max and above command_min in magnitude"),
    Key("reversed", BOOL, "The thruster is wired or propped backwards: its command is mirrored about the "
        "set-point of zero force (0, or a table's neutral), its force model unchanged (ArduSub's MOT_n_DIRECTION).",
        default=False, applies_to=_THR),
    Key("feeds", STR_LIST, "Power sources this thruster draws from (its row of DNV-ST-0111 Table A-5): the "
        "allocation and the DP capability analysis draw its power from them (docs/power.md).",
        applies_to=_THR, default_doc="none", read_only=True,
        constraint="names from power.sources, each at most once; required for every thruster when power.sources "
                   "is set"),
    Key("feed_shares", FLOAT_LIST, "Share of this thruster's power from each of its feeds, in feeds order (a split "
        "feed).", applies_to=_THR, default_doc="[1] with one feed; required with more", minimum=0.0,
        exclusive_minimum=True, read_only=True, constraint="one per feed, summing to 1"),
    Key("azimuth_min", FLOAT, "Feasible sector, lower end (the thruster cannot turn outside it).",
        default=-math.pi, applies_to=_ROT, unit="rad", constraint="below azimuth_max"),
    Key("azimuth_max", FLOAT, "Feasible sector, upper end; azimuth_max - azimuth_min = 2 pi means free rotation.",
        default=math.pi, applies_to=_ROT, unit="rad", constraint="above azimuth_min, at most 2 pi above it"),
    Key("azimuth_rate_max", FLOAT, "Largest turning rate (0: unlimited).", default=0.0, minimum=0.0,
        applies_to=_ROT, unit="rad/s"),
    Key("forbidden_sectors", FLOAT_LIST, "Flat list of [start, end] pairs: angles, counter-clockwise from start "
        "to end, at which the thruster must not produce thrust (it may turn through them at zero thrust).",
        applies_to=_ROT, default_doc="none", unit="rad", constraint="an even number of angles: [start, end] pairs"),
    Key("protects", STR_LIST, "The thruster each [start, end] pair of forbidden_sectors keeps this one from "
        "flushing, in order: the sector is in force only while that thruster works (its force range in force is "
        "not zero); an empty name keeps its sector always.", applies_to=_ROT,
        default_doc="none (every sector always in force)",
        constraint="one per sector; names from actuators.names other than this one, or empty"),
    Key("diameter", FLOAT, "Propeller diameter D, for the flushing zones of flushing_zones dnv ([3.11.3], "
        "[3.11.4]), and DNV-ST-0111 Level 1's D where the particulars file gives none.", default=0.0,
        minimum=0.0, applies_to=_THR, unit="m", default_doc="0 (none)"),
    Key("ducted", BOOL, "The propeller runs in a nozzle: [3.11.4]'s narrower loss sector, within 4 D instead "
        "of 8 D (flushing_zones dnv); DNV-ST-0111 Level 1's duct where the particulars file gives none.",
        default=False, applies_to=_THR),
    Key("tunnel", BOOL, "A tunnel thruster: others may flush it ([3.11.3], [3.11.4]; flushing_zones dnv).",
        default=False, applies_to=(FIXED,)),
    Key("reversible", BOOL, "Whether negative thrust along the current angle is allowed.", default=False,
        applies_to=_ROT),
    Key("azimuth_initial", FLOAT, "Angle at start-up; inside the feasible sector, outside forbidden ones.",
        default=0.0, applies_to=_ROT, unit="rad", constraint="in the feasible sector, outside forbidden ones"),
    Key("area", FLOAT, "Foil area A (1.48).", required=True, minimum=0.0, exclusive_minimum=True,
        applies_to=_SURF, unit="m^2"),
    Key("lift_coefficient", FLOAT, "C_L, lift per radian of deflection (1.48).", required=True, minimum=0.0,
        exclusive_minimum=True, applies_to=_SURF, unit="1/rad"),
    Key("drag_coefficient", FLOAT, "C_D, drag per squared radian of deflection (1.49).", default=0.0,
        minimum=0.0, applies_to=_SURF, unit="1/rad^2"),
    Key("deflection_max", FLOAT, "Largest deflection either way.", required=True, minimum=0.0,
        exclusive_minimum=True, maximum=math.pi / 2, applies_to=_SURF, unit="rad"),
    Key("deflection_rate_max", FLOAT, "Largest deflection rate (0: unlimited).", default=0.0, minimum=0.0,
        applies_to=_SURF, unit="rad/s"),
    Key("flow", STR, "Flow speed model: `free` uses the vehicle surge speed, `propeller_wake` multiplies it by "
        "wake_speed_factor.", default="free", choices=FLOW_MODELS, applies_to=_SURF),
    Key("wake_speed_factor", FLOAT, "u_f / u for `propeller_wake` surfaces.", default=1.0, minimum=0.0,
        exclusive_minimum=True, applies_to=_SURF),
    Key("min_control_speed", FLOAT, "Below this flow speed the surface produces nothing and is unavailable.",
        default=0.5, minimum=0.0, applies_to=_SURF, unit="m/s"),
)
