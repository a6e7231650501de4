"""Testing a vehicle's configuration with pytest: the ``allocator_harness`` fixture
(:mod:`allocator_pkg.testing.plugin`, registered under pytest's ``pytest11`` entry point, so
installing the package provides it) and the :class:`~allocator_pkg.testing.harness.Harness` it
returns. See docs/testing.md."""
