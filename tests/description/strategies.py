"""Hypothesis strategies producing random valid URDF documents (random trees)."""

from __future__ import annotations

from hypothesis import strategies as st

_NAME = st.text(alphabet="abcdefghijklmnopqrstuvwxyzABC_0123456789", min_size=1, max_size=8)
_FLOAT = st.floats(min_value=-10, max_value=10, allow_nan=False, allow_infinity=False)
_POS = st.floats(min_value=0.01, max_value=5, allow_nan=False, allow_infinity=False)
_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


def _vec(values: list[float]) -> str:
    return " ".join(repr(v) for v in values)


@st.composite
def _geometry(draw: st.DrawFn) -> str:
    kind = draw(st.sampled_from(("box", "cylinder", "sphere", "mesh")))
    if kind == "box":
        return f'<box size="{_vec(draw(st.lists(_POS, min_size=3, max_size=3)))}"/>'
    if kind == "cylinder":
        return f'<cylinder radius="{draw(_POS)!r}" length="{draw(_POS)!r}"/>'
    if kind == "sphere":
        return f'<sphere radius="{draw(_POS)!r}"/>'
    return f'<mesh filename="package://pkg/meshes/{draw(_NAME)}.stl" scale="1 1 1"/>'


@st.composite
def _link(draw: st.DrawFn, name: str) -> str:
    parts = []
    if draw(st.booleans()):
        a, b, c = sorted(draw(st.lists(_POS, min_size=3, max_size=3)))
        parts.append(
            f'<inertial><origin xyz="{_vec(draw(st.lists(_FLOAT, min_size=3, max_size=3)))}"/>'
            f'<mass value="{draw(_POS)!r}"/><inertia ixx="{b!r}" ixy="0" ixz="0" iyy="{c!r}" '
            f'iyz="0" izz="{(a + b)!r}"/></inertial>'
        )
    for _ in range(draw(st.integers(0, 2))):
        color = _vec(draw(st.lists(st.floats(0, 1), min_size=4, max_size=4)))
        parts.append(
            f'<visual><origin rpy="{_vec(draw(st.lists(_FLOAT, min_size=3, max_size=3)))}"/>'
            f"<geometry>{draw(_geometry())}</geometry>"
            f'<material name="{draw(_NAME)}"><color rgba="{color}"/></material></visual>'
        )
    for _ in range(draw(st.integers(0, 2))):
        parts.append(f"<collision><geometry>{draw(_geometry())}</geometry></collision>")
    return f'<link name="{name}">{"".join(parts)}</link>'


@st.composite
def robots(draw: st.DrawFn) -> str:
    """A random valid tree: unique names, each link after the first has one parent."""
    count = draw(st.integers(1, 12))
    link_names = draw(st.lists(_NAME, min_size=count, max_size=count, unique=True))
    joint_names = draw(st.lists(_NAME, min_size=count - 1, max_size=count - 1, unique=True))
    body = [draw(_link(name)) for name in link_names]
    for index in range(1, count):
        parent = link_names[draw(st.integers(0, index - 1))]
        jtype = draw(st.sampled_from(_TYPES))
        extra = ""
        if jtype in ("revolute", "prismatic") or draw(st.booleans()):
            lo, hi = sorted(draw(st.lists(_FLOAT, min_size=2, max_size=2)))
            extra += f'<limit lower="{lo!r}" upper="{hi!r}" effort="{draw(_POS)!r}" velocity="{draw(_POS)!r}"/>'
        if draw(st.booleans()):
            extra += f'<dynamics damping="{draw(_POS)!r}"/>'
        xyz = _vec(draw(st.lists(_FLOAT, min_size=3, max_size=3)))
        rpy = _vec(draw(st.lists(_FLOAT, min_size=3, max_size=3)))
        body.append(
            f'<joint name="{joint_names[index - 1]}" type="{jtype}"><origin xyz="{xyz}" '
            f'rpy="{rpy}"/><parent link="{parent}"/><child link="{link_names[index]}"/>'
            f'<axis xyz="0 0 1"/>{extra}</joint>'
        )
    if draw(st.booleans()):
        body.reverse()  # file order must not matter
    return (
        f'<?xml version="1.0"?>\n<robot name="{draw(_NAME)}">\n' + "\n".join(body) + "\n</robot>\n"
    )
