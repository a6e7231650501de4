"""Offline answers about a configuration, by linear programming under each method's
constraints: the capability envelope (``capability``), the table of single and double
failures (``fault_matrix``), the explicit method's regions enumerated ahead of time
(``explicit_regions``), and DP capability after DNV-ST-0111 Level 1 (``dp_capability``) on the
wind, current and wave-drift loads of ``environment_loads``. No ROS, no plotting, no argument
parsing."""
