"""Command-line tools: ``allocator-ctl`` (``ctl``), the station-keeping demo (``demo``),
``allocator-capability`` (``capability``) and ``allocator-explicit`` (``explicit``)."""
