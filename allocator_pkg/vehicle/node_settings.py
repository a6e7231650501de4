"""Settings of the ROS node that are not part of the vehicle: the allocation library never
reads them. Parsed and checked with the vehicle (:func:`allocator_pkg.configuration.parameters.parse_parameters`)."""

from __future__ import annotations

from dataclasses import dataclass

NODE_NAME = "thrust_allocator"
"""The allocator node's default name."""

FRD = "frd"
FLU = "flu"
FRAMES = (FRD, FLU)
"""Body frame conventions: x forward, y starboard, z down (marine); x forward, y left, z up (REP-103)."""

WRENCH = "wrench"
WRENCH_STAMPED = "wrench_stamped"
WRENCH_TYPES = (WRENCH, WRENCH_STAMPED)

TIMER = "timer"
INPUT = "input"
TRIGGERS = (TIMER, INPUT)

EVENTS = "events"
SINGLE_THREADED = "single_threaded"
EXECUTORS = (EVENTS, SINGLE_THREADED)
"""rclpy executors the node's process can spin with: rclpy's EventsExecutor (callbacks on
events, no wait set rebuilt per wake-up) or its SingleThreadedExecutor."""

PARAMS = "params"
ROBOT_DESCRIPTION = "robot_description"
GEOMETRY_SOURCES = (PARAMS, ROBOT_DESCRIPTION)


@dataclass(frozen=True)
class NodeSettings:
    """The node's own settings (see the node keys of :mod:`allocator_pkg.configuration.schema`).

    ``wrench_timeout`` [s] of the stale-input watchdog (0 disables it); whether to publish one
    Float64 topic per actuator; the body frame convention ``frame`` of the wrenches in and out
    and the name ``base_frame`` stamped on the outputs; the wrench message type; what starts a
    sample (``timer`` or ``input``); how often at most the status goes out (0: every sample);
    the rate of the thrust markers (0: none); where positions and directions come from and the
    URDF file (empty: the ``robot_description`` topic); how long [s] the thrust limits follow
    the last battery voltage before they fall back to the nominal voltage; how long [s] without
    a valid power_available message before that input is stale, and the share of each source's
    capacity its available power is held at most at meanwhile (the last valid value when
    lower); the ros2_control
    topics of thrust and of azimuth angles (empty: none) and the actuators they carry, in the
    controller's joint order (every actuator in configuration order unless the key gives
    them); whether ``~/hold_actuator`` may hold one actuator at a time, at most what share of
    its largest thrust and for how long; the rate [Hz] of the consequence analysis (0: off) and
    the time constant [s] of its load filter. A dotted key fills the field of its name with '_' for
    '.' (``ros2_control.thrust_topic``: ``ros2_control_thrust_topic``;
    :mod:`allocator_pkg.configuration.fields`).
    """

    wrench_timeout: float
    per_actuator_topics: bool
    frame: str
    base_frame: str
    wrench_type: str
    trigger: str
    status_rate_hz: float
    markers_rate_hz: float
    geometry_source: str
    robot_description_file: str
    battery_timeout: float
    power_timeout: float
    power_stale_fallback: float
    ros2_control_thrust_topic: str
    ros2_control_angle_topic: str
    ros2_control_actuators: tuple[str, ...]
    step_test_enabled: bool
    executor: str
    step_test_thrust_share: float
    step_test_duration_max: float
    consequence_rate: float
    consequence_filter_time: float
