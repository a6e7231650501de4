"""Offline answers about a configuration, by linear programming under each method's
constraints: the capability envelope (``capability``), the table of single and double
failures (``fault_matrix``) and the explicit method's regions enumerated ahead of time
(``explicit_regions``). No ROS, no plotting, no argument parsing."""
