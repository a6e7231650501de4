"""Actuator effectiveness: what the actuators can do, from the configuration.

Command maps and hydrofoil lift and drag (``actuators``: (1.3), (1.4), (1.48)), T(alpha) and
the extended T_e of (1.5)/(1.17) (``configuration_matrix``), the angle sets of rotatable
thrusters (``sectors``), faults and the static force ranges they leave (``faults``), the
configuration as arrays and one sample's limits (``model``), and which DOFs the actuators
reach (``reach``)."""
