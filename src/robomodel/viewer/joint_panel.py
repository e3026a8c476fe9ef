"""The joint panel: joint_state_publisher_gui in the page.

One slider per free joint (revolute and prismatic within their limits, continuous over
[-pi, pi]; prismatic values in metres) with viser's editable value box beside it, and the
Randomize and Center buttons. Mimic joints get no slider: they follow their source. Floating
and planar joints, which joint_state_publisher skips, get their own pose inputs.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from robomodel.description.model import Joint, JointType
from robomodel.runtime.nodes.joint_state_publisher import FreeJoint
from robomodel.viewer.markup import code, md, safe_markdown

__all__ = ["BodyPose", "JointPanel"]

# joint_state_publisher_gui maps [min, max] onto 10000 slider steps.
_SLIDER_STEPS = 10000


@dataclass(frozen=True, slots=True)
class BodyPose:
    """The pose a floating or planar joint's controls give (its motion after ``<origin>``).

    ``xyz_m`` [m] and ``rpy_rad`` [rad]; for a planar joint only x, y (in the plane normal to the
    axis) and the rotation about the axis (``rpy_rad[2]``) are used.
    """

    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)


class JointPanel:
    """GUI controls for one robot's joints.

    Args:
        gui: viser's GUI API.
        title: Folder title (the robot's name, with its prefix).
        free_joints: joint_state_publisher's free joints, in URDF order.
        mimic: Mimic joint name to the joint it follows.
        bodies: Floating and planar joints.
        on_change: Called with ``{joint: value}`` when the user moves a slider or types a value.
        on_randomize / on_center: The buttons.
        on_body: Called with ``(joint, BodyPose)`` when a floating/planar control changes.
        note: Text shown instead of the controls' absence (e.g. joint states from the bus).
        units: Unit of each joint's value ("rad" unless given, "m" for prismatic joints).
    """

    def __init__(
        self,
        gui: Any,
        title: str,
        free_joints: Sequence[FreeJoint],
        *,
        mimic: Mapping[str, str],
        bodies: Sequence[Joint],
        on_change: Callable[[dict[str, float]], None],
        on_randomize: Callable[[], None],
        on_center: Callable[[], None],
        on_body: Callable[[str, BodyPose], None],
        note: str | None = None,
        units: Mapping[str, str] | None = None,
    ) -> None:
        self.gui = gui
        self.sliders: dict[str, Any] = {}
        self._body_inputs: dict[str, tuple[Any, Any]] = {}
        self._on_change = on_change
        self._on_body = on_body
        self._units = dict(units or {})
        self.folder = gui.add_folder(title)
        with self.folder:
            if free_joints:
                randomize = gui.add_button("Randomize", hint="every joint to a random value")
                center = gui.add_button("Center", hint="every joint to its zero")
                randomize.on_click(lambda _event: on_randomize())
                center.on_click(lambda _event: on_center())
            for joint in free_joints:
                self._add_slider(joint)
            for name, source in mimic.items():
                safe_markdown(gui, md("{} mimics {}", code(name), code(source)))
            for body in bodies:
                self._add_body(body)
            if note is not None:
                safe_markdown(gui, note)
            elif not free_joints and not bodies:
                safe_markdown(gui, md("*no movable joints*"))

    def _add_slider(self, joint: FreeJoint) -> None:
        low, high = joint.min, joint.max
        if high <= low:  # joint_state_publisher_gui shows no slider for min == max
            return
        step = (high - low) / _SLIDER_STEPS
        value = joint.position if joint.position is not None else joint.zero
        slider = self.gui.add_slider(
            joint.name,
            min=low,
            max=high,
            step=step,
            initial_value=min(max(value, low), high),
            hint=f"[{low:.3f}, {high:.3f}] {self._units.get(joint.name, 'rad')}"
            + (" (continuous)" if joint.continuous else ""),
        )
        name = joint.name

        def changed(event: Any) -> None:
            if event.client is None:  # set by the program (Randomize, Center, reload)
                return
            self._on_change({name: float(slider.value)})

        slider.on_update(changed)
        self.sliders[name] = slider

    def _add_body(self, joint: Joint) -> None:
        planar = joint.type is JointType.PLANAR
        label = f"{joint.name} ({joint.type.value})"
        safe_markdown(self.gui, md("**{}**", label))
        if planar:
            xyz = self.gui.add_vector2(f"{joint.name} x y", (0.0, 0.0), step=0.001)
            rpy = self.gui.add_number(f"{joint.name} angle", 0.0, step=0.001)
        else:
            xyz = self.gui.add_vector3(f"{joint.name} xyz", (0.0, 0.0, 0.0), step=0.001)
            rpy = self.gui.add_vector3(f"{joint.name} rpy", (0.0, 0.0, 0.0), step=0.001)
        name = joint.name

        def changed(_event: Any) -> None:
            self._on_body(name, self.body_pose(name))

        xyz.on_update(changed)
        rpy.on_update(changed)
        self._body_inputs[name] = (xyz, rpy)

    def body_pose(self, name: str) -> BodyPose:
        """The current pose of a floating/planar joint's controls."""
        xyz, rpy = self._body_inputs[name]
        t = tuple(float(v) for v in xyz.value)
        if isinstance(rpy.value, tuple):
            r = tuple(float(v) for v in rpy.value)
            return BodyPose((t[0], t[1], t[2]), (r[0], r[1], r[2]))
        return BodyPose((t[0], t[1], 0.0), (0.0, 0.0, float(rpy.value)))

    def set_values(self, positions: Mapping[str, float]) -> None:
        """Move sliders to ``positions`` (after Randomize, Center or an external update)."""
        for name, value in positions.items():
            slider = self.sliders.get(name)
            if slider is not None:
                slider.value = min(max(float(value), slider.min), slider.max)

    def remove(self) -> None:
        self.folder.remove()
