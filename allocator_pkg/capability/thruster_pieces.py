"""The convex pieces (survey 4.2) of the forces one rotatable thruster gives in the capability
programme (:class:`~.envelope.Capability`): the allocator's pieces under the zones in force, a
direction-dependent thrust profile's chords, a stuck thruster's line, and the [3.11.4] loss onto
dead thrusters."""

from __future__ import annotations

import math
from dataclasses import replace

from ..allocation.pieces import convex_pieces
from ..effectiveness.faults import Fault, FaultMode
from ..effectiveness.flushing import DeadFlushing
from ..effectiveness.sectors import allowed_arcs
from ..vehicle.config import RotationConfig
from .thrust_profile import ForcePiece, ForceProfile


def thruster_pieces(rotation: RotationConfig, fault: Fault | None, low: float, high: float,
            profile: ForceProfile | None = None, losses: tuple[DeadFlushing, ...] = ()) -> list[ForcePiece]:
    """Convex pieces (start, end, radius, line, half-planes) of the forces a rotatable thruster
    of ``rotation`` (the zones in force) can give (:data:`~.thrust_profile.ForcePiece`): with a
    ``profile`` those it gives, stuck its limit times the profile's factor at that angle;
    without, cones of the allowed arcs. With [3.11.4] ``losses`` (onto dead thrusters), as the
    allocator has them (:func:`~.consequence.force_pieces`): each piece's radius times the least
    loss factor over its directions, and for a thruster that neither reverses nor is stuck also
    the pieces with the loss sectors forbidden (left alone)."""
    pieces = _plain_pieces(rotation, fault, low, high, profile)
    if not losses:
        return pieces
    cut = [(start, end, radius * min(loss.lowest(start, end) for loss in losses), line, chords)
           for start, end, radius, line, chords in pieces]
    if (fault is not None and fault.mode == FaultMode.STUCK) or low < 0.0:
        return cut
    left_alone = replace(rotation, forbidden_sectors=rotation.forbidden_sectors + tuple(loss.sector for loss in losses))
    return cut + _plain_pieces(left_alone, None, low, high, profile)


def _plain_pieces(rotation: RotationConfig, fault: Fault | None, low: float, high: float,
                  profile: ForceProfile | None) -> list[ForcePiece]:
    """:func:`thruster_pieces` without losses: with a ``profile`` (and not stuck) those it gives; else the
    allocator's :func:`~allocator_pkg.allocation.pieces.convex_pieces` (forward and reverse cones
    apart), a stuck thruster's line with its signed thrust in [low, high] as two half-planes along
    it, each way times the profile's factor there."""
    stuck = fault.angle if fault is not None and fault.mode == FaultMode.STUCK else None
    if profile is not None and stuck is None:
        return profile.force_pieces(allowed_arcs(rotation), low, high)
    pieces = []
    for piece in convex_pieces(rotation, low, high, stuck, whole=False):
        planes: tuple = ()
        if piece.line and piece.radius > 0.0:
            share = (lambda a: 1.0) if profile is None else profile.factor
            c, s = math.cos(piece.start), math.sin(piece.start)
            planes = ((c, s, high * share(piece.start) / piece.radius),
                      (-c, -s, -low * share(piece.start + math.pi) / piece.radius))
        pieces.append((piece.start, piece.end, piece.radius, piece.line, planes))
    return pieces
