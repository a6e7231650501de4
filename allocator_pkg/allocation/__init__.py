"""One sample, end to end: the :class:`~.allocator.Allocator` runs the pipeline

    request check -> limits (``limits``: static ranges, rate windows, azimuth plan
    (``azimuth``) and convex pieces (``pieces``)) -> the method's solve, with the
    pseudo-inverse as fallback and the drag feed-forward (``solve``) -> actuation
    (``actuation``: resolve, dead band, command maps, achieved wrench, flags) -> commit

each stage reading what faults, speed and voltage decide from one
:class:`~.conditions.Conditions`, and reports it as an :class:`~.result.AllocationResult`
with its typed :class:`~allocator_pkg.solvers.outcome.Outcome`."""
