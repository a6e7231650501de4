"""DNV-ST-0111 Level 1 loads [3.5]-[3.7]: the transcription's worked examples, hand calculations,
symmetry, limits, the conversion to the body frame and refusals naming the key."""

import math
from dataclasses import replace

import numpy as np
import pytest

from allocator_pkg.dp.standard.loads import (
    BodyFrame,
    DnvHull,
    LoadComponents,
    current_load,
    fold,
    period_factor,
    wave_drift_load,
    wind_load,
)

# The test hull of the transcription's worked examples (Descriptions/waveloads.md and
# currentloads.md): C_WLaft = 648 / (40 * 18) = 0.90.
HULL = DnvHull(lpp=80.0, beam=18.0, draught=6.0, los=86.0, los_centre_x=-1.0, bow_angle=0.4,
               waterplane_area_aft=648.0, wind_area_frontal=200.0, wind_area_lateral=800.0, wind_centre_x=5.0,
               current_area_lateral=490.0, current_centre_x=-1.5)
DEG = math.radians


def test_wind_by_hand():
    # 1/2 1.226 10^2 = 61.3 Pa; head on 61.3 200 0.7 = 8582 N aft; beam 61.3 800 0.9 = 44136 N to port
    # at 5 + 0.3 (1 - 1) 80 = 5 m: 220680 N m.
    assert wind_load(HULL, 10.0, 0.0) == pytest.approx([-8582.0, 0.0, 0.0], abs=1e-9)
    assert wind_load(HULL, 10.0, DEG(90)) == pytest.approx([0.0, 44136.0, 220680.0], abs=1e-6)
    assert wind_load(HULL, 10.0, DEG(270)) == pytest.approx([0.0, -44136.0, -220680.0], abs=1e-6)
    # 45 deg: lever 5 + 0.3 (1 - 1/2) 80 = 17 m; Fx = -8582 cos 45 = -6068.4, Fy = 31208.9.
    assert wind_load(HULL, 10.0, DEG(45)) == pytest.approx([-6068.4, 31208.9, 530551.0], rel=1e-5)


@pytest.mark.parametrize(("heading", "expected"), [
    (0, (-3878.28, 0.0, 0.0)),
    (30, (-3358.689, 75411.0, 1395103.5)),          # lever -1.5 + 0.25 80 = 18.5 m (upper clip)
    (45, (-2742.358, 106647.259, 1546385.255)),     # lever -1.5 + 0.2 80 = 14.5 m
    (90, (0.0, 150822.0, -226233.0)),               # lever x_L,current
    (150, (3358.689, 75411.0, -1319692.5)),         # lever -1.5 - 0.2 80 = -17.5 m (lower clip)
    (180, (3878.28, 0.0, 0.0)),
])
def test_current_worked_example(heading, expected):
    # The transcription's table (currentloads.md): 1 m/s, q = 513 Pa; 513 18 6 0.07 = 3878.28 N,
    # 513 490 0.6 = 150822 N.
    assert current_load(HULL, 1.0, DEG(heading)) == pytest.approx(expected, rel=1e-6, abs=1e-6)


@pytest.mark.parametrize(("heading", "expected"), [
    (0, (-18752.4833, 0.0, 0.0)),
    (90, (-3424.5931, 155807.1288, -423795.3903)),
    (135, (13367.2678, 110172.2773, -631287.1491)),
    (180, (20434.5981, 0.0, 0.0)),
    (270, (-3424.5931, -155807.1288, 423795.3903)),
])
def test_wave_drift_worked_example_short_waves(heading, expected):
    # The transcription's table (waveloads.md): Hs 2 m, Tp 3.5 s, both period factors 1.
    assert wave_drift_load(HULL, 2.0, 3.5, DEG(heading)) == pytest.approx(expected, rel=1e-6, abs=1e-6)


@pytest.mark.parametrize(("heading", "expected"), [
    (0, (-27034.2779, 0.0, 0.0)),
    (90, (-4937.0209, 138411.5230, -376479.3425)),
    (180, (29459.2772, 0.0, 0.0)),
])
def test_wave_drift_worked_example_long_waves(heading, expected):
    # Hs 4 m, Tp 10 s: T'surge 1.8625, f = 0.360409; T'sway 2.2370, f = 0.222088.
    assert wave_drift_load(HULL, 4.0, 10.0, DEG(heading)) == pytest.approx(expected, rel=1e-6, abs=1e-6)


def test_period_factor_is_continuous_and_by_hand():
    assert period_factor(0.5) == 1.0 and period_factor(1.0) == 1.0
    assert period_factor(1.0 + 1e-9) == pytest.approx(1.0)
    assert period_factor(2.0) == pytest.approx(0.125 * math.exp(0.875))        # 2^-3 e^(1 - 2^-3)


def test_aft_waterplane_coefficient_is_clipped():
    # C_WLaft 0.5 is clipped to 0.85: h1B = 0.7 0.85^2 = 0.50575, from astern h1 = h1B,
    # h2 = 0.05 + 0.95 arctan(1.45 (pi - 1.75)) = 1.10515111; Fx = 32610.7944 0.50575 1.10515111.
    thin = replace(HULL, waterplane_area_aft=360.0)
    assert wave_drift_load(thin, 2.0, 3.5, math.pi)[0] == pytest.approx(32610.7944 * 0.50575 * 1.10515111, rel=1e-7)


def test_calm_and_zero_give_zero():
    assert not np.any(wave_drift_load(HULL, 0.0, math.nan, 1.0))
    assert not np.any(wind_load(HULL, 0.0, 1.0)) and not np.any(current_load(HULL, 0.0, 1.0))


@pytest.mark.parametrize("heading", range(0, 360, 15))
def test_port_starboard_mirror(heading):
    for load in (lambda d: wind_load(HULL, 12.0, d), lambda d: current_load(HULL, 0.75, d),
                 lambda d: wave_drift_load(HULL, 4.0, 9.0, d)):
        starboard, port = load(DEG(heading)), load(DEG(360 - heading))
        assert port == pytest.approx(starboard * np.array([1.0, -1.0, -1.0]), abs=1e-6)


def test_head_and_stern_signs():
    assert wind_load(HULL, 10.0, 0.0)[0] < 0 < wind_load(HULL, 10.0, math.pi)[0]
    assert current_load(HULL, 1.0, 0.0)[0] < 0 < current_load(HULL, 1.0, math.pi)[0]
    assert wave_drift_load(HULL, 2.0, 6.0, 0.0)[0] < 0 < wave_drift_load(HULL, 2.0, 6.0, math.pi)[0]
    assert fold(DEG(-90)) == pytest.approx(math.pi / 2) and fold(DEG(540)) == pytest.approx(math.pi)


def test_body_frame_conversion():
    # Standard [Fx, Fy, Mz] = [1, 2, 3] about Lpp/2; body origin 10 m forward of Lpp/2:
    # about it Mz = 3 - 10 2 = -17; FRD: [1, -2, 17].
    frame = BodyFrame(origin_x=10.0, origin_height=5.0)
    assert frame.load(np.array([1.0, 2.0, 3.0])) == pytest.approx([1.0, -2.0, 17.0])
    assert frame.standard_x(-41.5) == pytest.approx(-31.5) and frame.height(4.5) == pytest.approx(0.5)
    # Wind from starboard pushes to port: Y < 0 in FRD, as in the standard's Fy > 0.
    frame = BodyFrame(0.0, 6.0)
    components = LoadComponents(wind=frame.load(wind_load(HULL, 10.0, DEG(90))),
                                current=frame.load(current_load(HULL, 1.0, DEG(90))),
                                waves=frame.load(wave_drift_load(HULL, 2.0, 3.5, DEG(90))))
    assert components.wind == pytest.approx([0.0, -44136.0, -220680.0], abs=1e-6)
    assert components.total == pytest.approx(components.wind + components.current + components.waves)


@pytest.mark.parametrize(("change", "key"), [
    ({"lpp": -1.0}, "lpp"), ({"los": 0.0}, "los"), ({"bow_angle": 2.0}, "bow_angle"),
    ({"wind_centre_x": math.nan}, "wind_centre_x"), ({"current_area_lateral": True}, "current_area_lateral"),
])
def test_bad_hull_is_refused_by_key(change, key):
    with pytest.raises(ValueError, match=key):
        replace(HULL, **change)
