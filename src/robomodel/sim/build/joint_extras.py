"""Joint dynamics that URDF 1.0 has no element for: armature and springs.

* **Armature** (rotor inertia reflected through the gearbox, added to the joint's diagonal of
  the mass matrix, MuJoCo ``joint.armature``) comes from Drake's transmission extension, the
  one published URDFs use for it::

      <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
        <joint name="joint1"/>
        <actuator name="motor1">
          <drake:rotor_inertia value="3.3e-5"/>   <!-- [kg m^2] -->
          <drake:gear_ratio value="100"/>         <!-- default: <mechanicalReduction>, else 1 -->
        </actuator>
      </transmission>

  armature = rotor_inertia x gear_ratio^2. Only single-joint transmissions carry it.
* **Springs** come from ``<gazebo reference="JOINT">`` ``<springStiffness>`` [N m/rad or N/m]
  and ``<springReference>`` [rad or m] (sdformat parser_urdf.cc: SDF ``dynamics/
  spring_stiffness``, ``spring_reference``), MuJoCo ``joint.stiffness`` and ``springref``.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from robomodel.description.model import GazeboBlock, RawElement, Robot, Transmission
from robomodel.sim.build.inertia import where
from robomodel.sim.exceptions import SimulationError

__all__ = ["JointExtras", "read_joint_extras"]

DRAKE_NS = "http://drake.mit.edu"


@dataclass(frozen=True, slots=True)
class JointExtras:
    """Per-joint additions: ``armature`` [kg m^2 or kg], spring stiffness and reference."""

    armature: float = 0.0
    spring_stiffness: float = 0.0
    spring_reference: float = 0.0


def read_joint_extras(robot: Robot) -> dict[str, JointExtras]:
    """The armature and springs of ``robot``'s joints (only joints that have some)."""
    out: dict[str, JointExtras] = {}
    transmissions = list(robot.transmissions)
    for component in robot.ros2_control:
        transmissions.extend(component.transmissions)
    for tr in transmissions:
        armature = _armature(tr)
        if armature is not None:
            joint = tr.joints[0].name
            if not robot.has_joint(joint):
                continue  # the description layer reports transmissions naming no joint
            out[joint] = JointExtras(armature=armature)
    for block in robot.gazebo:
        if block.reference is None or not robot.has_joint(block.reference):
            continue
        stiffness, reference = _springs(block)
        if stiffness is None and reference is None:
            continue
        old = out.get(block.reference, JointExtras())
        out[block.reference] = JointExtras(
            old.armature,
            old.spring_stiffness if stiffness is None else stiffness,
            old.spring_reference if reference is None else reference,
        )
    return out


def _armature(tr: Transmission) -> float | None:
    if len(tr.joints) != 1 or len(tr.actuators) != 1:
        return None
    actuator = tr.actuators[0]
    rotor = gear = None
    for raw in actuator.extra:
        element = etree.fromstring(raw.xml)
        if element.tag == f"{{{DRAKE_NS}}}rotor_inertia":
            rotor = _value(raw, element, tr, minimum_exclusive=False)
        elif element.tag == f"{{{DRAKE_NS}}}gear_ratio":
            gear = _value(raw, element, tr, minimum_exclusive=True)
    if rotor is None:
        return None
    if gear is None:
        gear = actuator.mechanical_reduction or tr.mechanical_reduction or 1.0
    return rotor * gear * gear


def _value(raw: RawElement, element: etree._Element, tr: Transmission, *, minimum_exclusive: bool) -> float:  # fmt: skip
    text = element.get("value")
    try:
        value = float(text if text is not None else "")
    except ValueError:
        value = float("nan")
    name = f"drake:{etree.QName(element).localname}"
    bad = value != value or value < 0 or (minimum_exclusive and value == 0)
    if bad:
        bound = "> 0" if minimum_exclusive else ">= 0"
        raise SimulationError(
            f"<{name} value={text!r}> of transmission '{tr.name}' must be a number {bound}",
            where=where(raw) or where(tr),
        )
    return value


def _springs(block: GazeboBlock) -> tuple[float | None, float | None]:
    try:
        root = etree.fromstring(block.xml.encode())
    except etree.XMLSyntaxError:
        return None, None  # read_gazebo reports it
    values: dict[str, float] = {}
    for tag in ("springStiffness", "springReference"):
        el = root.find(tag)
        if el is None:
            continue
        try:
            values[tag] = float((el.text or "").strip())
        except ValueError:
            raise SimulationError(
                f"<{tag}> of joint '{block.reference}' must be a number, got {el.text!r}",
                where=where(block),
            ) from None
    stiffness = values.get("springStiffness")
    if stiffness is not None and stiffness < 0:
        raise SimulationError(
            f"<springStiffness> of joint '{block.reference}' must be >= 0, got {stiffness:g}",
            where=where(block),
        )
    return stiffness, values.get("springReference")
