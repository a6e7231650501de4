"""allocator_pkg.simulation.power_plant: the simulated power plant starts at the capacities,
reports only what the power events named, trips a group's sources until the faults clear."""

import numpy as np
from conftest import ROOT

from allocator_pkg.configuration.parameters import load_vehicle
from allocator_pkg.simulation.power_plant import PowerPlant

VESSEL = load_vehicle(ROOT / "config" / "dp_vessel.yaml")


def test_the_plant_trips_a_group_and_restores_what_its_sources_gave():
    plant = PowerPlant(VESSEL)
    assert plant.sources == ("swbd_a", "swbd_b") and plant.reported == {}
    np.testing.assert_array_equal(plant.available(), [5600.0, 7800.0])
    plant.set_available("swbd_b", 2000.0)
    assert plant.reported == {"swbd_b": 2000.0}
    assert plant.trip_group("switchboard_b") == ("azimuth_port", "tunnel_aft")
    np.testing.assert_array_equal(plant.available(), [5600.0, 0.0])
    plant.set_available("swbd_b", 3000.0)                     # a tripped board gives nothing whatever it reports
    np.testing.assert_array_equal(plant.available(), [5600.0, 0.0])
    plant.restore()
    np.testing.assert_array_equal(plant.available(), [5600.0, 3000.0])


def test_a_vehicle_without_sources_has_an_empty_plant():
    plant = PowerPlant(load_vehicle(ROOT / "config" / "bluerov2_heavy.yaml"))
    assert plant.sources == () and plant.available().shape == (0,)
