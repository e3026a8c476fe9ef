"""One-off service callers are clients of the ROS 2 graph.

rmw_zenoh's ``ClientData::make`` (``rmw_zenoh_cpp/src/detail/rmw_client_data.cpp``, Jazzy
0.2.10) declares an ``SC`` liveliness token for each client (``liveliness_utils.cpp``,
``Entity::make``) and every request carries the GID derived from it: XXH3-128 of the token's
key, low 64 bits first (``Entity::Entity``, ``simplified_XXH3_128bits``). Here the GID is
recomputed with the xxhash package from the token a ``robomodel service call`` process
declares, and compared with the GID in the attachment of the request it sends.
"""

from __future__ import annotations

import queue
import subprocess
from typing import Any

import xxhash

from robomodel.runtime import Context
from robomodel.runtime.msg.types.std_srvs import SetBool, SetBool_Request, SetBool_Response
from robomodel.runtime.transport.rmw_zenoh import parse_attachment
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled, wait_until


def _tokens(session: Any, domain: str) -> list[str]:
    return [str(r.ok.key_expr) for r in session.liveliness().get(f"@ros2_lv/{domain}/**") if r.ok]


def test_a_command_line_caller_has_an_sc_token_and_its_gid() -> None:
    domain = unique_domain()
    requests: queue.Queue[bytes] = queue.Queue()

    def serve(request: SetBool_Request) -> SetBool_Response:
        return SetBool_Response(True, "seen")

    with Context("zenoh", domain_id=int(domain)) as ctx:
        ctx.create_node("probe").create_service(SetBool, "/probe/check", serve)
        transport: Any = ctx.transport
        session = transport.session
        # a second complete queryable on the key sees each request's attachment
        spy = session.declare_queryable(
            transport.data_key("/probe/check", SetBool),
            lambda q: requests.put(q.attachment.to_bytes() if q.attachment else b""),
            complete=True,
        )
        caller = subprocess.Popen(
            [*ROBOMODEL, "service", "call", "/probe/check", "std_srvs/srv/SetBool",
             "{data: true}", "--timeout", f"{scaled(60):.1f}", "--domain-id", domain],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        )  # fmt: skip
        try:
            # The server has not spun yet, so the caller waits for its answer, token declared.
            client_node = f"robomodel_client_{caller.pid}"
            [token] = wait_until(
                lambda: [k for k in _tokens(session, domain) if "/SC/" in k],
                30,
                what="SC token of the caller",
            )
            parts = token.split("/")
            assert parts[5:9] == ["SC", "%", "%", client_node]
            assert parts[9:11] == ["%probe%check", "std_srvs::srv::dds_::SetBool_"]
            assert parts[12] == "::,10:,:,:,,"  # rmw_qos_profile_services_default
            zid = parts[2]  # the node's token is the same session's
            node_tokens = wait_until(  # a liveliness query may answer before every token is in
                lambda: [k for k in _tokens(session, domain) if f"/NN/%/%/{client_node}" in k],
                30,
                what="the caller's node token",
            )
            assert [k.split("/")[2] for k in node_tokens] == [zid]
            attachment = parse_attachment(requests.get(timeout=scaled(30)))
            assert attachment is not None and attachment.sequence_number == 1
            digest = xxhash.xxh3_128_intdigest(token.encode())
            assert attachment.gid == digest.to_bytes(16, "little")
            clients = ctx.graph(timeout_s=scaled(10.0)).services["/probe/check"].clients
            assert [c.node for c in clients] == [f"/{client_node}"]
            ctx.spin(duration_s=scaled(60), until=lambda: caller.poll() is not None)
            out, err = caller.communicate(timeout=scaled(30))
            assert caller.returncode == 0, err
            assert "message: seen" in out
            wait_until(
                lambda: not [k for k in _tokens(session, domain) if client_node in k],
                30,
                what="the caller's tokens to go",
            )
        finally:
            caller.kill()
            caller.wait()
            spy.undeclare()
