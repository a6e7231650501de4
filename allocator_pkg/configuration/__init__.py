"""From files to a configuration: the table of every parameter (``schema``), a ROS params file
or dict to a validated :class:`~allocator_pkg.vehicle.config.Vehicle` and
:class:`~allocator_pkg.vehicle.node_settings.NodeSettings` (``parameters``), and actuator
positions and directions read from a URDF (``urdf``).

It sits above the methods: the method a file names is checked against the registry
(:data:`allocator_pkg.methods.METHODS`), its reasons included, when the file is read."""
