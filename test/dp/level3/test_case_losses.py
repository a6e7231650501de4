"""allocator_pkg.dp.level3.case_losses: a Level 3 case's thrust losses are the static analysis'
clauses, recomputed here from the clauses' formulas ([3.9.3] beta_misc, [3.9.4] beta_vent,
[3.11.4] beta at the centre of the dead sector), and a simulated thruster pushing onto a dead
one delivers its command times them."""

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.dp.inputs.particulars import load_particulars
from allocator_pkg.dp.level3.case_losses import case_losses
from allocator_pkg.dp.standard.thrust import BETA_MISC, ventilation_factor
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS
from allocator_pkg.simulation.thrusters import Thrusters

VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")
PARTICULARS = load_particulars(ROOT / "config" / "particulars" / "dp_vessel.yaml")
LOST = ("azimuth_stbd", "tunnel_fwd", "swbd_a")


def closer(half_spacing: float):
    """The DP vessel with its azimuths ``half_spacing`` [m] either side of the centre line."""
    actuators = tuple(replace(a, position=(a.position[0], math.copysign(half_spacing, a.position[1]), a.position[2]))
                      if a.name.startswith("azimuth") else a for a in VESSEL.actuators)
    return replace(VESSEL, actuators=actuators)


@pytest.mark.parametrize("number", [2, 5, 8, 11])
@pytest.mark.parametrize("heading", [0.0, 60.0, 135.0, 180.0, 270.0])
def test_the_factors_are_beta_misc_times_beta_vent_of_the_condition_and_heading(number, heading):
    condition = WEATHER_CONDITIONS[number]
    losses = case_losses(VESSEL, PARTICULARS, condition, math.radians(heading))
    (intact,) = losses.cases
    assert intact.dead == frozenset() and not intact.profiles
    frame, hull = PARTICULARS.frame, PARTICULARS.hull
    for actuator in VESSEL.actuators:
        data = replace(PARTICULARS.thrusters[actuator.name], diameter=actuator.diameter, ducted=actuator.ducted)
        x, submergence = frame.standard_x(actuator.position[0]), hull.draught - frame.height(actuator.position[2])
        for reverse, table in ((False, intact.forward), (True, intact.reverse)):
            if reverse and actuator.thrust_min >= 0.0:
                assert actuator.name not in table
                continue
            expected = BETA_MISC * ventilation_factor(data, x, submergence, hull.lpp, condition.hs, condition.tp,
                                                      math.radians(heading), reverse)
            assert table[actuator.name] == pytest.approx(expected, rel=1e-12)
    assert "intact" in losses.description and "beta_vent" in losses.description


@pytest.mark.parametrize("half_spacing", [3.0, 4.0, 5.0, 6.5])
def test_pushing_onto_the_dead_azimuth_delivers_the_command_times_its_loss(half_spacing):
    """Azimuths 2 s apart (s < 4 D = 13.6 m, ducted): after switchboard A's loss the port azimuth
    pushing toward port sends its race onto the dead starboard one, and loses thrust by [3.11.4]'s
    beta = 1 - 1 / (0.02 (s/D)^2 + 0.25 s/D + 1.2) at the centre of the sector."""
    vessel = closer(half_spacing)
    condition = WEATHER_CONDITIONS[4]
    losses = case_losses(vessel, PARTICULARS, condition, 0.0, LOST)
    intact, failed = losses.cases
    assert failed.dead == {"azimuth_stbd", "tunnel_fwd"} and set(failed.profiles) == {"azimuth_port"}
    ratio = 2.0 * half_spacing / 3.4
    beta = 1.0 - 1.0 / (0.02 * ratio ** 2 + 0.25 * ratio + 1.2)
    onto_dead = -math.pi / 2                                   # thrust toward port: the race to starboard
    assert failed.profiles["azimuth_port"].factor(onto_dead) == pytest.approx(beta, rel=1e-9)
    assert failed.profiles["azimuth_port"].factor(math.pi / 2) == 1.0
    thrusters = Thrusters(vessel, time_constant=0.5, trip=True, losses=losses)
    command = np.array([200e3, 300e3, 100e3, -100e3])
    angles = np.array([0.0, onto_dead, 0.0, 0.0])
    thrusters.start_at(command, angles)
    assert thrusters.thrust[1] == pytest.approx(intact.forward["azimuth_port"] * 300e3, rel=1e-12)
    for name in failed.dead:
        thrusters.set_fault(name, "failed")
    for _ in range(400):
        thrusters.step(command, angles, 0.1)
    assert thrusters.thrust[[0, 2]] == pytest.approx(0.0, abs=0.0)
    assert thrusters.thrust[1] == pytest.approx(failed.forward["azimuth_port"] * beta * 300e3, rel=1e-9)
    assert thrusters.thrust[3] == pytest.approx(-failed.reverse["tunnel_aft"] * 100e3, rel=1e-9)


def test_a_far_dead_azimuth_costs_nothing_by_direction():
    """The DP vessel as it is: 14 m between the azimuths, beyond 4 D = 13.6 m."""
    (_, failed) = case_losses(VESSEL, PARTICULARS, WEATHER_CONDITIONS[4], 0.0, LOST).cases
    assert not failed.profiles
