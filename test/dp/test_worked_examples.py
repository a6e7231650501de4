"""Worked examples of DNV-ST-0111 Level 1 by hand: the split-feed derating of a thruster that loses
one of its two feeds, two azimuths head on (intact, one lost, a board short of power), and the
standard's own Table A-1 example as far as the transcription reads it."""

import math

import numpy as np
import pytest

from allocator_pkg import vehicle_from_parameters
from allocator_pkg.dp.capability_result import INTACT, WORST, CapabilityResult, capability_summary
from allocator_pkg.dp.inputs.particulars import particulars_from_mapping
from allocator_pkg.dp.level1 import Level1
from allocator_pkg.dp.report.tables import table_a1
from allocator_pkg.dp.standard.power_balance import part_load_power
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS

# The transcription's round test hull (Lpp 80 m, B 18 m, T 6 m), body origin midships in the waterline.
HULL = {"lpp": 80.0, "beam": 18.0, "draught": 6.0, "wind_area_frontal": 200.0, "wind_area_lateral": 800.0,
        "wind_centre_x": 5.0, "underwater_centre_x": -1.5, "body_origin_x": 0.0, "body_origin_height": 6.0,
        "los": 86.0, "los_centre_x": -1.0, "bow_angle": math.degrees(0.4), "waterplane_area_aft": 648.0,
        "current_area_lateral": 490.0}
# An open FPP azimuth of D 2 m and P_B 1000 kW.
AZIMUTH = {"kind": "azimuth", "diameter": 2.0, "power": 1000.0}


def two_azimuths(**extra) -> dict:
    """F at x = +20 m and A at x = -20 m on the centreline, 4 m below the waterline (2 m above the
    keel): 40 m apart, more than 15 D = 30 m, so no [3.11.3] zones; without groups each is lost alone."""
    parameters = {"dofs": ["surge", "sway", "yaw"], "actuators.names": ["F", "A"]}
    for name, x in (("F", 20.0), ("A", -20.0)):
        parameters.update({f"actuators.{name}.type": "azimuth", f"actuators.{name}.position": [x, 0.0, 4.0],
                           f"actuators.{name}.thrust_max": 1.0})
    return {**parameters, **extra}


PARTICULARS = particulars_from_mapping({**HULL, "thrusters": {"F": AZIMUTH, "A": AZIMUTH}})


def test_split_feed_derating():
    """redundancy.md 4: the azimuth F is fed 50 % from S1 and 50 % from S2; S1 is lost (group S1:
    the source S1 and A, fed from S1 only).
    - Intact: T_nominal = eta1 eta2 (D P_B eta_M)^(2/3) = 800 1.0 (2 1000 0.93)^(2/3) = 800 151.24
      = 120.99 kN [3.9.2]; T_effective = 0.9 120.99 = 108.89 kN [3.9.3].
    - S1 lost: F keeps its S2 half, P_B' = 500 kW, T_nominal' = 120.99 0.5^(2/3) = 76.22 kN,
      T_effective' = 68.60 kN; at full thrust it draws 1000 (76.22 / 120.99)^1.5 = 500 kW, the power
      per newton unchanged.
    Calm (number 0: Hs 0), 4 m deep: beta_vent = Phi(2 2 4 / 2 - 1.5 sigma) with sigma = 0.25
    (sqrt(T_nominal / D^3) / 15.2 - 1) = 1.77 (0.86 after the loss), Phi(5.3) = 1 - 6e-8."""
    vehicle = vehicle_from_parameters(two_azimuths(**{
        "power.sources": ["S1", "S2"], "power.S1.capacity": 5000.0, "power.S2.capacity": 5000.0,
        "actuators.F.feeds": ["S1", "S2"], "actuators.F.feed_shares": [0.5, 0.5], "actuators.A.feeds": ["S1"],
        "redundancy_groups.names": ["S1"], "redundancy_groups.S1.sources": ["S1"],
        "redundancy_groups.S1.actuators": ["A"]}))
    analysis = Level1(vehicle, PARTICULARS)
    lost = analysis.groups["S1"]
    assert analysis.actuators["F"].forward == pytest.approx(120.99e3, abs=5.0)
    assert analysis.thrust_range("F", WEATHER_CONDITIONS[0], 0.0)[1] == pytest.approx(108.89e3, abs=5.0)
    assert analysis.power_share("F", lost) == 0.5
    assert analysis.thrust_range("F", WEATHER_CONDITIONS[0], 0.0, lost)[1] == pytest.approx(68.60e3, abs=5.0)
    assert 1000.0 * part_load_power(76.22 / 120.99) == pytest.approx(500.0, abs=0.2)
    assert [a.name for a in analysis.variant(WEATHER_CONDITIONS[0], 0.0, lost).actuators] == ["F"]


def test_two_azimuths_head_on_by_hand():
    """Head on (dir 0) the load is pure surge [3.5]-[3.7], per number (wind V, Hs, Tp; current 0.75 m/s):
    - wind 0.7 1/2 1.226 V^2 200; current 0.07 1/2 1026 0.75^2 18 6 = 2.18 kN;
    - waves 1/2 1026 9.81 Hs^2 18 0.09 h1 h2 f(T'surge), h1 = 0.8 0.4^0.45 = 0.52968,
      h2 = 0.05 + 0.95 arctan(1.45 (0 - 1.75)) = -1.08563, T'surge = Tp / 1.4049 / (0.9 80^0.33);
    - number 7 (17.1 m/s, Hs 4.2 m, Tp 9.0 s): 25.09 + 2.18 + 38.60 kN, times 1.25 = 82.34 kN;
      number 8 (20.7, 5.7, 10.0): 36.77 + 2.18 + 54.90, 117.31 kN; number 9 (24.4, 7.4, 10.5):
      51.09 + 2.18 + 81.63, 168.63 kN; number 10 (28.4, 9.5, 11.5): 69.22 + 2.18 + 105.72, 221.40 kN
      (the transcription's test gives the same four totals).
    Each azimuth 108.89 kN (beta_vent 4 m deep 0.99998 or more):
    - intact 217.79 kN: 9 held, 10 not: number 9;
    - one lost, 108.89 kN: 7 held, 8 not: number 7;
    - both on one 1200 kW board (1080 kW usable [3.12.3]), each at r = load / 217.79 kN drawing
      1000 r^1.5 kW: number 8 r = 0.5386, 2 395.3 = 790.6 kW, held; number 9 r = 0.7743,
      2 681.3 = 1362.6 kW > 1080 kW, not held: number 8."""
    analysis = Level1(vehicle_from_parameters(two_azimuths()), PARTICULARS)
    for number, total in ((7, 82.34e3), (8, 117.31e3), (9, 168.63e3), (10, 221.40e3)):
        assert analysis.required(WEATHER_CONDITIONS[number], 0.0)[0] == pytest.approx(total, rel=1e-4)
    number, wind = analysis.heading(0.0)
    assert number == 9 and WEATHER_CONDITIONS[9].wind < wind < WEATHER_CONDITIONS[10].wind
    assert analysis.heading(0.0, analysis.groups["F"])[0] == 7 and analysis.heading(0.0, analysis.groups["A"])[0] == 7
    board = Level1(vehicle_from_parameters(two_azimuths(**{
        "power.sources": ["swbd"], "power.swbd.capacity": 1200.0, "actuators.F.feeds": ["swbd"],
        "actuators.A.feeds": ["swbd"]})), PARTICULARS)
    assert 2 * 1000.0 * part_load_power(117.31 / 217.79) == pytest.approx(790.6, abs=0.5)
    assert 2 * 1000.0 * part_load_power(168.63 / 217.79) == pytest.approx(1362.6, abs=0.5)
    assert board.heading(0.0)[0] == 8


def test_table_a1_of_the_standard():
    """DNV-ST-0111 Table A-1 as the transcription reads it (p. 69, headings 0-30 deg only): loss of
    SWBD 1 9, 8, 6, 5; loss of SWBD 2 11, 11, 10, 8; combined (the lowest per heading [2.4.7]) 9, 8,
    6, 5, all from SWBD 1. Its Figure A-2 says L1(9, 7, 5, 2): A = 9 and C = 5 are the 30 deg values
    (intact 9 there; 11 at 0-20 deg in the transcription's test). B = 7 and D = 2 come from headings the
    transcription does not give, so they cannot be checked here."""
    headings = np.array([0.0, 10.0, 20.0, 30.0])
    numbers = {INTACT: np.array([11, 11, 11, 9]), "swbd_1": np.array([9, 8, 6, 5]),
               "swbd_2": np.array([11, 11, 10, 8])}
    numbers[WORST] = np.minimum(numbers["swbd_1"], numbers["swbd_2"])
    winds = {case: np.array([WEATHER_CONDITIONS[n].wind for n in values]) for case, values in numbers.items()}
    result = CapabilityResult(headings, numbers, winds, ())
    columns, rows = table_a1(result)
    assert columns == ("heading_deg", INTACT, "swbd_1", "swbd_2", "combined", "worst_group")
    assert [row[4] for row in rows] == [9, 8, 6, 5] and {row[5] for row in rows} == {"swbd_1"}
    a, _, c, _ = capability_summary(headings, numbers[INTACT], numbers[WORST])
    assert (a, c) == (9, 5)
