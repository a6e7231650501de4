"""Per-sample limits of a rotatable thruster.

Every method treats a rotatable thruster through :func:`plan`, which turns the thruster's
state (angle alpha0, signed thrust F0), its rate limits, feasible and forbidden sectors,
faults and the direction the unconstrained extended solution (1.33) wants, into the set of
angles and thrusts allowed this sample (:class:`~allocator_pkg.effectiveness.model.AzimuthLimits`).
The limits' ``goal`` is that direction, toward which an idle thruster turns (so that it is
ready, and a thruster that must turn the long way round gets there) when
:func:`~allocator_pkg.effectiveness.resolve.resolve` turns the method's force into the thrust
and angle commanded, inside every limit whatever the solver returned.

Crossing to another piece. Thrust is not allowed inside a forbidden sector, so the set of
usable angles splits into pieces, and the rate limit means the thruster only reaches nearby
angles each sample. When the wanted direction lies beyond a forbidden sector (by more than
``CROSSING_MARGIN``), or needs a sign change of a reversible thruster, the thruster first
ramps its thrust down to zero at its thrust rate limit, then turns through at its full
turning rate with zero thrust, and resumes normal allocation once the rest of the way is
clear. Once started, a crossing is finished; the other actuators carry the load meanwhile.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..effectiveness.model import AzimuthLimits
from ..effectiveness.sectors import (
    Surroundings,
    forbidden_offsets,
    in_forbidden_sector,
    surroundings,
    target_offsets,
)
from ..vehicle.angles import ANGLE_TOLERANCE, wrap
from ..vehicle.config import RotationConfig

CROSSING_MARGIN = 0.05
"""How far [rad] beyond a forbidden sector the wanted direction must lie before a crossing starts."""

CROSSING_PENALTY = 0.5
"""Extra angle [rad] charged to a path that needs zero thrust, so that turning with thrust is preferred."""

@dataclass(slots=True)
class AzimuthState:
    """What a rotatable thruster is doing: its angle, signed thrust and any crossing under way."""

    angle: float
    thrust: float = 0.0
    sigma: int = 1
    turning: int = 0
    turn_sigma: int = 1




def thrust_window(thrust: float, step: float, low: float, high: float) -> tuple[float, float]:
    """Signed thrusts reachable from ``thrust`` within one rate step, inside [low, high].

    When a fault has just narrowed [low, high] the window jumps to its nearest edge: a
    limit from a fault overrides the rate limit.
    """
    return (min(max(thrust - step, low), high), min(max(thrust + step, low), high))


def plan(
    rotation: RotationConfig,
    state: AzimuthState,
    angle_step: float,
    thrust_range: tuple[float, float],
    thrust_step: float,
    desired: tuple[float, float],
    hold: float,
    stuck: float | None = None,
    around: Surroundings | None = None,
) -> AzimuthLimits:
    """Limits of one rotatable thruster for this sample; updates ``state``'s crossing fields.

    ``thrust_range`` is the fault-adjusted signed thrust range, ``angle_step`` and
    ``thrust_step`` the largest changes in one sample (inf when unlimited), ``desired`` the
    extended force the unconstrained solution wants and ``hold`` the force below which the
    angle is undefined; ``around`` is :func:`~allocator_pkg.effectiveness.sectors.surroundings` of the
    current angle, when the caller has it already.
    """
    alpha0, thrust0 = state.angle, state.thrust
    window_low, window_high = thrust_window(thrust0, thrust_step, *thrust_range)
    if stuck is not None:
        state.turning = 0
        if in_forbidden_sector(rotation, stuck):           # stuck where it must not push: it does not
            window_low = window_high = 0.0
        return AzimuthLimits(stuck, stuck, 1, window_low, window_high, line=True)

    if thrust_range == (0.0, 0.0):                         # failed: nothing to turn for
        state.turning = 0
        return AzimuthLimits(alpha0, alpha0, state.sigma, 0.0, 0.0, physical_max=0.0)

    moving = abs(thrust0) > min(hold, thrust_step)        # cannot reach zero thrust this sample
    current_sigma = (1 if thrust0 > 0.0 else -1) if moving else state.sigma
    domain, forbidden, piece = around or surroundings(rotation, alpha0)
    wanted = math.hypot(desired[0], desired[1]) > hold
    best = _best_path(rotation, alpha0, desired, piece, current_sigma, moving, thrust_range) if wanted else None

    if state.turning and piece is not None and (best is None or not best[2]):
        state.turning = 0
        state.sigma = state.turn_sigma
        current_sigma = state.sigma
    if state.turning or piece is None:
        return _turn(rotation, state, alpha0, angle_step, domain, best)

    if best is not None:
        sigma, offset, crossing = best
        needs_zero = crossing and _beyond_forbidden(offset, forbidden) > CROSSING_MARGIN
        if (needs_zero or sigma != current_sigma) and moving:
            # Toward zero by a rate step, on the side it pushes: the window's end nearer zero,
            # which a fault that has just narrowed the range moves to the range's edge.
            ramp = max(window_low, 0.0) if current_sigma > 0 else min(window_high, 0.0)
            return AzimuthLimits(alpha0, alpha0, current_sigma, ramp, ramp)
        if needs_zero:
            state.turning = 1 if offset > 0.0 else -1
            state.turn_sigma = sigma
            return _turn(rotation, state, alpha0, angle_step, domain, best)
        if not moving:
            current_sigma = sigma
        state.sigma = current_sigma

    return _window(rotation, alpha0, angle_step, piece, forbidden, best, current_sigma, (window_low, window_high),
                   thrust_range)


def _window(
    rotation: RotationConfig,
    alpha0: float,
    angle_step: float,
    piece: tuple[float, float],
    forbidden: list[tuple[float, float]],
    best: tuple[int, float, bool] | None,
    current_sigma: int,
    thrust_window: tuple[float, float],
    thrust_range: tuple[float, float],
) -> AzimuthLimits:
    """The limits of a thruster that keeps pushing on the side ``current_sigma``: its thrust window on
    that side, and the angles of ``piece`` (offsets from ``alpha0``) within a rate step, opened
    only toward the long way round where the feasible sector's end blocks the short way, and
    at most half a turn wide about the wanted direction."""
    window_low, window_high = thrust_window
    if current_sigma > 0:
        thrust_low, thrust_high = max(window_low, 0.0), max(window_high, 0.0)
    else:
        thrust_low, thrust_high = min(window_low, 0.0), min(window_high, 0.0)
    goal = alpha0 + best[1] if best is not None and best[0] == current_sigma else None
    physical = thrust_range[1] if current_sigma > 0 else -thrust_range[0]
    if angle_step >= math.pi and rotation.continuous and not forbidden:
        # Free to point anywhere this sample: the whole circle, no window at all.
        return AzimuthLimits(-math.inf, math.inf, current_sigma, thrust_low, thrust_high, goal=goal,
                             physical_max=physical)
    low, high = piece
    step = min(angle_step, math.pi)
    low, high = max(low, -step), min(high, step)
    if best is not None and not rotation.continuous:
        # The feasible sector's end blocks the short way round: the window opens only toward
        # the long way. A free thruster takes the long way only to spare a crossing; cut toward
        # it, the window would open again a rate step past the goal's antipode, and the QP
        # could turn it back there for good.
        offset = best[1]
        natural = wrap(offset)
        if natural * offset < 0.0 or abs(offset) > math.pi + ANGLE_TOLERANCE:
            low, high = (0.0, high) if offset > 0.0 else (low, 0.0)
    if high - low > math.pi:
        centre = max(-0.5 * math.pi, min(0.5 * math.pi, best[1] if best is not None else 0.0))
        low, high = max(low, centre - 0.5 * math.pi), min(high, centre + 0.5 * math.pi)
    return AzimuthLimits(alpha0 + low, alpha0 + high, current_sigma, thrust_low, thrust_high, goal=goal,
                         physical_max=physical)


def _best_path(
    rotation: RotationConfig,
    alpha0: float,
    desired: tuple[float, float],
    piece: tuple[float, float] | None,
    current_sigma: int,
    moving: bool,
    thrust_range: tuple[float, float],
) -> tuple[int, float, bool] | None:
    """(sigma, offset, crosses a forbidden sector) of the cheapest way to the wanted direction."""
    direction = math.atan2(desired[1], desired[0])
    sides = [1, -1] if rotation.reversible and thrust_range[0] < 0.0 else [1]
    best = None
    best_cost = math.inf
    for sigma in sides:
        path = _cheapest_way(rotation, alpha0, direction if sigma > 0 else direction + math.pi, piece)
        if path is None:
            continue
        offset, crossing, cost = path
        if sigma != current_sigma and moving:
            cost += CROSSING_PENALTY
        if cost < best_cost - ANGLE_TOLERANCE:
            best, best_cost = (sigma, offset, crossing), cost
    return best


def _cheapest_way(rotation: RotationConfig, alpha0: float, target: float,
                  piece: tuple[float, float] | None) -> tuple[float, bool, float] | None:
    """(offset, crosses a forbidden sector, cost) of the cheapest way from alpha0 to ``target``
    (None if the feasible sector does not contain it): the angle turned, plus
    CROSSING_PENALTY when the way needs zero thrust through a forbidden sector. A way crosses
    one when it leaves ``piece``, the allowed offsets around alpha0 (every way does from inside
    a sector, where ``piece`` is None); a way never leaves the feasible sector."""
    best = None
    for offset in target_offsets(rotation, alpha0, target):
        crossing = piece is None or not piece[0] - ANGLE_TOLERANCE <= offset <= piece[1] + ANGLE_TOLERANCE
        cost = abs(offset) + (CROSSING_PENALTY if crossing else 0.0)
        if best is None or cost < best[2] - ANGLE_TOLERANCE:
            best = (offset, crossing, cost)
    return best


def _beyond_forbidden(offset: float, forbidden: list[tuple[float, float]]) -> float:
    """How far past the last forbidden interval on the path [0, offset] the target lies."""
    if offset > 0.0:
        ends = [hi for lo, hi in forbidden if 0.0 < hi <= offset + ANGLE_TOLERANCE and lo < offset]
        return offset - max(ends) if ends else 0.0
    starts = [lo for lo, hi in forbidden if offset - ANGLE_TOLERANCE <= lo < 0.0 and hi > offset]
    return min(starts) - offset if starts else 0.0


def _turn(
    rotation: RotationConfig,
    state: AzimuthState,
    alpha0: float,
    angle_step: float,
    domain: tuple[float, float],
    best: tuple[int, float, bool] | None,
) -> AzimuthLimits:
    """One sample of a crossing: zero thrust, the angle moves at full rate toward the
    wanted direction (or, with none, out of the forbidden sector it is in)."""
    goal = best[1] if best is not None else _exit_offset(rotation, alpha0)
    if not state.turning:
        state.turning = 1 if goal >= 0.0 else -1
        state.turn_sigma = best[0] if best is not None else state.sigma
    reach = abs(goal) if goal * state.turning > 0.0 else math.pi
    offset = state.turning * min(angle_step, reach)
    offset = max(domain[0], min(domain[1], offset))
    angle = alpha0 + offset
    if rotation.continuous:
        angle = wrap(angle)
    return AzimuthLimits(angle, angle, state.turn_sigma, 0.0, 0.0)


def _exit_offset(rotation: RotationConfig, alpha0: float) -> float:
    """Offset to the nearer edge of the forbidden sector the thruster is in (0 if none)."""
    for lo, hi in forbidden_offsets(rotation, alpha0):
        if lo < 0.0 < hi:
            return hi if hi <= -lo else lo
    return 0.0


def piece_in_question(rotation: RotationConfig, alpha0: float, angle_step: float, desired: tuple[float, float],
                      hold: float, around: Surroundings | None = None) -> bool:
    """Whether a thruster's side of its forbidden sectors is in question this sample: an edge
    of the allowed piece it is in (a forbidden sector, or the feasible sector's end) lies within
    a rate step, or the direction the unconstrained solution wants lies beyond one: the
    cheapest way :func:`plan` would turn toward it (on either side, for a reversible thruster)
    crosses a forbidden sector, even where the long way round stays in the piece. Only then
    can the optimum the method converges to locally fail to be the global one
    (:mod:`allocator_pkg.allocation.pieces`); and a crossing the unconstrained wish (which ignores every
    limit) would start is weighed by the piece planner first, never started past it."""
    _, _, piece = around or surroundings(rotation, alpha0)
    if piece is None:
        return False                                        # inside a sector: a crossing is under way
    reach = min(angle_step, math.pi) + CROSSING_MARGIN
    if -piece[0] <= reach or piece[1] <= reach:
        return True
    if math.hypot(desired[0], desired[1]) <= hold:
        return False
    direction = math.atan2(desired[1], desired[0])
    sides = (direction, direction + math.pi) if rotation.reversible else (direction,)
    ways = [way for way in (_cheapest_way(rotation, alpha0, side, piece) for side in sides) if way is not None]
    return not ways or any(crossing for _, crossing, _ in ways)
