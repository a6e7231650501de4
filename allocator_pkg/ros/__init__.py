"""The ROS 2 boundary: topics, timers and one sample per trigger (``runtime``) with its outputs
and their rates (``outputs``), the supply voltage input (``battery``) and the bench's actuator
hold (``hold``); services, parameters and loading shared by both nodes (``node_base``) and
their process's main loop and executor (``main_loop``); the plain and the managed node
(``node``, ``lifecycle_node``), parameters as ROS descriptors (``ros_parameters``), messages
(``conversions``, ``markers``, ``diagnostics``), the accepted wrench input (``wrench_input``),
QoS profiles (``qos``), per-actuator topics (``actuator_topics``), the ros2_control arrays
(``ros2_control``) and the stale-input ``watchdog``."""
