"""Request/response services: in-process and across processes over Zenoh."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from robomodel.errors import RobomodelError
from robomodel.runtime import Context
from tests.conftest import ROBOMODEL, unique_domain

SERVER = textwrap.dedent(
    """
    import sys
    from robomodel.runtime import Context
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    def add(request):
        if "a" not in request:
            raise ValueError("missing 'a'")
        return {"sum": request["a"] + request["b"]}
    ctx.create_service("/calc/add", add)
    print("ready", flush=True)
    ctx.spin(duration_s=30)
    """
)


def test_inproc_service_call_and_errors() -> None:
    with Context("inproc") as ctx:
        unregister = ctx.create_service("/calc/add", lambda r: {"sum": r["a"] + r["b"]})
        assert ctx.call_service("/calc/add", {"a": 1, "b": 2}) == {"sum": 3}
        with pytest.raises(RobomodelError, match="already offered"):
            ctx.create_service("/calc/add", lambda r: r)
        assert ctx.graph().services == {"/calc/add"}
        unregister()
        with pytest.raises(RobomodelError, match="not found"):
            ctx.call_service("/calc/add", {})


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
            assert ctx.call_service("/calc/add", {"a": 2, "b": 40}) == {"sum": 42}
            # a handler's exception comes back as an error answer, not a dead server
            assert "missing 'a'" in ctx.call_service("/calc/add", {"b": 1})["error"]
            with pytest.raises(RobomodelError, match="did not answer"):
                ctx.call_service("/calc/nothing", {}, timeout_s=0.5)
            assert "/calc/add" in ctx.graph().services
        cli = [*ROBOMODEL, "service"]
        listed = subprocess.run([*cli, "list", "--domain-id", domain], capture_output=True, text=True, timeout=20)  # fmt: skip
        assert listed.returncode == 0 and "/calc/add" in listed.stdout.split()
        called = subprocess.run([*cli, "call", "calc/add", "{a: 2, b: 3.5}", "--domain-id", domain], capture_output=True, text=True, timeout=20)  # fmt: skip
        assert called.returncode == 0, called.stderr
        assert "sum: 5.5" in called.stdout and '{"a": 2, "b": 3.5}' in called.stdout
        failed = subprocess.run([*cli, "call", "/calc/add", "{b: 1}", "--domain-id", domain], capture_output=True, text=True, timeout=20)  # fmt: skip
        assert failed.returncode == 2 and "missing 'a'" in failed.stdout
        missing = subprocess.run([*cli, "call", "/calc/sub", "--timeout", "0.5", "--domain-id", domain], capture_output=True, text=True, timeout=20)  # fmt: skip
        assert missing.returncode == 2
        assert "did not answer" in missing.stderr and "/calc/add" in missing.stderr
    finally:
        proc.kill()
        proc.wait()


def test_service_request_yaml_is_checked() -> None:
    from robomodel.cli.service import parse_request

    assert parse_request("") == {} and parse_request("{}") == {}
    assert parse_request("{steps: 10}") == {"steps": 10}
    with pytest.raises(RobomodelError, match="mapping"):
        parse_request("[1, 2]")
    with pytest.raises(RobomodelError, match="not valid YAML at line 1"):
        parse_request("{steps: [}")
