"""Offline answers about a configuration, by linear programming under each method's
constraints: the capability envelope (``capability``), the table of single and double
failures (``fault_matrix``), the explicit method's regions enumerated ahead of time
(``explicit_regions``), and DP capability after DNV-ST-0111 Level 1 (``dp_capability``) on the
standard's loads, thrust and forbidden zones (``dnv_loads``, ``dnv_thrust``, ``dnv_zones``) and
a particulars file (``dp_particulars``). ``environment_loads`` is the static wind, current and
wave-drift model the closed-loop simulation shares. No ROS, no plotting, no argument parsing."""
