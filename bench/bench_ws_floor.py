"""The floor under bench/bench_bridges.py: what delivering the same messages over one WebSocket
costs on this machine, with no bridge, no Zenoh and no ROS in the way.

A bare sender (a TCP socket, the HTTP upgrade and Foxglove's ``serverInfo``, ``advertise`` and
binary ``messageData`` frames written by hand, ``TCP_NODELAY`` and a 4 MiB send buffer as
robomodel's foxglove_bridge sets) serves the bench's two topics at their rates to the same node
client as bench_bridges.py (``bench/bench_bridges_client.js``, ``@foxglove/ws-protocol``'s
``FoxgloveClient``): the CDR of the same 32-joint /joint_states at 1 kHz and the same 640x480
rgb8 image (0.92 MB) at 30 Hz. Each payload carries ``time.monotonic_ns()`` taken just before its
frame is written (``sendmsg`` of the frame's header and the payload, no copy), where the
bridge's carries the publisher's stamp, so what is measured is the socket, the kernel's
loopback and the client alone. The bridge's hop (its client's p50 minus robomodel's own
subscriber's, bench_bridges.py) cannot be shorter than this.

Run: ``.venv/bin/python bench/bench_ws_floor.py [--seconds 5]`` (node and the client's modules
from ``tools/system-deps test``).
"""

from __future__ import annotations

import argparse
import base64
import hashlib
import json
import os
import socket
import struct
import subprocess
import threading
import time
from typing import Any

from bench_bridges import (
    _STAMP,
    NODE_MODULES,
    ROOT,
    TOPICS,
    _node_client,
    _percentile,
    messages,
    paced,
)

_WS_GUID = b"258EAFA5-E914-47DA-95CA-C5AB0DC85B11"  # RFC 6455
_SEND_BUFFER_BYTES = 4 << 20


def _frame_header(opcode: int, length: int) -> bytes:
    if length < 126:
        return struct.pack("!BB", 0x80 | opcode, length)
    if length < 1 << 16:
        return struct.pack("!BBH", 0x80 | opcode, 126, length)
    return struct.pack("!BBQ", 0x80 | opcode, 127, length)


def _text(conn: socket.socket, message: dict[str, object]) -> None:
    data = json.dumps(message).encode()
    conn.sendall(_frame_header(1, len(data)) + data)


def _read_text_frame(conn: socket.socket) -> dict[str, Any]:
    """One masked text frame from the client (its ``subscribe``)."""
    head = conn.recv(2, socket.MSG_WAITALL)
    length = head[1] & 0x7F
    if length == 126:
        (length,) = struct.unpack("!H", conn.recv(2, socket.MSG_WAITALL))
    mask = conn.recv(4, socket.MSG_WAITALL)
    body = conn.recv(length, socket.MSG_WAITALL)
    return dict(json.loads(bytes(b ^ mask[i % 4] for i, b in enumerate(body))))


def _send_all(conn: socket.socket, parts: list[memoryview]) -> None:
    while parts:
        sent = conn.sendmsg(parts)
        while parts and sent >= len(parts[0]):
            sent -= len(parts[0])
            parts.pop(0)
        if parts and sent:
            parts[0] = parts[0][sent:]


def serve(server: socket.socket, payloads: dict[str, bytearray], seconds: float) -> dict[str, int]:
    """Accept the client, advertise the topics, and send each payload at its topic's rate for
    ``seconds``, with the time of sending as its ``header.stamp``."""
    conn, _ = server.accept()
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    conn.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, _SEND_BUFFER_BYTES)
    request = b""
    while b"\r\n\r\n" not in request:
        request += conn.recv(4096)
    key = next(line.split(b":", 1)[1].strip() for line in request.split(b"\r\n")
               if line.lower().startswith(b"sec-websocket-key"))  # fmt: skip
    accept = base64.b64encode(hashlib.sha1(key + _WS_GUID).digest())
    conn.sendall(b"HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\n"
                 b"Connection: Upgrade\r\nSec-WebSocket-Accept: " + accept +
                 b"\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n")  # fmt: skip
    _text(conn, {"op": "serverInfo", "name": "bench_ws_floor", "capabilities": [],
                 "supportedEncodings": [], "metadata": {}, "sessionId": "1"})  # fmt: skip
    channels = [{"id": i + 1, "topic": t, "encoding": "cdr", "schemaName": "", "schema": "",
                 "schemaEncoding": "ros2msg"} for i, t in enumerate(TOPICS)]  # fmt: skip
    _text(conn, {"op": "advertise", "channels": channels})
    subscription_of: dict[str, int] = {}
    while len(subscription_of) < len(TOPICS):
        for sub in _read_text_frame(conn)["subscriptions"]:
            subscription_of[channels[sub["channelId"] - 1]["topic"]] = sub["id"]

    def send(topic: str) -> None:
        payload = payloads[topic]
        stamp_ns = time.monotonic_ns()
        _STAMP.pack_into(payload, 4, stamp_ns // 10**9, stamp_ns % 10**9)
        body = struct.pack("<BIQ", 1, subscription_of[topic], stamp_ns)  # messageData
        head = _frame_header(2, len(body) + len(payload)) + body
        _send_all(conn, [memoryview(head), memoryview(payload)])

    return paced(seconds, send)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    args = parser.parse_args()
    from robomodel.runtime.msg.cdr import serialize

    payloads = {topic: bytearray(serialize(msg)) for topic, msg in messages().items()}
    server = socket.create_server(("127.0.0.1", 0))
    port = server.getsockname()[1]
    load = os.getloadavg()
    env = {**os.environ, "ROBOMODEL_NODE_MODULES": str(NODE_MODULES)}
    client = subprocess.Popen(_node_client(port, args.seconds + 3.0), env=env,
                              stdout=subprocess.PIPE, text=True, cwd=ROOT)  # fmt: skip
    result: dict[str, dict[str, int]] = {}
    sender = threading.Thread(
        target=lambda: result.update(sent=serve(server, payloads, args.seconds))
    )
    sender.start()
    got = json.loads(client.communicate()[0])
    sender.join()
    print(f"a bare WebSocket sender to the node Foxglove client, {args.seconds:g} s (latency "
          f"[ms]); load average before {load[0]:.2f} (1 min), {load[1]:.2f} (5 min)")  # fmt: skip
    print(f"{'topic':<16}{'bytes':>9}{'sent':>7}{'received':>10}{'p50':>9}{'p90':>9}{'min':>8}")
    for topic in TOPICS:
        values = got[topic]
        print(f"{topic:<16}{len(payloads[topic]):>9}{result['sent'][topic]:>7}{len(values):>10}"
              f"{_percentile(values, 50):>9.2f}{_percentile(values, 90):>9.2f}"
              f"{min(values, default=float('nan')):>8.2f}")  # fmt: skip


if __name__ == "__main__":
    main()
