"""Command-line tools: ``allocator-ctl`` (``ctl``, with its client ``controller``, its live table
``echo``, its MCAP ``recording`` and the bench's direction check ``direction_check``, its verb
``step-test``), ``allocator-capability`` (``capability``, with DNV-ST-0111 Level 1 in
``dp_capability``), ``allocator-explicit`` (``explicit``), ``allocator-sim`` (``sim``, with the
node in the loop ``sim_loop``, its ROS side ``sim_link``, ``sim_metrics`` and ``sim_plots``) and
the closed-loop demo (``demo``)."""
