"""The thrust bias keys (``bias.*``) checked against the actuators and the controlled DOFs: the
pairs of ``bias.pairs`` (two rotatable thrusters of one type at different positions, each in one
pair at most, able to push toward each other, their opposed forces free of wrench in the
controlled DOFs), a ``bias.thrust`` below every paired thruster's thrust_max, ``bias.fade_end``
above ``bias.fade_start``, and ``bias.enabled`` only with pairs and a thrust. Every problem is
recorded on the :class:`~allocator_pkg.configuration.values.Reader`, naming the key."""

from __future__ import annotations

import math
from typing import Any

from ..effectiveness.sectors import can_push_along
from ..effectiveness.thrust_bias import WRENCH_TOLERANCE, pair_direction, pair_wrench
from ..vehicle.config import DOF_NAMES, ActuatorConfig
from .values import MISSING, Reader

PAIRS = "bias.pairs"


def parse_bias_pairs(reader: Reader, values: dict[str, Any], actuators: list[ActuatorConfig],
                     dofs: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
    """The pairs of ``bias.pairs`` (``values``: the vehicle-wide keys read), every problem with
    them and the other bias keys recorded."""
    listed = values[PAIRS]
    names = [] if listed in (None, MISSING) else list(listed)
    by_name = {actuator.name: actuator for actuator in actuators}
    pairs: list[tuple[str, str]] = []
    if len(names) % 2:
        reader.fail(PAIRS, f"needs pairs, an even number of names; got {len(names)}")
    else:
        seen: set[str] = set()
        for first, second in zip(names[0::2], names[1::2]):
            if _pair_fits(reader, first, second, by_name, seen, dofs):
                pairs.append((first, second))
            seen.update((first, second))
    _thrust(reader, values, [by_name[name] for pair in pairs for name in pair])
    start, end = values["bias.fade_start"], values["bias.fade_end"]
    if start is not MISSING and end is not MISSING and end <= start:
        reader.fail("bias.fade_end", f"{end:g} must be above bias.fade_start ({start:g})")
    if values["bias.enabled"] is True and not names:
        reader.fail("bias.enabled", "needs bias.pairs: the pairs of rotatable thrusters that push against each other")
    return tuple(pairs)


def _pair_fits(reader: Reader, first: str, second: str, by_name: dict[str, ActuatorConfig], seen: set[str],
               dofs: tuple[str, ...]) -> bool:
    """Whether one pair can push against itself, recording why not."""
    pair = f"pair ({first}, {second})"
    unknown = [name for name in (first, second) if name not in by_name]
    if unknown:
        reader.fail(PAIRS, f"{pair}: {', '.join(unknown)} not in actuators.names ({', '.join(by_name)})")
        return False
    if first == second:
        reader.fail(PAIRS, f"{pair}: a thruster cannot push against itself")
        return False
    for name in (first, second):
        if name in seen:
            reader.fail(PAIRS, f"{pair}: {name} is in another pair already; each thruster in one pair at most")
            return False
        if not by_name[name].rotatable:
            reader.fail(PAIRS, f"{pair}: {name} is a {by_name[name].type} actuator, not a rotatable thruster")
            return False
    a, b = by_name[first], by_name[second]
    if a.type != b.type:
        reader.fail(PAIRS, f"{pair}: {a.type} and {b.type} thrusters turn in different planes")
        return False
    direction = pair_direction(a, b)
    if direction is None:
        reader.fail(PAIRS, f"{pair}: the two stand at one point of their plane of rotation; no direction between them")
        return False
    angle = math.atan2(direction[1], direction[0])
    for actuator, toward in ((a, angle), (b, angle + math.pi)):
        if not can_push_along(actuator.rotation, toward):
            reader.fail(PAIRS, f"{pair}: {actuator.name} cannot push toward the other (at {math.degrees(toward):.1f} "
                               "deg: outside its feasible sector or inside a forbidden sector)")
            return False
    wrench = pair_wrench(a, b, direction)
    left = [(dof, wrench[DOF_NAMES.index(dof)]) for dof in dofs if abs(wrench[DOF_NAMES.index(dof)]) > WRENCH_TOLERANCE]
    if left:
        reader.fail(PAIRS, f"{pair}: their opposed forces leave a wrench in "
                           + ", ".join(f"{dof} ({value:.3g} per N)" for dof, value in left)
                           + " (the thrusters stand at different heights of their plane)")
        return False
    return True


def _thrust(reader: Reader, values: dict[str, Any], paired: list[ActuatorConfig]) -> None:
    """bias.thrust above 0 when enabled, below the thrust_max of every paired thruster."""
    thrust = values["bias.thrust"]
    if thrust is MISSING:
        return
    if values["bias.enabled"] is True and thrust == 0.0:
        reader.fail("bias.thrust", "must be above 0 with bias.enabled")
    for actuator in paired:
        if thrust >= actuator.thrust_max:
            reader.fail("bias.thrust", f"{thrust:g} N is not below the thrust_max of {actuator.name} "
                                       f"({actuator.thrust_max:g} N)")
