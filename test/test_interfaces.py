"""The generated allocator_msgs interfaces: importable from the venv with no sourcing, with
the exact fields and constants other packages rely on."""

from allocator_msgs.msg import (
    ActuatorFault,
    AllocationStatus,
    ConsequenceAnalysis,
    GroupConsequence,
    PowerAvailable,
    ThrusterCommands,
)
from allocator_msgs.srv import GetCapability, SetActuatorFault, SetGroupFault


def test_actuator_fault_constants_and_fields():
    assert (ActuatorFault.NOMINAL, ActuatorFault.DEGRADED, ActuatorFault.FAILED, ActuatorFault.STUCK) == (0, 1, 2, 3)
    assert ActuatorFault.get_fields_and_field_types() == {
        "actuator": "string", "mode": "uint8", "efficiency": "double", "azimuth": "double"}


def test_thruster_commands_fields():
    assert ThrusterCommands.get_fields_and_field_types() == {
        "header": "std_msgs/Header", "name": "sequence<string>", "thrust": "sequence<double>",
        "command": "sequence<double>", "azimuth": "sequence<double>", "mode": "sequence<uint8>"}


def test_allocation_status_fields():
    assert AllocationStatus.get_fields_and_field_types() == {
        "header": "std_msgs/Header", "requested": "geometry_msgs/Wrench", "achieved": "geometry_msgs/Wrench",
        "saturated": "boolean", "method": "string", "solver_status": "string", "outcome": "uint8",
        "iterations": "uint32",
        "solve_time": "double", "power": "double", "unallocated": "geometry_msgs/Wrench",
        "at_thrust_limit": "sequence<boolean>", "at_rate_limit": "sequence<boolean>", "voltage": "double",
        "power_source": "sequence<string>", "source_power": "sequence<double>",
        "source_available": "sequence<double>", "power_limited": "boolean", "consequence_alarm": "boolean",
        "lost_reach": "sequence<string>"}
    assert (AllocationStatus.OUTCOME_SOLVED, AllocationStatus.OUTCOME_INACCURATE,
            AllocationStatus.OUTCOME_ITERATION_LIMIT, AllocationStatus.OUTCOME_FALLBACK,
            AllocationStatus.OUTCOME_STOPPED) == (0, 1, 2, 3, 4)


def test_set_actuator_fault_service():
    assert SetActuatorFault.Request.get_fields_and_field_types() == {"fault": "allocator_msgs/ActuatorFault"}
    assert SetActuatorFault.Response.get_fields_and_field_types() == {"success": "boolean", "message": "string"}


def test_get_capability_service():
    assert GetCapability.Request.get_fields_and_field_types() == {"direction": "geometry_msgs/Wrench"}
    assert GetCapability.Response.get_fields_and_field_types() == {
        "success": "boolean", "message": "string", "scale": "double", "achieved": "geometry_msgs/Wrench"}


def test_power_available_fields():
    assert PowerAvailable.get_fields_and_field_types() == {
        "header": "std_msgs/Header", "source": "sequence<string>", "available": "sequence<double>"}


def test_consequence_analysis_fields():
    assert GroupConsequence.get_fields_and_field_types() == {
        "group": "string", "utilisation": "double", "margin": "double"}
    assert ConsequenceAnalysis.get_fields_and_field_types() == {
        "header": "std_msgs/Header", "load": "geometry_msgs/Wrench",
        "groups": "sequence<allocator_msgs/GroupConsequence>", "alarm": "boolean"}


def test_set_group_fault_service():
    assert SetGroupFault.Request.get_fields_and_field_types() == {"group": "string"}
    assert SetGroupFault.Response.get_fields_and_field_types() == {"success": "boolean", "message": "string"}
