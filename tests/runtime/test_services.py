"""Typed request/response services: in-process and across processes over Zenoh (rmw_zenoh's
queryables), and the ``robomodel service`` command."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest

from robomodel.errors import RobomodelError
from robomodel.runtime import Context
from robomodel.runtime.msg.types.std_srvs import SetBool, SetBool_Request, SetBool_Response, Trigger
from robomodel.runtime.transport.base import ServiceCallError
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

SERVER = textwrap.dedent(
    """
    import sys
    from robomodel.runtime import Context
    from robomodel.runtime.msg.types.std_srvs import SetBool, SetBool_Response
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    def check(request):
        if not request.data:
            raise ValueError("data must be true")
        return SetBool_Response(True, "checked")
    ctx.create_node("calc").create_service(SetBool, "/calc/check", check)
    print("ready", flush=True)
    ctx.spin(duration_s=30)
    """
)


def _check(request: SetBool_Request) -> SetBool_Response:
    if not request.data:
        raise ValueError("data must be true")
    return SetBool_Response(True, "checked")


def test_a_zenoh_call_waits_for_a_server_that_comes_up_late(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A query that no queryable matched is asked again until the call's timeout, as rclpy's
    ``wait_for_service`` before ros2controlcli's calls: a ``control load`` typed right after
    ``control run`` started must not be told that nobody serves it."""
    from robomodel.runtime.transport._zenoh_services import ServiceClient

    asked_nobody = threading.Event()
    ask = ServiceClient._ask

    def spied(self: ServiceClient, *args: object) -> object:
        answer = ask(self, *args)  # type: ignore[arg-type]
        if answer == (None, True):
            asked_nobody.set()
        return answer

    monkeypatch.setattr(ServiceClient, "_ask", spied)
    domain = int(unique_domain())
    answers: list[object] = []
    with Context("zenoh", domain_id=domain) as caller, Context("zenoh", domain_id=domain) as late:
        request = SetBool_Request(True)
        call = threading.Thread(
            target=lambda: answers.append(
                caller.call_service("/late/check", SetBool, request, timeout_s=scaled(30))
            )
        )
        call.start()
        assert asked_nobody.wait(scaled(10)), "the first query should have found nobody"
        late.create_node("late").create_service(SetBool, "/late/check", _check)
        late.spin(duration_s=scaled(30), until=lambda: not call.is_alive())
        call.join()
    assert answers == [SetBool_Response(True, "checked")]


def test_a_zenoh_server_that_does_not_answer_in_time_is_said_so() -> None:
    """A server that holds the request past the call's timeout (here: nobody spins its
    executor) makes Zenoh end the query with an error reply of its own, "Timeout", from no
    replier: the caller is told the service did not answer, not "service '...': Timeout"."""
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as caller, Context("zenoh", domain_id=domain) as slow:
        slow.create_node("slow").create_service(SetBool, "/slow/check", _check)
        from robomodel.cli._bus import wait_for_peers

        wait_for_peers(caller)
        with pytest.raises(ServiceCallError) as raised:
            caller.call_service("/slow/check", SetBool, SetBool_Request(True), timeout_s=0.5)
        assert "did not answer within 0.5 s" in str(raised.value), raised.value


def test_inproc_service_call_and_errors() -> None:
    with Context("inproc") as ctx:
        node = ctx.create_node("calc")
        server = node.create_service(SetBool, "check", _check)
        assert server.name == "/check"
        reply = ctx.call_service("/check", SetBool, SetBool_Request(True))
        assert reply == SetBool_Response(True, "checked")
        with pytest.raises(ServiceCallError, match="data must be true"):
            ctx.call_service("/check", SetBool, SetBool_Request(False))
        with pytest.raises(ServiceCallError, match="has type std_srvs/srv/SetBool"):
            ctx.call_service("/check", Trigger)
        with pytest.raises(RobomodelError, match="already offered"):
            node.create_service(SetBool, "/check", _check)
        assert ctx.graph().services["/check"].types == {"std_srvs/srv/SetBool"}
        server.destroy()
        with pytest.raises(ServiceCallError, match="not found"):
            ctx.call_service("/check", SetBool)


def test_an_inproc_service_answers_a_call_with_another_class_of_its_type() -> None:
    """A client's service class of the same type as the server's, not the same class (a
    client library's face, as rclpy's rosidl-shaped SetBool), is served, not refused."""
    from robomodel.clientlibs.messages import service_class

    face = service_class("std_srvs/srv/SetBool", "rosidl")
    assert face is not SetBool
    with Context("inproc") as ctx:
        ctx.create_node("calc").create_service(SetBool, "check", _check)
        reply = ctx.call_service("/check", face, face.Request(data=True))
        assert (reply.success, reply.message) == (True, "checked")


def test_zenoh_service_across_processes(tmp_path: Path) -> None:
    script = tmp_path / "server.py"
    script.write_text(SERVER)
    domain = unique_domain()
    proc = subprocess.Popen(
        [sys.executable, str(script), domain], stdout=subprocess.PIPE, text=True
    )
    try:
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
        with Context("zenoh", domain_id=int(domain)) as ctx:
            from robomodel.cli._bus import wait_for_peers

            wait_for_peers(ctx)
            assert (
                ctx.call_service("/calc/check", SetBool, SetBool_Request(True)).message == "checked"
            )
            # a handler's exception comes back as an error answer, not a dead server
            with pytest.raises(ServiceCallError, match="data must be true"):
                ctx.call_service("/calc/check", SetBool, SetBool_Request(False))
            with pytest.raises(ServiceCallError, match=r"did not answer|has no server on the bus"):
                ctx.call_service("/calc/nothing", SetBool, timeout_s=scaled(0.5))
            with pytest.raises(ServiceCallError, match=r"did not answer|has no server on the bus"):
                ctx.call_service(
                    "/calc/check", Trigger, timeout_s=scaled(0.5)
                )  # another type: no match
            info = ctx.graph().services["/calc/check"]
            # the Trigger call above left a client of that type (30.8: callers are in the graph)
            assert [(s.type_name, s.node) for s in info.servers] == [
                ("std_srvs/srv/SetBool", "/calc")
            ]
            assert {c.type_name for c in info.clients} == {
                "std_srvs/srv/SetBool",
                "std_srvs/srv/Trigger",
            }
        cli = [*ROBOMODEL, "service"]
        listed = subprocess.run([*cli, "list", "-t", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert listed.returncode == 0 and "/calc/check [std_srvs/srv/SetBool]" in listed.stdout
        typed = subprocess.run([*cli, "type", "/calc/check", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert typed.stdout.strip() == "std_srvs/srv/SetBool", typed.stderr
        called = subprocess.run([*cli, "call", "calc/check", "std_srvs/srv/SetBool", "{data: true}", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert called.returncode == 0, called.stderr
        assert "message: checked" in called.stdout and "data: true" in called.stdout
        untyped = subprocess.run([*cli, "call", "/calc/check", "{data: true}", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert untyped.returncode == 0 and "success: true" in untyped.stdout
        failed = subprocess.run([*cli, "call", "/calc/check", "std_srvs/SetBool", "{data: false}", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert failed.returncode == 2 and "data must be true" in failed.stderr
        wrong = subprocess.run([*cli, "call", "/calc/check", "std_srvs/srv/SetBool", "{dat: 1}", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert wrong.returncode == 2 and "has no field 'dat'" in wrong.stderr
        missing = subprocess.run([*cli, "call", "/calc/sub", "--timeout", "0.5", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert missing.returncode == 2
        assert "not offered" in missing.stderr and "/calc/check" in missing.stderr
        # A mistyped service, with or without its type, gets a did-you-mean
        for typed_args in ([], ["std_srvs/srv/SetBool", "{data: true}"]):
            typo = subprocess.run([*cli, "call", "/calc/chek", *typed_args, "--timeout", "0.5", "--domain-id", domain], capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
            assert typo.returncode == 2 and "Traceback" not in typo.stderr
            assert "did you mean '/calc/check'?" in typo.stderr, typo.stderr
            assert len(typo.stderr.strip().splitlines()) == 1, typo.stderr
    finally:
        proc.kill()
        proc.wait()
