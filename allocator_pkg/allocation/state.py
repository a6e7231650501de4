"""What the actuators are doing between samples: the state a sample starts from and commits."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..effectiveness.model import Model
from .azimuth import AzimuthState


@dataclass
class ActuatorState:
    """Thrust, angle and control-surface deflection of every actuator (configuration order),
    and the crossing state of each rotatable thruster (actuator indices ``rotatable``).
    ``thrust`` and ``angle`` are shared with the last result, so both are read-only."""

    thrust: np.ndarray
    angle: np.ndarray
    deflection: np.ndarray
    azimuth: list[AzimuthState] = field(default_factory=list)
    rotatable: list[int] = field(default_factory=list)

    @classmethod
    def at_start(cls, model: Model) -> ActuatorState:
        """Zero thrust, every rotatable thruster at its initial angle."""
        angle = np.zeros(model.r)
        for i in model.rot:
            angle[i] = model.vehicle.actuators[i].rotation.initial
        return cls(thrust=np.zeros(model.r), angle=angle, deflection=np.zeros(model.r),
                   azimuth=[AzimuthState(angle=float(angle[i])) for i in model.rot], rotatable=model.rot.tolist())

    def commit(self, model: Model, thrust: np.ndarray, angle: np.ndarray, lift: np.ndarray) -> None:
        """This sample's thrust and angles become the state (made read-only: the result
        shares them); a control surface's deflection is its force over its lift gain."""
        thrust.setflags(write=False)
        angle.setflags(write=False)
        self.thrust, self.angle = thrust, angle
        surfaces = model.surfaces
        if surfaces.size:
            gain = lift[surfaces]
            self.deflection[surfaces] = np.divide(thrust[surfaces], gain, out=np.zeros(surfaces.size), where=gain > 0.0)
        for azimuth_state, i in zip(self.azimuth, self.rotatable):
            azimuth_state.angle = float(angle[i])
            azimuth_state.thrust = float(thrust[i])
