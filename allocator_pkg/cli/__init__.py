"""Command-line tools: ``allocator-ctl`` (``ctl``, with its MCAP ``recording`` and the
direction check ``step_test``), ``allocator-capability`` (``capability``, with DNV-ST-0111
Level 1 in ``dp_capability``), ``allocator-explicit`` (``explicit``), ``allocator-sim``
(``sim``, ``sim_plots``) and the closed-loop demo (``demo``)."""
