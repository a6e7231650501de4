"""Closed-loop simulation maths: vehicle models (a DP vessel in 3 DOF, a BlueROV2 Heavy in
6 DOF), thrusters as the water sees them, a seeded environment, a station-keeping
controller, scenario files and run metrics. No ROS, no plotting, no argument parsing: the
co-simulation process that runs these against the real node is ``cli/sim.py``."""
