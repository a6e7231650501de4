"""The supply voltage from battery_state in a node on simulated time: it sets the thrust limits,
bad ones are counted and kept out, and without one for battery_timeout the limits go back to
nominal_voltage."""

import math

import pytest
from conftest import ROOT

BLUEROV = ROOT / "config" / "bluerov2_heavy.yaml"


@pytest.mark.params(BLUEROV, wrench_timeout=0.0, battery_timeout=2.0)
def test_the_battery_voltage_sets_the_thrust_limits_and_bad_ones_are_counted(harness):
    from sensor_msgs.msg import BatteryState
    battery = harness.probe.create_publisher(BatteryState, "battery_state", 10)
    harness.spin_until(lambda: battery.get_subscription_count() > 0)
    values = harness.diagnostics_after_a_second()
    assert values["voltage source"] == "nominal_voltage (no battery voltage)" and values["voltage [V]"] == "16"
    battery.publish(BatteryState(voltage=12.0))
    harness.spin_until(lambda: harness.node.allocator.voltage == 12.0)
    harness.send_wrench([0.0, 0.0, 400.0, 0.0, 0.0, 0.0])
    harness.tick(2)
    status = harness.status[-1]
    assert status.voltage == 12.0 and status.saturated
    assert status.achieved.force.z == pytest.approx(4 * 36.4, rel=1e-4)          # 12 V: 36.4 N a thruster
    assert status.unallocated.force.z == pytest.approx(400.0 - 4 * 36.4, rel=1e-3)
    assert list(status.at_thrust_limit) == [False] * 4 + [True] * 4
    for count, bad in enumerate((math.nan, 25.0, -1.0), start=1):
        battery.publish(BatteryState(voltage=bad))
        harness.spin_until(lambda count=count: harness.node.runtime.counters.rejected_battery == count)
    assert harness.node.allocator.voltage == 12.0
    values = harness.diagnostics_after_a_second()
    assert values["rejected battery states"] == "3" and values["voltage source"].endswith("battery_state")
    harness.tick(round(2.0 / harness.node.period))                              # no battery for battery_timeout
    values = harness.diagnostics_after_a_second()
    assert values["voltage [V]"] == "16" and values["voltage source"] == "nominal_voltage (no battery voltage)"
    assert harness.node.allocator.voltage == 16.0


def test_a_voltage_before_the_simulated_clock_starts_counts_from_its_start():
    """Before the first /clock a node on simulated time reads 0: a voltage stamped then must not
    look battery_timeout old when the clock starts at 100 s (it did, with a false warning)."""
    import threading

    import rclpy
    from rclpy.parameter import Parameter
    from sensor_msgs.msg import BatteryState

    from allocator_pkg import Allocator, load_vehicle
    from allocator_pkg.ros.battery import BatteryInput
    from allocator_pkg.ros.diagnostics import Counters
    from allocator_pkg.ros.process import namespace_arguments, run_namespace

    context = rclpy.Context()
    rclpy.init(context=context, args=["--ros-args", *namespace_arguments(run_namespace())])   # /clock of its own
    try:
        node = rclpy.create_node("battery_probe", context=context,
                                 parameter_overrides=[Parameter("use_sim_time", value=True)])
        allocator = Allocator(load_vehicle(BLUEROV))
        battery = BatteryInput(node, threading.Lock(), allocator, Counters())
        assert node.get_clock().now().nanoseconds == 0
        battery._on_battery(BatteryState(voltage=12.0))
        assert allocator.voltage == 12.0 and not battery.fallback
        start = 100_000_000_000
        battery.check(start, 5.0)
        battery.check(start + 4_900_000_000, 5.0)
        assert allocator.voltage == 12.0 and not battery.fallback
        battery.check(start + 5_100_000_000, 5.0)
        assert allocator.voltage == 16.0 and battery.fallback
        battery.close()
        node.destroy_node()
    finally:
        rclpy.try_shutdown(context=context)
