"""allocator_pkg.simulation.control_system: the controller acting on the passive observer's
estimate in a closed-loop run of the DP vessel in a JONSWAP sea (the allocator in process),
read from a scenario file's keys; the keys' checks."""

import contextlib
import math
from dataclasses import replace

import numpy as np
import pytest
import yaml
from conftest import ROOT
from scipy import signal

from allocator_pkg.simulation.closed_loop import ClosedLoop
from allocator_pkg.simulation.in_process import InProcessLink
from allocator_pkg.simulation.scenario import load_scenario
from allocator_pkg.simulation.scenario_values import ScenarioError

BASE = ROOT / "config" / "scenarios" / "dp_station_keeping.yaml"


def scenario_file(tmp_path, **changes):
    data = yaml.safe_load(BASE.read_text())
    data.update(vehicle=str(ROOT / "config" / "dp_vessel.yaml"),
                particulars=str(ROOT / "config" / "particulars" / "dp_vessel.yaml"), **changes)
    path = tmp_path / "scenario.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


@contextlib.contextmanager
def in_process(run, out):
    yield InProcessLink(run)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 2])
def test_the_controller_acts_on_the_estimate_which_filters_the_wave_motion(tmp_path, seed):
    """Hs 2.5 m, Tp 8 s from the starboard bow, 0.1 m and 0.05 deg of noise: over 120 s every
    request is the controller's law at the estimate plus the feed-forward; the estimate's error
    from the vessel's low-frequency position has an RMS under 0.8 of the measurement's, its part
    above 0.05 Hz (the wave frequencies) under 0.4 of the wave motion's (the notch passes 0.10 at
    omega_o), and the vessel holds station within 4 m."""
    path = scenario_file(tmp_path, seed=seed, duration=120.0,
                         observer={"enabled": True}, measurement={"position_sigma": 0.1, "heading_sigma": 0.05},
                         controller={**yaml.safe_load(BASE.read_text())["controller"], "wind_feedforward": True},
                         environment={**yaml.safe_load(BASE.read_text())["environment"],
                                      "waves": {"hs": 2.5, "peak_period": 8.0, "direction": 40.0,
                                                "spectrum": "jonswap"}})
    scenario = load_scenario(path)
    assert scenario.control.observer.wave_period == 8.0 and scenario.control.wind_feedforward
    loop = ClosedLoop(scenario, tmp_path / "run", in_process, log=lambda _: None)
    control, records = loop.control, []
    advance = control.advance

    def recorded(setpoint, dt, unallocated):
        law = control.controller.wrench(control.observer.eta, control.observer.nu, setpoint) + control.feedforward
        records.append((control.plant.eta.copy(), control.observer.eta.copy(), control.measured.copy(),
                        control.request[[0, 1, 5]].copy(), law))
        advance(setpoint, dt, unallocated)

    control.advance = recorded
    result = loop.run()
    true, estimate, measured, request, law = (np.array(column) for column in zip(*records))
    assert request == pytest.approx(law, rel=1e-12, abs=1e-6)
    error, wave = (estimate - true)[:, :2], (measured - true)[:, :2]
    assert rms(error) < 0.8 * rms(wave)
    high = signal.butter(2, 0.05, "highpass", fs=1.0 / loop.period, output="sos")
    assert rms(signal.sosfiltfilt(high, error, axis=0)) < 0.4 * rms(signal.sosfiltfilt(high, wave, axis=0))
    assert result.metrics["position_error_max"] < 4.0


def rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum(values ** 2, axis=1))))


def test_the_control_system_is_off_unless_a_file_turns_it_on(tmp_path):
    scenario = load_scenario(BASE)
    assert scenario.control.observer is None and not scenario.control.wind_feedforward
    assert not scenario.fault_trip and scenario.thrust_losses is None
    on = load_scenario(scenario_file(tmp_path, observer={"enabled": True, "wave_period": 9.0, "cutoff_ratio": 1.3},
                                     fault_trip=True))
    assert on.control.observer.wave_period == 9.0 and on.control.observer.cutoff_ratio == 1.3 and on.fault_trip
    assert "passive observer" in on.control.describe() and "omega_c = 1.3 omega_o" in on.control.describe()


@pytest.mark.parametrize(("changes", "key"), [
    ({"observer": {"enabled": True, "cutoff_ratio": 0.9}}, "observer.cutoff_ratio"),
    ({"observer": {"enabled": True, "k3_ratio": 2.0}}, "observer.k3_ratio"),
    ({"observer": {"enabled": True, "wave_damping": 1.5}}, "observer.wave_damping"),
    ({"observer": {"enabled": True, "bias_time_constant": 10.0}}, "observer.bias_time_constant"),
    ({"observer": {"enabled": "yes"}}, "observer.enabled"),
    ({"observer": {"enabled": True, "k4_bis": [1.0, 1.0]}}, "observer.k4_bis"),
    ({"measurement": {"position_sigma": -0.1}}, "measurement.position_sigma"),
    ({"fault_trip": 1}, "fault_trip"),
    ({"observer": {"enabled": True, "gain": 1.0}}, "observer.gain"),
])
def test_a_bad_control_system_key_is_refused_naming_it(tmp_path, changes, key):
    with pytest.raises(ScenarioError, match=key.replace(".", r"\.")):
        load_scenario(scenario_file(tmp_path, **changes))


def test_the_rov_takes_no_observer(tmp_path):
    data = yaml.safe_load((ROOT / "config" / "scenarios" / "rov_thruster_failure.yaml").read_text())
    data.update(vehicle=str(ROOT / "config" / "bluerov2_heavy.yaml"), observer={"enabled": True, "wave_period": 8.0})
    path = tmp_path / "rov.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(ScenarioError, match=r"observer\.enabled: for the dp_vessel model only"):
        load_scenario(path)
    assert math.isfinite(replace(load_scenario(BASE), fault_trip=True).duration)
