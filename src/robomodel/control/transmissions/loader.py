"""Building transmissions from URDF ``<transmission>`` elements (ROS 1 or ROS 2 form)."""

from __future__ import annotations

from robomodel.control.transmissions.base import Transmission
from robomodel.control.transmissions.differential import DifferentialTransmission
from robomodel.control.transmissions.exceptions import TransmissionError
from robomodel.control.transmissions.simple import SimpleTransmission
from robomodel.description.model import Transmission as TransmissionElement

__all__ = ["transmission_from_description"]

KNOWN = (
    "transmission_interface/SimpleTransmission",
    "transmission_interface/DifferentialTransmission",
)


def _by_role(items: tuple[object, ...], prefix: str) -> list[object]:
    """Order by ``role`` (``joint1``, ``joint2``), as differential_transmission_loader.cpp."""
    return sorted(
        items, key=lambda it: getattr(it, "role", None) or f"{prefix}{items.index(it) + 1}"
    )


def transmission_from_description(element: TransmissionElement) -> Transmission:
    """The transmission a ``<transmission>`` describes.

    Missing reductions count as 1 and missing offsets as 0 (ROS 1 requires the actuator's
    ``mechanicalReduction``; we accept its absence, as the ROS 2 loader does for joints).
    """
    kind = element.type.replace(" ", "_").split("/")[-1]
    if kind == "SimpleTransmission":
        if len(element.joints) != 1 or len(element.actuators) != 1:
            raise TransmissionError(
                f"transmission '{element.name}': SimpleTransmission needs one joint and one "
                f"actuator, got {len(element.joints)} and {len(element.actuators)}"
            )
        joint, actuator = element.joints[0], element.actuators[0]
        reduction = actuator.mechanical_reduction or element.mechanical_reduction or 1.0
        return SimpleTransmission(reduction, joint.offset or 0.0)
    if kind == "DifferentialTransmission":
        joints = _by_role(element.joints, "joint")
        actuators = _by_role(element.actuators, "actuator")
        if len(joints) != 2 or len(actuators) != 2:
            raise TransmissionError(
                f"transmission '{element.name}': DifferentialTransmission needs two joints "
                "and two actuators"
            )
        return DifferentialTransmission(
            [getattr(a, "mechanical_reduction", None) or 1.0 for a in actuators],
            [getattr(j, "mechanical_reduction", None) or 1.0 for j in joints],
            [getattr(j, "offset", None) or 0.0 for j in joints],
        )
    raise TransmissionError(
        f"transmission '{element.name}' has type '{element.type}'; supported: {', '.join(KNOWN)}"
    )
