"""Count whole scene updates a viser page would receive, without a browser (bench_viewer).

Run by ``bench_viewer.py --scaling --socket`` in a process of its own: connects to the viewer's
websocket as viser's client does (subprotocol ``viser-v<version>``), skips the first 2 s (the
initial scene), then counts, for ``duration`` seconds, the frames that carry the marker
node's new orientation. Prints updates per second.

Usage: ``_ws_count.py WS_URL MARKER_NODE DURATION_S``
"""

from __future__ import annotations

import sys
import time

import msgspec
import viser
import zstandard
from websockets.sync.client import connect


def main() -> None:
    url, marker, duration_s = sys.argv[1], sys.argv[2], float(sys.argv[3])
    marker_bytes = marker.encode()
    unzip = zstandard.ZstdDecompressor()
    count = 0
    with connect(url, subprotocols=[f"viser-v{viser.__version__}"], max_size=None) as ws:  # type: ignore[list-item]
        start = time.perf_counter() + 2.0
        while (now := time.perf_counter()) < start + duration_s:
            payload = ws.recv()
            # viser's wire format: [u64 raw size][u64 zstd size][zstd msgpack][binary buffers]
            if not isinstance(payload, bytes) or len(payload) < 16 or now < start:
                continue
            size = int.from_bytes(payload[8:16], "little")
            meta = unzip.decompress(payload[16 : 16 + size])
            if marker_bytes not in meta:
                continue
            for message in msgspec.msgpack.decode(meta)["messages"]:
                if message.get("type") == "SetOrientationMessage" and message.get("name") == marker:
                    count += 1
    print(f"{count / duration_s:.2f}")


if __name__ == "__main__":
    main()
