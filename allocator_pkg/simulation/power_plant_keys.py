"""The keys of a scenario's ``power_plant`` section (:data:`POWER_PLANT`), part of
:data:`~.scenario_keys.SCENARIO_KEYS`: the simulated generator sets, other consumers,
power management system and load reduction of :mod:`.electric_plant`. The defaults are
MarPowSim's drilling rig (NTNU-MCS/MarPowSim,
``Example/DrillingRigMSStoolbox/initDrillingRigMSStoolbox.m``)."""

from __future__ import annotations

from ..configuration.file_keys import BOOLEAN, EACH, LIST, MAPPING, NUMBER, TEXT, FileKey

GENERATOR_SET_KEYS = (
    FileKey("name", TEXT, "the set's name, unique", required=True),
    FileKey("switchboard", TEXT, "the power source of the vehicle (a switchboard) it feeds", required=True),
    FileKey("rating", NUMBER, "S, its apparent power rating (MarPowSim `Sb`: 9.1 MVA)", required=True, unit="kVA",
            minimum=0.0, exclusive_minimum=True),
    FileKey("power_factor", NUMBER, "its rated power over S (MarPowSim `powerFactor`)", default=0.85,
            minimum=0.0, maximum=1.0, exclusive_minimum=True),
    FileKey("inertia", NUMBER, "H, the inertia constant (MarPowSim `H`: 2 x 1.2027 s)", default=2.4054, unit="s",
            minimum=0.0, exclusive_minimum=True),
    FileKey("droop", NUMBER, "R, the governor droop (MarPowSim `governor.droop`)", default=0.02, unit="pu",
            minimum=0.0, maximum=0.2, exclusive_minimum=True),
    FileKey("governor_time_constant", NUMBER, "T of the governor and engine as one first-order lag (not in "
            "MarPowSim, whose governor is a PID on an engine model)", default=0.5, unit="s", minimum=0.0,
            exclusive_minimum=True),
    FileKey("p_max", NUMBER, "the engine's largest power (MarPowSim `pMax`)", default=1.1, unit="pu of S",
            minimum=0.0, exclusive_minimum=True),
    FileKey("step_allowance", NUMBER, "the load the engine takes at once above its slow level (MarPowSim "
            "`governor.deltaU`)", default=0.19882, unit="pu of S", minimum=0.0),
    FileKey("ramp_max", NUMBER, "the slow level's largest rise (MarPowSim `governor.rampMax`)", default=0.08109741,
            unit="pu of S/s", minimum=0.0, exclusive_minimum=True),
    FileKey("under_frequency", NUMBER, "the relay's lower frequency (MarPowSim `wMin`)", default=0.9, unit="pu",
            minimum=0.0, maximum=1.0, exclusive_minimum=True, exclusive_maximum=True),
    FileKey("over_frequency", NUMBER, "the relay's upper frequency (MarPowSim `wMax`)", default=1.1, unit="pu",
            minimum=1.0, exclusive_minimum=True),
    FileKey("trip_delay", NUMBER, "how long out of the band before the breaker opens (MarPowSim `wBreakerTime`)",
            default=0.1, unit="s", minimum=0.0),
    FileKey("connected", BOOLEAN, "on the bus at t = 0", default=True),
)
CONSUMER_KEYS = (
    FileKey("switchboard", TEXT, "the power source of the vehicle it draws from", required=True),
    FileKey("power", NUMBER, "its power while on", required=True, unit="kW", minimum=0.0),
    FileKey("on_time", NUMBER, "on for this long in each period (a drawworks pulse, MarPowSim `lengthHigh`); 0: "
            "always on", default=0.0, unit="s", minimum=0.0),
    FileKey("off_time", NUMBER, "then off for this long (MarPowSim `lengthLow`)", default=0.0, unit="s", minimum=0.0),
    FileKey("start", NUMBER, "the first period starts then", default=0.0, unit="s"),
)
MANAGEMENT_KEYS = (
    FileKey("reaction_time", NUMBER, "after a fault, when the reported power available is first held "
            "(MarPowSim `reactionTimePowerAvaialble`)", default=1.0, unit="s", minimum=0.0),
    FileKey("ramp_time", NUMBER, "the held power available rises by the bus's rated power in this time "
            "(MarPowSim `rampTimePowerAvaialble`)", default=45.0, unit="s", minimum=0.0, exclusive_minimum=True),
)
LOAD_REDUCTION_KEYS = (
    FileKey("enabled", BOOLEAN, "the fast load reduction and the frequency-based thrust limitation act",
            default=True),
    FileKey("reaction_time", NUMBER, "from a trip signal to the thrusters' reduced limit (MarPowSim "
            "`flrRestoreTime`)", default=0.2, unit="s", minimum=0.0),
    FileKey("restore_time", NUMBER, "a limit rises back by the thruster's rated power in this time (MarPowSim "
            "`flrRampTime`)", default=5.0, unit="s", minimum=0.0, exclusive_minimum=True),
    FileKey("frequency_start", NUMBER, "below this bus frequency its thrusters' power is limited", default=0.97,
            unit="pu", minimum=0.0, maximum=1.0, exclusive_minimum=True),
    FileKey("frequency_zero", NUMBER, "the frequency at which that limit reaches 0", default=0.9, unit="pu",
            minimum=0.0, range_doc="below frequency_start"),
)
POWER_PLANT = FileKey(
    "power_plant", MAPPING, "a simulated electric power plant on the vehicle's power sources (docs/power.md, "
    "\"The drilling-rig benchmark\"): it reports power_available in place of the capacities, and the `power` "
    "and `group_fault` events do not apply; its bus ties are the vehicle's (`power.bus_ties`), which the `bus_tie` "
    "event opens and closes for the allocator and the plant alike", default_doc="none (each source at its capacity)",
    keys=(
        FileKey("generator_sets", LIST, "the diesel generator sets", required=True, keys=GENERATOR_SET_KEYS,
                item=EACH),
            FileKey("consumers", LIST, "the other consumers (hotel, drilling, a drawworks)", default_doc="none",
                keys=CONSUMER_KEYS, item=EACH),
        FileKey("management", MAPPING, "the power management system's power available", keys=MANAGEMENT_KEYS),
        FileKey("load_reduction", MAPPING, "the fast load reduction of the PMS and the thruster drives",
                keys=LOAD_REDUCTION_KEYS)))
"""A scenario's ``power_plant`` section."""
