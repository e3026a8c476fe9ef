"""Broken URDF files, one per rule, with the verdict urdfdom gives and where we must point.

``verdict`` is what both tools must agree on:
- ``"fatal"``: check_urdf exits non-zero; robomodel check exits 2.
- ``"error"``: check_urdf logs ``Error:`` but exits 0 (urdfdom drops the element); robomodel
  reports an error at the element and exits 2.
- ``"warn"``: check_urdf accepts silently; robomodel accepts (exit 0) and warns.
- ``"hang"``: check_urdf never terminates (it recurses forever); robomodel warns and exits 0.
``at`` is a substring of the line our diagnostic must point at (None: any line).
"""

from __future__ import annotations

from dataclasses import dataclass

HEAD = '<?xml version="1.0"?>\n'


@dataclass(frozen=True)
class Case:
    name: str
    xml: str
    verdict: str
    at: str | None
    code: str = ""
    urdfdom6: bool = False  # needs urdfdom 6 (URDF 1.1/1.2 features)

    def line(self) -> int | None:
        if self.at is None:
            return None
        for number, text in enumerate(self.xml.splitlines(), start=1):
            if self.at in text:
                return number
        raise AssertionError(f"marker {self.at!r} not in case {self.name}")


def robot(body: str, attrs: str = ' name="r"') -> str:
    return f"{HEAD}<robot{attrs}>\n{body}</robot>\n"


LINK_A_B = '  <link name="a"/>\n  <link name="b"/>\n'
INERTIAL_OK = (
    '    <inertial>\n      <mass value="1"/>\n'
    '      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n'
)


def joint(body: str, jtype: str = "revolute", name: str = "j") -> str:
    return (
        f'  <joint name="{name}" type="{jtype}">\n    <parent link="a"/>\n    <child link="b"/>\n'
        f"{body}  </joint>\n"
    )


LIMIT = '    <limit lower="-1" upper="1" effort="1" velocity="1"/>\n'

CASES: tuple[Case, ...] = (
    # --- XML and document level (fatal) -------------------------------------------------
    Case("malformed_xml", robot('  <link name="a">\n  <link name="b"/>\n'), "fatal", None),
    Case("empty_file", "", "fatal", None),
    Case(
        "not_robot_root",
        HEAD + '<model name="r">\n  <link name="a"/>\n</model>\n',
        "fatal",
        "<model",
    ),
    Case("no_robot_name", robot('  <link name="a"/>\n', attrs=""), "fatal", "<robot"),
    Case(
        "version_2_0", robot('  <link name="a"/>\n', ' name="r" version="2.0"'), "fatal", "<robot"
    ),
    Case(
        "version_one_field",
        robot('  <link name="a"/>\n', ' name="r" version="1"'),
        "fatal",
        "<robot",
    ),
    Case(
        "version_junk", robot('  <link name="a"/>\n', ' name="r" version="1.0a"'), "fatal", "<robot"
    ),
    Case(
        "version_blank", robot('  <link name="a"/>\n', ' name="r" version=".0"'), "fatal", "<robot"
    ),
    Case(
        "version_not_int",
        robot('  <link name="a"/>\n', ' name="r" version="a.0"'),
        "fatal",
        "<robot",
    ),
    Case(
        "version_negative",
        robot('  <link name="a"/>\n', ' name="r" version="-1.0"'),
        "fatal",
        "<robot",
    ),
    Case(
        "version_three_fields",
        robot('  <link name="a"/>\n', ' name="r" version="1.0.0"'),
        "fatal",
        "<robot",
    ),
    Case(
        "no_links",
        robot('  <material name="m">\n    <color rgba="1 0 0 1"/>\n  </material>\n'),
        "fatal",
        "<robot",
    ),
    # --- duplicates (fatal) --------------------------------------------------------------
    Case(
        "duplicate_link",
        robot('  <link name="a"/>\n  <link name="a"/> <!-- dup -->\n'),
        "fatal",
        "dup",
    ),
    Case(
        "duplicate_joint",
        robot(
            '  <link name="a"/>\n  <link name="b"/>\n  <link name="c"/>\n'
            '  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
            '  <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint> <!-- dup -->\n'
        ),
        "fatal",
        "dup",
    ),
    Case(
        "duplicate_material",
        robot(
            '  <material name="m"><color rgba="1 0 0 1"/></material>\n'
            '  <material name="m"><color rgba="0 1 0 1"/></material> <!-- dup -->\n'
            '  <link name="a"/>\n'
        ),
        "fatal",
        "dup",
    ),
    # --- joints (fatal) ------------------------------------------------------------------
    Case("revolute_no_limit", robot(LINK_A_B + joint("")), "fatal", '<joint name="j"'),
    Case(
        "prismatic_no_limit", robot(LINK_A_B + joint("", "prismatic")), "fatal", '<joint name="j"'
    ),
    Case(
        "limit_no_effort",
        robot(LINK_A_B + joint('    <limit lower="-1" upper="1" velocity="1"/>\n')),
        "fatal",
        "<limit",
    ),
    Case(
        "limit_no_velocity",
        robot(LINK_A_B + joint('    <limit lower="-1" upper="1" effort="1"/>\n')),
        "fatal",
        "<limit",
    ),
    Case(
        "limit_nan",
        robot(LINK_A_B + joint('    <limit lower="nan" upper="1" effort="1" velocity="1"/>\n')),
        "fatal",
        "<limit",
    ),
    Case(
        "limit_not_number",
        robot(LINK_A_B + joint('    <limit lower="-1" upper="one" effort="1" velocity="1"/>\n')),
        "fatal",
        "<limit",
    ),
    Case(
        "joint_no_name",
        robot(
            LINK_A_B
            + '  <joint type="fixed">\n    <parent link="a"/>\n    <child link="b"/>\n  </joint>\n'
        ),
        "fatal",
        "<joint",
    ),
    Case(
        "joint_no_type",
        robot(
            LINK_A_B
            + '  <joint name="j">\n    <parent link="a"/>\n    <child link="b"/>\n  </joint>\n'
        ),
        "fatal",
        "<joint",
    ),
    Case("joint_unknown_type", robot(LINK_A_B + joint("", "ball")), "fatal", "<joint"),
    Case(
        "rpy_two_values",
        robot(LINK_A_B + joint('    <origin xyz="0 0 0" rpy="0 0"/>\n' + LIMIT)),
        "fatal",
        "<origin",
    ),
    Case(
        "origin_pi_text",
        robot(LINK_A_B + joint('    <origin rpy="0 0 pi"/>\n' + LIMIT)),
        "fatal",
        "<origin",
    ),
    Case(
        "axis_two_values",
        robot(LINK_A_B + joint('    <axis xyz="0 1"/>\n' + LIMIT)),
        "fatal",
        "<axis",
    ),
    Case(
        "dynamics_empty", robot(LINK_A_B + joint(LIMIT + "    <dynamics/>\n")), "fatal", "<dynamics"
    ),
    Case("mimic_no_joint", robot(LINK_A_B + joint(LIMIT + "    <mimic/>\n")), "fatal", "<mimic"),
    Case(
        "safety_no_k_velocity",
        robot(LINK_A_B + joint(LIMIT + '    <safety_controller k_position="1"/>\n')),
        "fatal",
        "<safety_controller",
    ),
    # --- tree (fatal) --------------------------------------------------------------------
    Case(
        "unknown_parent",
        robot(
            '  <link name="b"/>\n  <joint name="j" type="fixed">\n    <parent link="a"/>\n    <child link="b"/>\n  </joint>\n'
        ),
        "fatal",
        '<joint name="j"',
    ),
    Case(
        "unknown_child",
        robot(
            '  <link name="a"/>\n  <joint name="j" type="fixed">\n    <parent link="a"/>\n    <child link="b"/>\n  </joint>\n'
        ),
        "fatal",
        '<joint name="j"',
    ),
    Case(
        "missing_parent_element",
        robot(LINK_A_B + '  <joint name="j" type="fixed">\n    <child link="b"/>\n  </joint>\n'),
        "fatal",
        '<joint name="j"',
    ),
    Case("two_roots", robot(LINK_A_B), "fatal", "<robot"),
    Case(
        "cycle_no_root",
        robot(
            LINK_A_B
            + joint("", "fixed", "j1")
            + '  <joint name="j2" type="fixed">\n    <parent link="b"/>\n    <child link="a"/>\n  </joint>\n'
        ),
        "fatal",
        "<robot",
    ),
    # --- link level (urdfdom: "Error:", exit 0) -------------------------------------------
    Case(
        "mass_nan",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass value="nan"/>\n      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n  </link>\n'
        ),
        "error",
        "<mass",
    ),
    Case(
        "mass_missing_value",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass/>\n      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n  </link>\n'
        ),
        "error",
        "<mass",
    ),
    Case(
        "inertia_missing_attr",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass value="1"/>\n      <inertia ixx="1" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n  </link>\n'
        ),
        "error",
        "<inertia ",
    ),
    Case(
        "box_no_size",
        robot(
            '  <link name="a">\n    <collision>\n      <geometry>\n        <box/>\n      </geometry>\n    </collision>\n  </link>\n'
        ),
        "error",
        "<box",
    ),
    Case(
        "box_two_values",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <box size="1 1"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<box",
    ),
    Case(
        "cylinder_no_length",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <cylinder radius="1"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<cylinder",
    ),
    Case(
        "sphere_bad_radius",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <sphere radius="1x"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<sphere",
    ),
    Case(
        "mesh_no_filename",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <mesh/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<mesh",
    ),
    Case(
        "geometry_empty",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<geometry",
    ),
    Case(
        "geometry_unknown",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <cone radius="1"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<cone",
    ),
    Case(
        "capsule_in_1_0",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <capsule radius="1" length="1"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<capsule",
    ),
    Case(
        "visual_material_no_name",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <sphere radius="1"/>\n      </geometry>\n      <material/>\n    </visual>\n  </link>\n'
        ),
        "error",
        "<material",
    ),
    Case("link_no_name", robot("  <link>\n  </link>\n"), "error", "<link"),
    Case(
        "material_rgba_out_of_range",
        robot(
            '  <material name="m">\n    <color rgba="2 0 0 1"/>\n  </material>\n  <link name="a"/>\n'
        ),
        "error",
        "<color",
    ),
    # --- accepted by urdfdom, warned by robomodel ----------------------------------------
    Case(
        "material_undefined_ref",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <sphere radius="1"/>\n      </geometry>\n      <material name="nope"/>\n    </visual>\n  </link>\n'
        ),
        "warn",
        '<material name="nope"',
        "material-undefined",
    ),
    Case(
        "zero_axis",
        robot(LINK_A_B + joint('    <axis xyz="0 0 0"/>\n' + LIMIT)),
        "warn",
        '<joint name="j"',
        "axis",
    ),
    Case(
        "axis_no_xyz",
        robot(LINK_A_B + joint("    <axis/>\n" + LIMIT)),
        "warn",
        '<joint name="j"',
        "axis",
    ),
    Case(
        "non_unit_axis",
        robot(LINK_A_B + joint('    <axis xyz="0 0 2"/>\n' + LIMIT)),
        "warn",
        '<joint name="j"',
        "axis",
    ),
    Case(
        "lower_gt_upper",
        robot(LINK_A_B + joint('    <limit lower="1" upper="-1" effort="1" velocity="1"/>\n')),
        "warn",
        '<joint name="j"',
        "limits",
    ),
    Case(
        "negative_mass",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass value="-1"/>\n      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n  </link>\n'
        ),
        "warn",
        "<inertial",
        "mass",
    ),
    Case(
        "inertia_not_positive_definite",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass value="1"/>\n      <inertia ixx="1" ixy="2" ixz="0" iyy="1" iyz="0" izz="1"/>\n    </inertial>\n  </link>\n'
        ),
        "warn",
        "<inertial",
        "inertia",
    ),
    Case(
        "inertia_triangle",
        robot(
            '  <link name="a">\n    <inertial>\n      <mass value="1"/>\n      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/>\n    </inertial>\n  </link>\n'
        ),
        "warn",
        "<inertial",
        "inertia",
    ),
    Case(
        "mimic_unknown_joint",
        robot(LINK_A_B + joint(LIMIT + '    <mimic joint="nope"/>\n')),
        "warn",
        '<joint name="j"',
        "mimic",
    ),
    Case(
        "mimic_cycle",
        robot(
            '  <link name="a"/>\n  <link name="b"/>\n  <link name="c"/>\n'
            + joint(LIMIT + '    <mimic joint="k"/>\n')
            + '  <joint name="k" type="revolute">\n    <parent link="a"/>\n    <child link="c"/>\n'
            + LIMIT
            + '    <mimic joint="j"/>\n  </joint>\n'
        ),
        "warn",
        '<joint name="j"',
        "mimic-cycle",
    ),
    Case(
        "mimic_self",
        robot(LINK_A_B + joint(LIMIT + '    <mimic joint="j"/>\n')),
        "warn",
        '<joint name="j"',
        "mimic-cycle",
    ),
    Case(
        "two_parents",
        robot(
            '  <link name="a"/>\n  <link name="b"/>\n  <link name="c"/> <!-- here -->\n'
            '  <joint name="j1" type="fixed"><parent link="a"/><child link="c"/></joint>\n'
            '  <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>\n'
            '  <joint name="j3" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
        ),
        "warn",
        "here",
        "two-parents",
    ),
    Case(
        "cycle_detached",
        robot(
            '  <link name="root"/>\n  <link name="a"/>\n  <link name="b"/> <!-- here -->\n  <link name="c"/>\n'
            '  <joint name="j1" type="fixed"><parent link="root"/><child link="a"/></joint>\n'
            '  <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>\n'
            '  <joint name="j3" type="fixed"><parent link="c"/><child link="b"/></joint>\n'
        ),
        "warn",
        "here",
        "cycle",
    ),
    Case(
        "mesh_missing_file",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <mesh filename="meshes/nope.stl"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "warn",
        "<visual",
        "mesh",
    ),
    Case(
        "package_uri_unresolved",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <mesh filename="package://no_such_pkg/meshes/a.stl"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "warn",
        "<visual",
        "mesh",
    ),
    Case(
        "negative_sphere_radius",
        robot(
            '  <link name="a">\n    <visual>\n      <geometry>\n        <sphere radius="-1"/>\n      </geometry>\n    </visual>\n  </link>\n'
        ),
        "warn",
        "<visual",
        "geometry",
    ),
    # --- check_urdf never terminates on these ----------------------------------------------
    Case(
        "self_loop",
        robot(
            '  <link name="a"/>\n  <link name="b"/>\n'
            '  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
            '  <joint name="j2" type="fixed"><parent link="b"/><child link="b"/></joint> <!-- here -->\n'
        ),
        "hang",
        "here",
        "self-loop",
    ),
    # --- URDF 1.2 rules (urdfdom 6) --------------------------------------------------------
    Case(
        "v12_upper_below_lower",
        robot(LINK_A_B + joint('    <limit lower="1" upper="-1"/>\n'), ' name="r" version="1.2"'),
        "fatal",
        "<limit",
        urdfdom6=True,
    ),
    Case(
        "v12_negative_velocity",
        robot(
            LINK_A_B + joint('    <limit lower="-1" upper="1" velocity="-1"/>\n'),
            ' name="r" version="1.2"',
        ),
        "fatal",
        "<limit",
        urdfdom6=True,
    ),
    Case(
        "v12_missing_lower",
        robot(LINK_A_B + joint('    <limit upper="1"/>\n'), ' name="r" version="1.2"'),
        "fatal",
        "<limit",
        urdfdom6=True,
    ),
    Case(
        "v11_rpy_and_quat",
        robot(
            LINK_A_B + joint('    <origin rpy="0 0 0" quat_xyzw="0 0 0 1"/>\n' + LIMIT),
            ' name="r" version="1.1"',
        ),
        "fatal",
        "<origin",
        urdfdom6=True,
    ),
    Case(
        "v11_quat_three_values",
        robot(
            LINK_A_B + joint('    <origin quat_xyzw="0 0 1"/>\n' + LIMIT), ' name="r" version="1.1"'
        ),
        "fatal",
        "<origin",
        urdfdom6=True,
    ),
)
