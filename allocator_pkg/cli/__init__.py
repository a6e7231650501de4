"""Command-line tools: ``allocator-ctl`` (``ctl``, with its MCAP ``recording`` and the
bench's direction check ``direction_check``, its verb ``step-test``), ``allocator-capability``
(``capability``, with DNV-ST-0111 Level 1 in ``dp_capability``), ``allocator-explicit``
(``explicit``), ``allocator-sim`` (``sim``, ``sim_plots``) and the closed-loop demo (``demo``)."""
