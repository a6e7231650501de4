"""From files to a configuration: the table of every parameter (``schema``), a ROS params file
or dict to a validated :class:`~allocator_pkg.vehicle.config.Vehicle` and
:class:`~allocator_pkg.vehicle.node_settings.NodeSettings` (``parameters``), and actuator
positions and directions read from a URDF (``urdf``).

It sits below the solvers and the methods: a file names its method from
:data:`~allocator_pkg.vehicle.config.METHOD_NAMES`, and whether that method can serve the vehicle
is the allocator's check (:func:`allocator_pkg.allocation.solve.check_method`)."""
