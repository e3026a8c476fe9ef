"""The ROS 1 master's XML-RPC methods called in-process, with the notifications they queue
recorded: rosmaster's answers, status messages and publisherUpdate/shutdown calls; the master's
notification queue and ``master_answers`` over loopback sockets."""

from __future__ import annotations

import logging
import os
import socket
import threading
import xmlrpc.client
from typing import Any

import pytest

from robomodel.runtime.transport.ros1 import master as master_module
from robomodel.runtime.transport.ros1 import xmlrpc_io
from robomodel.runtime.transport.ros1.master import Master, MasterApi, master_answers
from robomodel.runtime.transport.ros1.names import MAX_NAME_BYTES
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, XmlRpcServer
from tests.timing import scaled, wait_until

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


@pytest.fixture
def lines(caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch) -> Any:
    """The master's log lines, none of them held back by an earlier test's throttled line."""
    monkeypatch.setattr(xmlrpc_io, "_throttled", {})
    caplog.set_level(logging.DEBUG, logger="robomodel.ros1")
    return lambda: [r.getMessage() for r in caplog.records if r.name == "robomodel.ros1"]


def test_a_refused_shutdown_and_a_replaced_node_are_one_line_each(
    api: tuple[MasterApi, list[Any]], lines: Any
) -> None:
    master, _ = api
    master.shutdown("/rosnode", "user request")
    master.shutdown("/rosnode")  # held back: one line per kind per 5 s
    xmlrpc_io._throttled.clear()
    master.shutdown("/rosnode")
    master.registerPublisher("/talker", "/chatter", "std_msgs/String", TALKER)
    master.registerPublisher("/talker", "/chatter", "std_msgs/String", TALKER_AGAIN)
    assert lines() == [
        "master: /rosnode asked it to shut down (user request); refused",
        "master: /rosnode asked it to shut down (); refused",
        "master: new node registered with the name /talker; shutting down the old",
    ]


def test_names_are_resolved_for_the_caller_and_checked_on_both_sides(
    api: tuple[MasterApi, list[Any]],
) -> None:
    master, _ = api
    assert master.registerPublisher("/ns/talker", "chatter", "std_msgs/String", TALKER)[1] == (
        "Registered [/ns/talker] as publisher of [/ns/chatter]"
    )
    assert master.lookupNode("/ns/x", "talker") == [1, "node api", TALKER]
    assert master.registerSubscriber("/ns/ear", "chatter", "std_msgs/String", EAR)[2] == [TALKER]
    assert master.registerPublisher("/t", "", "std_msgs/String", TALKER) == [
        -1, "ERROR: topic must be a non-empty string", 0
    ]  # fmt: skip
    # a private name of a long caller id resolves past the bound
    caller = "/" + "n" * 1020
    assert master.registerPublisher(caller, "~abcd", "std_msgs/String", TALKER) == [
        -1, "ERROR: topic is 1026 characters; at most 1024", 0
    ]  # fmt: skip
    assert master.registerPublisher("/t", "/x", "std_msgs/String", "garbage") == [
        -1, "ERROR: caller_api 'garbage' is not an http:// or rosrpc:// URI", 0
    ]  # fmt: skip


@pytest.mark.parametrize("topic_type", ["std_msgs/", "/String", "std_msgs/Str ing"])
def test_a_topic_type_has_a_package_and_a_type_name(
    api: tuple[MasterApi, list[Any]], topic_type: str
) -> None:
    master, _ = api
    code, status, _ = master.registerSubscriber("/ear", "/x", topic_type, EAR)
    assert code == -1 and status.startswith("ERROR: topic_type ")
    assert master.getTopicTypes("/x")[2] == []
    assert master.registerSubscriber("/ear", "/x", "std_msgs/String", EAR)[0] == 1


def test_parameter_keys_are_bounded_after_resolution(api: tuple[MasterApi, list[Any]]) -> None:
    master, _ = api
    longest = "/" + "k" * (MAX_NAME_BYTES - 1)
    assert master.setParam("/x", longest, 1) == [1, f"parameter {longest} set", 0]
    assert master.hasParam("/x", longest) == [1, longest, True]
    assert master.getParamNames("/x") == [1, "Parameter names", [longest]]
    caller = "/" + "c" * 1000
    status = master.getParam(caller, "~" + "k" * 30)[1]
    assert status == (
        f"ERROR: parameter key {(caller + '/' + 'k' * 30)[:80]!r}... is longer than 1024"
    )
    assert master.getParam("/x", "k" * (MAX_NAME_BYTES + 1))[1] == (
        "ERROR: a parameter key must be a string of at most 1024 characters"
    )


def test_setting_the_root_tells_every_parameter_subscriber(
    api: tuple[MasterApi, list[Any]],
) -> None:
    master, sent = api
    master.subscribeParam("/ear", EAR, "/a")
    master.subscribeParam("/all", TALKER, "/")
    master.setParam("/x", "/", {"a": 1, "b": {"c": 2}})
    assert sorted(sent) == [
        (EAR, "paramUpdate", ("/master", "/a/", 1)),
        (TALKER, "paramUpdate", ("/master", "/", {"a": 1, "b": {"c": 2}})),
    ]


def test_a_parameter_update_goes_to_the_subscribers_of_that_key_only(
    api: tuple[MasterApi, list[Any]],
) -> None:
    master, sent = api
    master.subscribeParam("/ear", EAR, "/a")
    master.subscribeParam("/talker", TALKER, "/aX")
    master.setParam("/x", "/aX", 2)
    master.setParam("/x", "/a", 1)
    assert sent == [
        (TALKER, "paramUpdate", ("/master", "/aX/", 2)),
        (EAR, "paramUpdate", ("/master", "/a/", 1)),
    ]


def test_stale_topic_types_are_dropped_past_the_bound_and_live_ones_kept(
    api: tuple[MasterApi, list[Any]], monkeypatch: pytest.MonkeyPatch
) -> None:
    master, _ = api
    monkeypatch.setattr(master_module, "MAX_REGISTRATIONS", 3)
    master.registerPublisher("/talker", "/gone", "std_msgs/Bool", TALKER)
    master.unregisterPublisher("/talker", "/gone", TALKER)
    master.registerPublisher("/talker", "/a", "std_msgs/Int8", TALKER)
    master.registerPublisher("/talker", "/b", "std_msgs/Int16", TALKER)
    types = [["/a", "std_msgs/Int8"], ["/b", "std_msgs/Int16"], ["/gone", "std_msgs/Bool"]]
    assert master.getTopicTypes("/x")[2] == types  # kept after its last registration
    master.registerPublisher("/talker", "/b", "std_msgs/Int32", TALKER)  # not a new topic
    assert master.getTopicTypes("/x")[2] == [types[0], ["/b", "std_msgs/Int32"], types[2]]
    master.registerPublisher("/talker", "/c", "std_msgs/Int64", TALKER)
    assert master.getTopicTypes("/x")[2] == [
        ["/a", "std_msgs/Int8"], ["/b", "std_msgs/Int32"], ["/c", "std_msgs/Int64"]
    ]  # fmt: skip


def test_master_answers_is_true_for_a_master_only(monkeypatch: pytest.MonkeyPatch) -> None:
    with socket.socket() as bound:
        bound.bind(("127.0.0.1", 0))
        nobody = f"http://127.0.0.1:{bound.getsockname()[1]}/"  # bound, not listening
        assert not master_answers(nobody)
        bound.listen()
        silent = nobody  # accepts, never answers
        assert not master_answers(silent, timeout_s=0.2)
    m = Master(f"http://127.0.0.1:{_free_port()}/", "127.0.0.1")
    try:
        assert master_answers(m.uri)
    finally:
        m.close()
    other = XmlRpcServer("127.0.0.1", 0, {"getUri": lambda caller: [1, "", ""]})
    try:  # an XML-RPC server without getPid is not a master
        assert not master_answers(f"http://127.0.0.1:{other.port}/")
    finally:
        other.close()


def test_a_full_notification_queue_drops_with_a_line(
    monkeypatch: pytest.MonkeyPatch, lines: Any
) -> None:
    taken, release, sent = threading.Event(), threading.Event(), []

    def stuck(uri: str, method: str, *args: Any, timeout_s: float) -> None:
        taken.set()
        release.wait()
        sent.append((uri, method, args))

    monkeypatch.setattr(master_module, "call_raw", stuck)
    monkeypatch.setattr(master_module, "MAX_PENDING_NOTIFICATIONS", 1)
    m = Master(f"http://127.0.0.1:{_free_port()}/", "127.0.0.1")
    try:
        m.api.registerSubscriber("/ear", "/chatter", "std_msgs/String", EAR)
        for port in (5001, 5002, 5003):  # the worker holds the first; one waits; one dropped
            m.api.registerPublisher(f"/t{port}", "/chatter", "std_msgs/String", f"http://h:{port}/")
            if port == 5001:
                assert taken.wait(scaled(5))
        release.set()
    finally:
        m.close()
    assert len(sent) == 2
    assert "master: notification queue full; dropping publisherUpdate to " + EAR in lines()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_a_failing_notification_is_a_line_and_the_next_ones_are_sent(
    monkeypatch: pytest.MonkeyPatch, lines: Any
) -> None:
    """Nothing a peer does to one notification ends the worker that sends everyone's."""
    failures = [RuntimeError("peer sent nonsense"), Ros1WireError("connection refused")]
    sent: list[tuple[str, str]] = []

    def flaky(uri: str, method: str, *args: Any, timeout_s: float) -> None:
        sent.append((uri, method))
        if failures:
            raise failures.pop(0)

    monkeypatch.setattr(master_module, "call_raw", flaky)
    m = Master(f"http://127.0.0.1:{_free_port()}/", "127.0.0.1")
    try:
        assert xmlrpc.client.ServerProxy(m.uri).getUri("/x") == [1, "", m.uri]
        m.api.registerSubscriber("/ear", "/chatter", "std_msgs/String", EAR)
        for talker in (TALKER, TALKER_AGAIN, "http://127.0.0.1:4006/"):
            m.api.registerPublisher(f"/t{talker[-5:-1]}", "/chatter", "std_msgs/String", talker)
        wait_until(lambda: len(sent) == 3, scaled(5), what="three notifications sent")
    finally:
        m.close()
    assert sent == [(EAR, "publisherUpdate")] * 3
    assert [line for line in lines() if line.startswith("master: ")] == [
        f"master: publisherUpdate to {EAR} failed: RuntimeError: peer sent nonsense",
        f"master: publisherUpdate to {EAR} failed: connection refused",
    ]


def test_a_subscriber_that_never_answers_holds_the_others_up_2_s_at_most() -> None:
    updates: list[Any] = []
    good = XmlRpcServer(
        "127.0.0.1", 0, {"publisherUpdate": lambda *a: updates.append(a) or [1, "", 0]}
    )
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen()
        m = Master(f"http://127.0.0.1:{_free_port()}/", "127.0.0.1")
        try:
            m.api.registerSubscriber("/mute", "/chatter", "std_msgs/String",
                                     f"http://127.0.0.1:{silent.getsockname()[1]}/")  # fmt: skip
            m.api.registerSubscriber("/ear", "/chatter", "std_msgs/String",
                                     f"http://127.0.0.1:{good.port}/")  # fmt: skip
            m.api.registerPublisher("/talker", "/chatter", "std_msgs/String", TALKER)
            wait_until(lambda: updates, scaled(10), what="publisherUpdate past the silent one")
        finally:
            m.close()
            good.close()
    assert updates == [("/master", "/chatter", [TALKER])]
