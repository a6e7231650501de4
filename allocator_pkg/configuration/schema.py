"""The configuration schema: every parameter the allocator reads, in one table.

The same table drives the params-file loader
(:func:`allocator_pkg.configuration.parameters.load_vehicle`), the fields of the configuration
types it fills (:mod:`allocator_pkg.configuration.fields`), the node's parameter declarations
(descriptions, ranges, read-only flags) and the reference page ``docs/configuration.md``: no
default or range is written anywhere else. Parameter names are the ROS ones: dotted,
vehicle-wide keys such as ``weights.slack``, and per-actuator keys under ``actuators.<name>.``.

Values are typed the way a ROS 2 params file types them: an integer is accepted where a
float is expected, a list holds one element type, and an empty list means "not set".
"""

from __future__ import annotations

import re

from ..vehicle.config import ACTUATOR_TYPES, DOF_NAMES, FLUSHING_ZONES, METHOD_NAMES, SATURATION_MODES, Vehicle
from ..vehicle.node_settings import EXECUTORS, FRAMES, GEOMETRY_SOURCES, TRIGGERS, WRENCH_TYPES
from .actuator_keys import ACTUATOR_KEYS
from .key import BOOL, FLOAT, FLOAT_LIST, INT, INT_LIST, STR, STR_LIST, Key

ACTUATOR_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")

VEHICLE_KEYS: tuple[Key, ...] = (
    Key("rate_hz", FLOAT, "Allocation rate: one sample per period, also the dt of rate limits.",
        default=50.0, minimum=0.0, exclusive_minimum=True, maximum=10000.0, unit="Hz"),
    Key("method", STR, "Allocation method (see docs/theory.md).", default="qp", choices=METHOD_NAMES),
    Key("dofs", STR_LIST, "Controlled degrees of freedom; the others of the requested wrench are ignored.",
        default=list(DOF_NAMES), default_doc="all six",
        constraint=f"at least one of {', '.join(DOF_NAMES)}, each at most once"),
    Key("saturation", STR, "Unattainable requests: `weighted` trades DOFs by weights.slack; "
        "`preserve_direction` scales the request down along its own direction first; `direct` answers with "
        "Durham's solution on the boundary of the attainable set along the request (qp, lp, pseudoinverse).",
        default="weighted", choices=SATURATION_MODES),
    Key("weights.slack", FLOAT_LIST, "Q: weight of the wrench error of each controlled DOF, in `dofs` order (1.35).",
        default_doc="derived per DOF (see above)", minimum=0.0, exclusive_minimum=True),
    Key("priorities", INT_LIST, "DOF priorities, one integer per controlled DOF in `dofs` order, 0 the highest "
        "(e.g. [2, 2, 0, 0, 0, 1] for depth and attitude first, then yaw, then surge and sway): an unattainable "
        "request meets a higher level as far as it can before a lower one gets anything (lexicographic; see "
        "docs/theory.md). DOFs of one level are traded by weights.slack.",
        default_doc="none (all DOFs traded by weights.slack)", minimum=0.0,
        constraint="one per DOF of `dofs`; only with a method that implements priorities (qp, pseudoinverse) "
                   "and saturation weighted"),
    Key("nominal_voltage", FLOAT, "Supply voltage the thrust limits and tables with table_voltage follow at start "
        "and whenever no battery voltage is known (the node: none within battery_timeout).",
        default_doc="required with table_voltage", minimum=0.0, exclusive_minimum=True, unit="V",
        constraint="within every table_voltage range"),
    Key("weights.minimax", FLOAT, "beta: weight of the largest actuator force (1.35).", default=0.0, minimum=0.0),
    Key("weights.azimuth_change", FLOAT,
        "Omega: weight of the squared azimuth change per sample (1.44), nonlinear method.",
        default=10.0, minimum=0.0, unit="1/rad^2"),
    Key("singularity.rho", FLOAT, "rho: weight of the singularity-avoidance term (1.44), nonlinear method.",
        default=0.0, minimum=0.0),
    Key("singularity.epsilon", FLOAT, "epsilon: keeps the singularity term finite (1.44).",
        default=1e-3, minimum=0.0, exclusive_minimum=True),
    Key("azimuth_polygon_sides", INT, "Sides N of the polygon that stands for |f| <= f_max of a rotatable thruster in "
        "the QP (section 5.3); it is turned every sample to the thruster's direction, where its bound is exact, so "
        "N only shapes how forces off that direction are modelled while the thruster turns.", default=8, minimum=4,
        maximum=128),
    Key("nonlinear.max_iterations", INT, "Linearised QPs solved per sample by the nonlinear method (1.45), "
        "at most; a pass that misses the request by more than the one before ends them.",
        default=1, minimum=1, maximum=50),
    Key("dynamic.gain", FLOAT, "h of the dynamic method's update law (section 5.1): the share of the remaining "
        "error of the optimality conditions removed per sample (1: a full Newton step; changes of the request are "
        "fed forward whole).", default=0.5, minimum=0.0, exclusive_minimum=True, maximum=1.0),
    Key("svd_filter.time_constant", FLOAT, "Time constant of the filter that steers each rotatable thruster of the "
        "svd_filter method toward the direction the extended solution wants most force in (section 5.4; 0: no "
        "filter).", default=0.2, minimum=0.0, unit="s"),
    Key("svd_filter.damping_threshold", FLOAT, "epsilon of the svd_filter method: singular values of the "
        "normalised configuration matrix T(alpha) below it are damped (damped least squares), so that no force "
        "exceeds 1/epsilon of the request in units of authority and range.", default=0.05, minimum=0.0,
        exclusive_minimum=True, maximum=1.0),
    Key("explicit.regions", STR, "Method explicit: a file of its regions from `allocator-explicit precompute`, "
        "loaded when the method is set up (empty: the regions are found as requests reach them).", default="",
        constraint="a file path, or empty"),
    Key("solver.eps_abs", FLOAT, "OSQP absolute tolerance, as a fraction of each variable's range (the nonlinear "
        "method solves its linearised QPs to a tenth of it and of eps_rel).",
        default=1e-5, minimum=0.0, exclusive_minimum=True),
    Key("solver.eps_rel", FLOAT, "OSQP relative tolerance.", default=1e-5, minimum=0.0),
    Key("solver.max_iter", INT, "OSQP iteration limit per solve.", default=4000, minimum=1),
    Key("solver.time_limit", FLOAT, "OSQP time limit per solve (0: none).", default=0.0, minimum=0.0, unit="s"),
    Key("water_density", FLOAT, "rho_w in the lift and drag of control surfaces (1.48), (1.49).",
        default=1025.0, minimum=0.0, exclusive_minimum=True, unit="kg/m^3"),
    Key("flushing_zones", STR, "`dnv`: every azimuth thruster with a diameter gets the DNV-ST-0111 [3.11.3] "
        "zones of the geometry: it may not push its race onto a working thruster (not a tunnel) closer than 15 D, "
        "within arctan(0.1 + D / s); a zone lifts while the thruster it protects does not work, and pushing onto "
        "that dead thruster costs thrust instead ([3.11.4]; docs/theory.md). `none`: only the vehicle file's "
        "forbidden_sectors.", default="none", choices=FLUSHING_ZONES,
        constraint="dnv: a diameter for every azimuth thruster, no two thrusters at one horizontal position"),
    Key("bias.enabled", BOOL, "Thrust bias for calm weather: each pair of bias.pairs pushes toward each other with "
        "bias.thrust, so that at low load they hold their angles instead of hunting; the forces cancel "
        "(docs/theory.md, thrust bias). Switched at runtime without a new solver set-up.", default=False,
        constraint="with bias.pairs and bias.thrust > 0; only with method qp"),
    Key("bias.pairs", STR_LIST, "Pairs of rotatable thrusters that push against each other, as a flat list [first, "
        "second, first, second, ...].", default_doc="none", constraint="names from actuators.names: two rotatable "
        "thrusters of one type at different positions, each in one pair at most, able to push toward each other, "
        "their opposed forces free of wrench in the controlled DOFs"),
    Key("bias.thrust", FLOAT, "Force each thruster of a pair pushes toward the other with; a pair with a thruster "
        "failed, stuck or degraded to it pushes none.", default=0.0, minimum=0.0, unit="N",
        constraint="below the thrust_max of every thruster in bias.pairs"),
    Key("bias.fade_start", FLOAT, "Load up to which the bias is in full: the largest |tau_k| of the request over "
        "its DOF's authority, filtered (bias.fade_time_constant).", default=0.03, minimum=0.0, maximum=1.0,
        unit="share"),
    Key("bias.fade_end", FLOAT, "Load from which there is no bias (linear between).", default=0.06, minimum=0.0,
        exclusive_minimum=True, maximum=1.0, unit="share", constraint="above bias.fade_start"),
    Key("bias.fade_time_constant", FLOAT, "Time constant of the low-pass filter on the load the fade follows, so "
        "that the bias does not follow the gusts (0: none).", default=60.0, minimum=0.0, unit="s"),
    Key("actuators.names", STR_LIST, "Actuator names, in the order of every per-actuator array.",
        required=True, read_only=True,
        constraint="at least one; unique; letters, digits and '_', starting with a letter"),
    Key("power.sources", STR_LIST, "Power sources of the thrusters (switchboards, prime movers: the columns of "
        "DNV-ST-0111 Table A-5), each with power.<source>.capacity; with any, every thruster names its "
        "actuators.<name>.feeds. The allocation keeps each source's draw within its available power (the "
        "power_available topic, else the capacity; docs/power.md), as does the DP capability analysis.",
        default_doc="none", read_only=True,
        constraint="unique; letters, digits and '_', starting with a letter; no actuator's name"),
    Key("power.phase_back", BOOL, "With power.sources: when a source's available power drops, true holds the "
        "new bounds from the next sample, faster than thrust_rate_max allows (no source over its available power "
        "by more than rounding); false brings the thrust down at its rate limit, the source over meanwhile and "
        "allocation_status's power_limited set (docs/power.md).", default=True),
    Key("power.restore_ramp", FLOAT, "With power.sources: time in which a source's available power in use may "
        "rise from zero to its capacity. A drop holds at once (power.phase_back); when the power comes back (a "
        "higher power_available, a group fault cleared) the power the allocation uses, and with it the thrust "
        "limits, rises at most at capacity / restore_ramp per second (docs/power.md). 0: at once.", default=0.0,
        minimum=0.0, maximum=600.0, unit="s"),
    Key("power.bus_ties", STR_LIST, "Bus-tie breakers between two power.sources, each with "
        "power.bus_tie.<tie>.sources and power.bus_tie.<tie>.closed: the sources joined by closed ties are one "
        "bus, whose thrusters draw on the power of all of them; ~/set_bus_tie opens or closes one at runtime "
        "(docs/power.md).", default_doc="none", read_only=True,
        constraint="unique; letters, digits and '_', starting with a letter; only with power.sources"),
    Key("redundancy_groups.names", STR_LIST, "Redundancy groups: what one single failure takes away together "
        "(DNV-ST-0111 [2.4.8]; the DP FMEA's redundancy concept), each with redundancy_groups.<group>.sources and "
        "redundancy_groups.<group>.actuators. The node's ~/set_group_fault fails one at runtime and its consequence "
        "analysis (consequence.rate) weighs each one's loss; the DP capability analysis fails each in turn.",
        default_doc="none", read_only=True,
        constraint="unique; letters, digits and '_', starting with a letter"),
)

SOURCE_KEYS: tuple[Key, ...] = (
    Key("capacity", FLOAT, "Power the source can deliver to its consumers (Table A-5's available power).",
        required=True, minimum=0.0, exclusive_minimum=True, unit="kW", read_only=True),
)
"""Keys of each power source, ``power.<source>.<key>``."""

GROUP_KEYS: tuple[Key, ...] = (
    Key("sources", STR_LIST, "Power sources lost with the group: a thruster fed by one of them loses that "
        "feed's share of its power.", default_doc="none", read_only=True,
        constraint="names from power.sources, each at most once"),
    Key("actuators", STR_LIST, "Actuators lost with the group.", default_doc="none", read_only=True,
        constraint="names from actuators.names, each at most once; with sources, at least one of the two; every "
                   "thruster fed only by the group's sources"),
)
"""Keys of each redundancy group, ``redundancy_groups.<group>.<key>``."""

TIE_KEYS: tuple[Key, ...] = (
    Key("sources", STR_LIST, "The two power sources the breaker joins.", required=True, length=2, read_only=True,
        constraint="two different names from power.sources"),
    Key("closed", BOOL, "The breaker's state at start (and after a new configuration of it): closed joins the "
        "two sources into one bus. ~/set_bus_tie changes it at runtime.", default=True, read_only=True),
)
"""Keys of each bus-tie breaker, ``power.bus_tie.<tie>.<key>``."""

NODE_KEYS: tuple[Key, ...] = (
    Key("wrench_timeout", FLOAT, "Watchdog: with no valid wrench for this long, command zero thrust (0 disables).",
        default=0.5, minimum=0.0, unit="s"),
    Key("per_actuator_topics", BOOL, "Also publish thrusters/<name>/thrust and thrusters/<name>/azimuth "
        "(std_msgs/Float64) each sample.", default=False),
    Key("frame", STR, "Body frame convention of wrench_command, of the wrenches in allocation_status, of "
        "thrust_markers and of a URDF's geometry: `frd` x forward, y starboard, z down (marine); `flu` x forward, "
        "y left, z up (REP-103 base_link). Converted at the node's boundary: the params file's positions and "
        "directions and every azimuth angle stay FRD.", default="frd", choices=FRAMES, read_only=True),
    Key("base_frame", STR, "Name of the body frame: the frame_id stamped on every output, the frame_id a "
        "WrenchStamped must carry, and the URDF link the geometry is measured from.", default="base_link",
        read_only=True, constraint="a non-empty frame name"),
    Key("wrench_type", STR, "Message type of wrench_command: geometry_msgs/Wrench or geometry_msgs/WrenchStamped "
        "(whose frame_id must be base_frame).", default="wrench", choices=WRENCH_TYPES, read_only=True),
    Key("trigger", STR, "What starts a sample: `timer` every period of rate_hz on the latest wrench; `input` "
        "each valid wrench at once, at most rate_hz times per second (earlier ones coalesced to the latest), "
        "the timer kept as the watchdog.", default="timer", choices=TRIGGERS),
    Key("executor", STR, "The rclpy executor of the node's process: `events` (rclpy's EventsExecutor: callbacks "
        "run on events, with less CPU per sample than `single_threaded`; docs/performance.md) or "
        "`single_threaded` (rclpy's SingleThreadedExecutor, which rebuilds its wait set at every wake-up). Read "
        "when the process starts.", default="events", choices=EXECUTORS, read_only=True),
    Key("status_rate_hz", FLOAT, "How often at most allocation_status goes out: 0, every sample; above 0, at most "
        "this many times a second, the samples between not reported (thruster_commands and the diagnostics still "
        "cover every sample). Either way it is built and published only while someone subscribes.", default=0.0,
        minimum=0.0, unit="Hz"),
    Key("markers_rate_hz", FLOAT, "Rate of ~/thrust_markers (visualization_msgs/MarkerArray), built only while "
        "someone subscribes (0: never).", default=10.0, minimum=0.0, maximum=10.0, unit="Hz"),
    Key("geometry_source", STR, "Where actuator positions and fixed thrusters' directions come from: this params "
        "file, or the URDF robot description (see actuators.<name>.link).", default="params",
        choices=GEOMETRY_SOURCES, read_only=True),
    Key("battery_timeout", FLOAT, "With tables measured at several voltages: with no valid sensor_msgs/BatteryState "
        "on battery_state for this long, the thrust limits follow nominal_voltage again (diagnostics say so).",
        default=5.0, minimum=0.0, exclusive_minimum=True, unit="s"),
    Key("power_timeout", FLOAT, "With power.sources: with no valid allocator_msgs/PowerAvailable on power_available "
        "for this long the input is stale: every source's available power is held at its last valid value, or "
        "lower with power_stale_fallback, and the diagnostics are at ERROR until a valid message comes.",
        default=5.0, minimum=0.0, exclusive_minimum=True, unit="s"),
    Key("power_stale_fallback", FLOAT, "With power.sources: while power_available is stale (power_timeout), each "
        "source's available power is the lower of its last valid value and this share of its capacity: 1 holds the "
        "last valid values, below 1 assumes the sources may have lost power since.", default=1.0, minimum=0.0,
        maximum=1.0, unit="share"),
    Key("robot_description_file", STR, "URDF file read with geometry_source robot_description; empty: the "
        "robot_description topic (transient local, as robot_state_publisher offers it).", default="",
        read_only=True, constraint="a file path, or empty"),
    Key("ros2_control.thrust_topic", STR, "Topic of a std_msgs/Float64MultiArray of the thrust of the actuators of "
        "ros2_control.actuators, in that order, each sample: the commands of a ros2_control "
        "forward_command_controller (e.g. /thruster_controller/commands; docs/ros2_control.md). Empty: none.",
        default="", unit="N", constraint="a topic name, or empty"),
    Key("ros2_control.angle_topic", STR, "Topic of a std_msgs/Float64MultiArray of the azimuth angles of the "
        "rotatable thrusters of ros2_control.actuators, in that order, each sample, for a position controller. "
        "Empty: none.", default="", unit="rad",
        constraint="a topic name, or empty; only with a rotatable thruster in ros2_control.actuators"),
    Key("ros2_control.actuators", STR_LIST, "The actuators of the ros2_control topics in the controller's joint "
        "order.", default_doc="actuators.names",
        constraint="names from actuators.names, each at most once"),
    Key("consequence.rate", FLOAT, "Rate of the online consequence analysis on ~/consequence (IMO MSC/Circ.645): "
        "for each of redundancy_groups, the utilisation the actuators left after its loss would need to hold the "
        "present load, and an alarm while one exceeds 1 (docs/power.md). 0: off. Without redundancy groups there is "
        "nothing to analyse.", default=1.0, minimum=0.0, maximum=10.0, unit="Hz", constraint="0 (off) or at least 1"),
    Key("consequence.filter_time", FLOAT, "Time constant of the first-order low-pass filter of the requested wrench "
        "that the consequence analysis takes as the present load (0: the last request).", default=10.0,
        minimum=0.0, maximum=600.0, unit="s"),
    Key("step_test.enabled", BOOL, "Allow ~/hold_actuator (allocator-ctl step-test --actuators): one actuator held "
        "at a small thrust for a bounded time, every other one held out as FAILED. For a vehicle on the bench or "
        "tethered, never in operation (docs/step_test.md).", default=False),
    Key("step_test.thrust_share", FLOAT, "Largest thrust of a hold, as a share of the actuator's largest thrust "
        "magnitude (thrust_max or -thrust_min).", default=0.2, minimum=0.0, exclusive_minimum=True, maximum=0.5),
    Key("step_test.duration_max", FLOAT, "Longest hold; a hold ends by itself after its duration.", default=5.0,
        minimum=0.0, exclusive_minimum=True, maximum=30.0, unit="s"),
)
"""Settings of the ROS node only (:class:`allocator_pkg.vehicle.node_settings.NodeSettings`)."""

REPLACED_KEYS = {
    "wrench_qos": "not a parameter: wrench_command is best-effort by default, which takes reliable and "
                  "best-effort publishers alike; to change it set "
                  "qos_overrides./<namespace>/wrench_command.subscription.reliability",
}
"""Keys users reach for that this package does not have, with what does their job."""

VEHICLE_KEY_BY_NAME = {key.name: key for key in VEHICLE_KEYS}
NODE_KEY_BY_NAME = {key.name: key for key in NODE_KEYS}
ACTUATOR_KEY_BY_NAME = {key.name: key for key in ACTUATOR_KEYS}
SOURCE_KEY_BY_NAME = {key.name: key for key in SOURCE_KEYS}
GROUP_KEY_BY_NAME = {key.name: key for key in GROUP_KEYS}
TIE_KEY_BY_NAME = {key.name: key for key in TIE_KEYS}
ACTUATOR_PREFIX = "actuators."
SOURCE_PREFIX = "power."
GROUP_PREFIX = "redundancy_groups."
TIE_PREFIX = "power.bus_tie."
INSTANCE_KEYS = ((ACTUATOR_PREFIX, ACTUATOR_KEY_BY_NAME), (TIE_PREFIX, TIE_KEY_BY_NAME),
                 (SOURCE_PREFIX, SOURCE_KEY_BY_NAME), (GROUP_PREFIX, GROUP_KEY_BY_NAME))
"""The keys given per named instance, ``<prefix><instance>.<key>``: actuators, bus ties, power
sources and redundancy groups (a bus tie's prefix first: it lies inside the sources')."""


def actuator_parameter(actuator: str, key: str) -> str:
    """Full parameter name of a per-actuator key."""
    return f"{ACTUATOR_PREFIX}{actuator}.{key}"


def source_parameter(source: str, key: str) -> str:
    """Full parameter name of a power source's key."""
    return f"{SOURCE_PREFIX}{source}.{key}"


def group_parameter(group: str, key: str) -> str:
    """Full parameter name of a redundancy group's key."""
    return f"{GROUP_PREFIX}{group}.{key}"


def tie_parameter(tie: str, key: str) -> str:
    """Full parameter name of a bus tie's key."""
    return f"{TIE_PREFIX}{tie}.{key}"


def key_for(name: str) -> Key | None:
    """The key of a parameter name (``actuators.<name>.<key>``, ``power.<source>.<key>`` and
    ``redundancy_groups.<group>.<key>``, ``power.bus_tie.<tie>.<key>`` included), or None."""
    if name in VEHICLE_KEY_BY_NAME or name in NODE_KEY_BY_NAME:
        return VEHICLE_KEY_BY_NAME.get(name) or NODE_KEY_BY_NAME.get(name)
    for prefix, keys in INSTANCE_KEYS:
        key = keys.get(name[len(prefix):].partition(".")[2]) if name.startswith(prefix) else None
        if key is not None:
            return key
    return None


def instance_keys(vehicle: Vehicle) -> list[tuple[str, Key]]:
    """(parameter name, key) of every per-actuator, per-source and per-group key of a vehicle."""
    keys = [(actuator_parameter(a.name, key.name), key) for a in vehicle.actuators for key in keys_for_type(a.type)]
    keys += [(source_parameter(s.name, key.name), key) for s in vehicle.power_sources for key in SOURCE_KEYS]
    keys += [(group_parameter(g.name, key.name), key) for g in vehicle.redundancy_groups for key in GROUP_KEYS]
    keys += [(tie_parameter(t.name, key.name), key) for t in vehicle.bus_ties for key in TIE_KEYS]
    return keys


def keys_for_type(actuator_type: str) -> tuple[Key, ...]:
    """The per-actuator keys that apply to one actuator type."""
    return tuple(key for key in ACTUATOR_KEYS if actuator_type in key.applies_to)


def markdown_reference() -> str:
    """The key tables of docs/configuration.md, generated from this schema."""

    def table(keys: tuple[Key, ...], show_types: bool) -> list[str]:
        header = "| key | type | default | range | unit | meaning |"
        rule = "|---|---|---|---|---|---|"
        if show_types:
            header = "| key | type | applies to | default | range | unit | meaning |"
            rule = "|---|---|---|---|---|---|---|"
        rows = [header, rule]
        for key in keys:
            cells = [f"`{key.name}`", key.kind]
            if show_types:
                cells.append(", ".join(key.applies_to) if key.applies_to != ACTUATOR_TYPES else "all")
            cells += [key.documented_default(), key.documented_range(), key.unit,
                      key.description + (" Read-only at runtime." if key.read_only else "")]
            rows.append("| " + " | ".join(cell.replace("|", "\\|") for cell in cells) + " |")
        return rows

    lines = ["### Vehicle-wide keys", ""]
    lines += table(VEHICLE_KEYS, show_types=False)
    lines += ["", "### Node keys (only the nodes read them, not the library)", ""]
    lines += table(NODE_KEYS, show_types=False)
    lines += ["", "### Per-actuator keys (`actuators.<name>.<key>`)", ""]
    lines += table(ACTUATOR_KEYS, show_types=True)
    lines += ["", "### Power sources (`power.<source>.<key>`)", ""]
    lines += table(SOURCE_KEYS, show_types=False)
    lines += ["", "### Redundancy groups (`redundancy_groups.<group>.<key>`)", ""]
    lines += table(GROUP_KEYS, show_types=False)
    lines += ["", "### Bus ties (`power.bus_tie.<tie>.<key>`)", ""]
    lines += table(TIE_KEYS, show_types=False)
    return "\n".join(lines) + "\n"
