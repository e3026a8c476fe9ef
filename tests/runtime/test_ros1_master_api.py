"""The ROS 1 master's XML-RPC methods called in-process (no sockets), with the notifications
they queue recorded: rosmaster's answers, status messages and publisherUpdate/shutdown calls."""

from __future__ import annotations

import os
from typing import Any

import pytest

from robomodel.runtime.transport.ros1.master import MasterApi

URI = "http://127.0.0.1:11311/"
EAR, TALKER, TALKER_AGAIN = (f"http://127.0.0.1:{port}/" for port in (4001, 4002, 4005))


@pytest.fixture
def api() -> tuple[MasterApi, list[tuple[str, str, tuple[Any, ...]]]]:
    sent: list[tuple[str, str, tuple[Any, ...]]] = []
    return MasterApi(URI, lambda *call: sent.append(call)), sent


def test_the_methods_served_are_rosmaster_s(api: tuple[MasterApi, list[Any]]) -> None:
    master, _ = api
    served = master.methods()
    assert {
        "deleteParam", "getParam", "getParamNames", "getPid", "getPublishedTopics",
        "getSystemState", "getTopicTypes", "getUri", "hasParam", "lookupNode", "lookupService",
        "registerPublisher", "registerService", "registerSubscriber", "searchParam", "setParam",
        "shutdown", "subscribeParam", "unregisterPublisher", "unregisterService",
        "unregisterSubscriber", "unsubscribeParam",
    } <= set(served)  # fmt: skip
    # neither its own attributes nor private helpers are served
    assert not set(served) & {"methods", "uri", "params", "registry", "topic_types"}
    assert not any(name.startswith("_") for name in served)
    assert master.getUri("/x") == [1, "", URI]
    assert master.getPid("/x") == [1, "", os.getpid()]
    assert master.shutdown("/x", "bye") == [
        0, "robomodel's master ends with the process that hosts it", 0
    ]  # fmt: skip


def test_publishers_subscribers_and_their_notifications(api: tuple[MasterApi, list[Any]]) -> None:
    master, sent = api
    assert master.registerSubscriber("/ear", "/chatter", "std_msgs/String", EAR) == [
        1, "Subscribed to [/chatter]", []
    ]  # fmt: skip
    assert master.registerPublisher("/talker", "chatter", "std_msgs/String", TALKER) == [
        1, "Registered [/talker] as publisher of [/chatter]", [EAR]
    ]  # fmt: skip
    assert sent == [(EAR, "publisherUpdate", ("/master", "/chatter", [TALKER]))]
    # a node registering again under its name from another URI replaces the old one, which
    # is told to shut down (rosmaster's shutdown_node_task)
    master.registerPublisher("/talker", "/chatter", "std_msgs/String", TALKER_AGAIN)
    assert sent[1:] == [
        (TALKER, "shutdown", ("/master", "new node registered with same name")),
        (EAR, "publisherUpdate", ("/master", "/chatter", [TALKER_AGAIN])),
    ]
    assert master.lookupNode("/x", "/talker") == [1, "node api", TALKER_AGAIN]
    assert master.lookupNode("/x", "/nobody") == [-1, "unknown node [/nobody]", ""]
    assert master.getSystemState("/x") == [
        1, "current system state", [[["/chatter", ["/talker"]]], [["/chatter", ["/ear"]]], []]
    ]  # fmt: skip
    del sent[:]
    assert master.unregisterPublisher("/talker", "/chatter", TALKER_AGAIN) == [
        1, "Unregistered [/talker] as provider of [/chatter]", 1
    ]  # fmt: skip
    assert sent == [(EAR, "publisherUpdate", ("/master", "/chatter", []))]
    assert master.unregisterPublisher("/talker", "/chatter", TALKER_AGAIN) == [
        1, "[/talker] is not a known provider of [/chatter]", 0
    ]  # fmt: skip
    assert master.unregisterSubscriber("/ear", "/chatter", EAR)[2] == 1
    assert master.unregisterSubscriber("/ear", "/chatter", EAR)[2] == 0


def test_topic_types_are_kept_as_rosmaster_keeps_them(api: tuple[MasterApi, list[Any]]) -> None:
    master, _ = api
    master.registerSubscriber("/ear", "/a", "std_msgs/String", EAR)
    master.registerSubscriber("/ear", "/b", "*", EAR)
    master.registerPublisher("/talker", "/a", "*", TALKER)  # "*" keeps the type known
    master.registerSubscriber("/ear2", "/a", "std_msgs/Int32", "http://127.0.0.1:4003/")
    master.registerPublisher("/talker", "/c", "std_msgs/Bool", TALKER)
    master.registerPublisher("/talker", "/c", "std_msgs/Int8", TALKER)  # a publisher's type wins
    assert master.getTopicTypes("/x") == [
        1, "current topic types", [["/a", "std_msgs/String"], ["/c", "std_msgs/Int8"]]
    ]  # fmt: skip
    assert master.getPublishedTopics("/x", "") == [
        1, "current topics", [["/a", "std_msgs/String"], ["/c", "std_msgs/Int8"]]
    ]  # fmt: skip
    master.registerPublisher("/talker", "/ns/d", "std_msgs/Bool", TALKER)
    assert master.getPublishedTopics("/x", "/ns")[2] == [["/ns/d", "std_msgs/Bool"]]
    assert master.getPublishedTopics("/x", "/n")[2] == []  # a namespace, not a text prefix


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (("registerPublisher", "/t", "/", "std_msgs/String", TALKER),
         "ERROR: topic cannot be the global namespace"),
        (("registerPublisher", "/t", "/x", "a/b/c", TALKER),
         "ERROR: topic_type must be '*' or a package/Type name"),
        (("registerPublisher", "/t", "/x", 5, TALKER),
         "ERROR: topic_type must be '*' or a package/Type name"),
        (("registerPublisher", "bad name!", "/x", "a/b", TALKER),
         "ERROR: caller_id 'bad name!' is not a ROS name (no ':', whitespace or control characters)"),
        (("registerService", "/t", "/", "rosrpc://127.0.0.1:5000", TALKER),
         "ERROR: service cannot be the global namespace"),
        (("getParam", "/t", 5), "ERROR: a parameter key must be a string of at most "),
    ],
)  # fmt: skip
def test_refusals_are_rosmaster_s_error_triples(
    api: tuple[MasterApi, list[Any]], call: tuple[Any, ...], message: str
) -> None:
    master, sent = api
    code, status, value = getattr(master, call[0])(*call[1:])
    assert (code, value) == (-1, 0) and status.startswith(message)
    assert sent == []


def test_the_empty_caller_id_is_taken_and_the_root_is_a_node_name(
    api: tuple[MasterApi, list[Any]],
) -> None:
    master, _ = api
    assert master.registerPublisher("", "/x", "std_msgs/String", TALKER)[0] == 1
    assert master.lookupNode("/x", "/") == [-1, "unknown node [/]", ""]
