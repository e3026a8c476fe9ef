"""The one parser of interface definitions (runtime.msg.definition): ``---`` splitting of
services and actions, the parts' names, the field-type mapping of both ROS dialects and the
``.msg`` text written back from a class."""

from __future__ import annotations

import pytest

from robomodel.runtime.msg.definition import (
    field_spec,
    message_text,
    parse_interface,
    parse_message,
    split_parts,
)
from robomodel.runtime.msg.schema import Array, Message, MessageTypeError, Seq, get_message_type

pytest.importorskip("rosbags.typesys")


def _no_lookup(name: str) -> type[Message]:
    raise AssertionError(f"no nested type expected, got {name}")


def test_split_parts_at_separator_lines_only() -> None:
    text = "int32 a # not --- a separator\n---\nstring b\n---  \nbool c\n"
    assert split_parts(text, "action", where="x") == (
        "int32 a # not --- a separator\n",
        "string b\n",
        "bool c\n",
    )
    assert split_parts("---\n", "srv", where="x") == ("\n", "\n")
    with pytest.raises(MessageTypeError, match=r"^f\.srv: a service needs .* \(found 2\)$"):
        split_parts("---\n---\n", "srv", where="f.srv")
    with pytest.raises(MessageTypeError, match=r"^f\.action: an action needs .* \(found 1\)$"):
        split_parts("int8 a\n---\n", "action", where="f.action")


def test_parse_interface_names_the_parts_as_rosidl() -> None:
    found = parse_interface("Header header\n---\nbool ok\n", "my_pkg/srv/Do", where="Do.srv")
    assert list(found) == ["my_pkg/srv/Do_Request", "my_pkg/srv/Do_Response"]
    assert found["my_pkg/srv/Do_Request"][1][0][1][1] == "std_msgs/msg/Header"
    goal = parse_interface("Pose p\n---\n---\nfloat32 f\n", "my_pkg/action/Go", where="Go.action")
    assert list(goal) == [
        "my_pkg/action/Go_Goal",
        "my_pkg/action/Go_Result",
        "my_pkg/action/Go_Feedback",
    ]
    # a relative name resolves in the file's own package
    assert goal["my_pkg/action/Go_Goal"][1][0][1][1] == "my_pkg/msg/Pose"
    with pytest.raises(MessageTypeError, match=r"^bad\.msg: not a valid message definition") as e:
        parse_message("int32[x a\n", "my_pkg/msg/Bad", where="bad.msg")
    assert "\n" not in str(e.value)


def test_byte_and_char_in_both_dialects() -> None:
    fields = dict(
        parse_message("byte b\nchar c\nbyte[] bs\nchar[2] cs\n", "p/msg/T", where="t")["p/msg/T"][1]
    )

    def spec(name: str, *, ros1: bool) -> object:
        return field_spec(fields[name], _no_lookup, where=name, ros1=ros1)

    # ROS 2: byte is IDL's octet (unsigned); ROS 1: genmsg's deprecated alias of int8
    assert spec("b", ros1=False) == "byte" and spec("b", ros1=True) == "int8"
    assert spec("bs", ros1=False) == Seq("byte") and spec("bs", ros1=True) == Seq("int8")
    # char is uint8 in both, kept as char (its RIHS01 type id and .msg text differ)
    assert spec("c", ros1=False) == spec("c", ros1=True) == "char"
    assert spec("cs", ros1=True) == Array("char", 2)
    octet = (1, ("octet", 0))
    assert field_spec(octet, _no_lookup, where="o", ros1=True) == "byte"


def test_message_text_round_trips_through_the_parser() -> None:
    cls = get_message_type("sensor_msgs/msg/BatteryState")  # constants, arrays, nested Header
    text = message_text(cls)
    assert text.startswith("uint8 POWER_SUPPLY_STATUS_UNKNOWN=0\n")
    assert "std_msgs/Header header\n" in text and "float32[] cell_voltage\n" in text
    parsed = parse_message(text, "sensor_msgs/msg/BatteryState", where="text")
    assert parsed["sensor_msgs/msg/BatteryState"][0] == list(cls.__constants__)
    names = [name for name, _ in parsed["sensor_msgs/msg/BatteryState"][1]]
    assert names == list(cls.field_names())


def test_a_definition_rosbags_cannot_parse_is_one_line_with_its_reason() -> None:
    from robomodel.runtime.msg.definition import parse_interface, parse_message

    for parse in (parse_message, parse_interface):
        with pytest.raises(MessageTypeError) as refused:
            parse("int32 !bad\n", "pkg/msg/A", where="a.msg")
        message = str(refused.value)
        assert message.startswith("a.msg: not a valid message definition: Could not parse: ")
        assert "int32 !bad" in message and "\n" not in message


def test_the_field_bound_counts_each_type_s_section_alone() -> None:
    """A ``message_definition`` with ``MSG:`` sections: each type's lines are counted apart,
    and the refusal names the section past the bound."""
    from robomodel.runtime.msg.definition import LIMITS, parse_message

    main = "pkg/Sub a\n" + "".join(f"int8 m{k}\n" for k in range(LIMITS.max_fields - 1))
    sub = "".join(f"int8 f{k}\n" for k in range(LIMITS.max_fields))
    text = f"{main}{'=' * 80}\nMSG: pkg/Sub\n{sub}"
    assert "pkg/msg/Sub" in parse_message(text, "pkg/msg/Main", where="bag")
    with pytest.raises(MessageTypeError) as refused:
        parse_message(text + "int8 one_more\n", "pkg/msg/Main", where="bag")
    assert str(refused.value) == (
        f"bag: pkg/Sub has more than {LIMITS.max_fields} fields and constants "
        "(robomodel's bound, docs/reference/limits.md)"
    )


def test_types_the_definitions_do_not_define_count_as_one_level() -> None:
    from robomodel.runtime.msg.definition import LIMITS, check_limits

    base, name = 1, 2
    found = {
        f"pkg/msg/T{k}": ([], [("next", (name, f"pkg/msg/T{k + 1}")), ("x", (base, ("int8", 0)))])
        for k in range(LIMITS.max_depth - 2)
    }
    # the last one holds a type from elsewhere (a Header): one more level, at the bound
    found[f"pkg/msg/T{LIMITS.max_depth - 2}"] = (
        [], [("header", (name, "std_msgs/msg/Header"))]
    )  # fmt: skip
    check_limits(found)
    found["pkg/msg/Top"] = ([], [("t", (name, "pkg/msg/T0"))])
    with pytest.raises(MessageTypeError, match=f"nested more than {LIMITS.max_depth} deep"):
        check_limits(found)
