"""Closed-loop simulation maths: vehicle models (a DP vessel in 3 DOF, a BlueROV2 Heavy in
6 DOF), thrusters as the water sees them, a seeded environment, a station-keeping
controller, scenario files, run metrics, and the closed loop (``closed_loop``) with the
allocator library in it (``in_process``). No ROS, no plotting, no argument parsing: the
co-simulation process that runs the loop against the real node is ``cli/sim.py``."""
