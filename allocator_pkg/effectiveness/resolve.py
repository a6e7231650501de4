"""From a rotatable thruster's extended force (f1, f2) (1.16)-(1.18) back to the thrust and angle
it is commanded (1.23), inside this sample's :class:`~.model.AzimuthLimits`.

:func:`pointing` chooses the angle: atan2 of the force (1.23) on the side the thruster pushes,
nearest its present angle, or a method's proposal; for a force too small to define an angle
(below ``hold``) or a thruster that may not push this sample, the direction a method or the
limits say an idle thruster turns toward, or the present angle. Either way inside the
allowed angles. :func:`resolve` adds the thrust: the projection of the force on that angle
(never pointing the wrong way while turning), clipped to the allowed thrusts. The allocator's
actuation resolves every method's answer so; the ``dynamic`` method projects its state with
the same angle."""

from __future__ import annotations

import math

from ..vehicle.angles import wrap
from .model import AzimuthLimits


def pointing(limits: AzimuthLimits, alpha0: float, f1: float, f2: float, hold: float,
             proposal: float | None = None, turn: float | None = None) -> float:
    """The angle, inside ``limits``, at which a thruster at ``alpha0`` gives as much of the
    force (f1, f2) as it can: atan2 of the force (1.23), or ``proposal`` if a method chose
    one; for a force below ``hold`` or a thruster that may not push this sample (an idle or
    failed one) toward ``turn`` if a method chose where an idle thruster should go (and it may
    push), else toward the limits' goal, or the present angle. Not wrapped: within a turn of
    ``alpha0``."""
    if limits.line:
        angle = alpha0
    elif turn is not None and limits.magnitude_max > 0.0 and math.hypot(f1, f2) < hold:
        angle = alpha0 + wrap(turn - alpha0)
    elif math.hypot(f1, f2) < hold or limits.magnitude_max == 0.0:
        angle = alpha0 if limits.goal is None else limits.goal
    elif proposal is not None:
        angle = alpha0 + wrap(proposal - alpha0)
    else:
        direction = math.atan2(f2, f1) if limits.sigma > 0 else math.atan2(-f2, -f1)
        angle = alpha0 + wrap(direction - alpha0)
    return min(max(angle, limits.low), limits.high)


def resolve(limits: AzimuthLimits, alpha0: float, force: tuple[float, float], hold: float,
            continuous: bool, proposal: float | None = None, turn: float | None = None) -> tuple[float, float]:
    """(thrust, angle) that produce as much of ``force`` as this sample's limits allow: the
    angle of :func:`pointing` (wrapped for a ``continuous`` thruster), the thrust the force's
    projection on it, clipped to the allowed thrusts."""
    f1, f2 = force
    angle = pointing(limits, alpha0, f1, f2, hold, proposal, turn)
    if continuous:
        angle = wrap(angle)
    thrust = f1 * math.cos(angle) + f2 * math.sin(angle)
    thrust = min(max(thrust, limits.thrust_low), limits.thrust_high)
    return thrust, angle
