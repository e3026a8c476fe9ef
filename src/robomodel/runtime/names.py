"""ROS 2 names: validation, expansion (relative, absolute, ``~`` private) and remapping.

Rules from the ROS 2 design article "Topic and Service name mapping" and rcl's
``rcl_expand_topic_name``: names contain ``[A-Za-z0-9_/~{}]``, must not start with a digit,
must not contain ``//`` or end with ``/`` (except the root ``/``); a relative name is put in the
node's namespace, ``~`` is replaced by the node's fully qualified name.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from robomodel.errors import RobomodelError

__all__ = [
    "NameError_",
    "apply_remappings",
    "expand_topic_name",
    "fully_qualified_node_name",
    "parse_remapping",
    "validate_namespace",
    "validate_node_name",
]

_TOKEN = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_NODE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


class NameError_(RobomodelError):
    """A node, namespace or topic name that ROS 2 would reject."""


def validate_node_name(name: str) -> str:
    if not _NODE.match(name):
        raise NameError_(
            f"invalid node name '{name}': use letters, digits and underscores, not starting with a digit"
        )
    return name


def validate_namespace(namespace: str) -> str:
    """Return the namespace in canonical form (``""`` and ``"/"`` mean the root ``/``)."""
    ns = namespace or "/"
    if not ns.startswith("/"):
        ns = "/" + ns
    if ns != "/":
        ns = ns.rstrip("/")
        for token in ns.split("/")[1:]:
            if not _TOKEN.match(token):
                raise NameError_(f"invalid namespace '{namespace}': bad token '{token}'")
    return ns


def fully_qualified_node_name(name: str, namespace: str) -> str:
    ns = validate_namespace(namespace)
    return f"/{name}" if ns == "/" else f"{ns}/{name}"


def expand_topic_name(topic: str, node_name: str, namespace: str) -> str:
    """Expand ``topic`` for a node as rcl does (``chatter`` -> ``/ns/chatter``, ``~/x``...)."""
    if not topic:
        raise NameError_("topic name must not be empty")
    ns = validate_namespace(namespace)
    if topic.startswith("~"):
        fq = fully_qualified_node_name(node_name, ns)
        expanded = fq + topic[1:]
    elif topic.startswith("/"):
        expanded = topic
    else:
        expanded = f"/{topic}" if ns == "/" else f"{ns}/{topic}"
    if expanded != "/" and (expanded.endswith("/") or "//" in expanded):
        raise NameError_(f"invalid topic name '{topic}': no '//' and no trailing '/'")
    for token in expanded.split("/")[1:]:
        if not _TOKEN.match(token):
            raise NameError_(
                f"invalid topic name '{topic}': token '{token}' must be letters, digits and "
                "underscores, not starting with a digit"
            )
    return expanded


def parse_remapping(rule: str) -> tuple[str, str]:
    """Parse ``from:=to`` (``--ros-args -r`` syntax)."""
    source, sep, target = rule.partition(":=")
    if not sep or not source or not target:
        raise NameError_(f"invalid remapping '{rule}'; expected from:=to")
    return source, target


def apply_remappings(
    expanded: str, remappings: Mapping[str, str], node_name: str, namespace: str
) -> str:
    """Apply remapping rules (their names expanded in the node's context) to a topic."""
    for source, target in remappings.items():
        if expand_topic_name(source, node_name, namespace) == expanded:
            return expand_topic_name(target, node_name, namespace)
    return expanded
